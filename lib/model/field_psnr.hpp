// PSNR on the 8-bit scale, the way RTI tools quote quality (GUIDE section 3b): every light's image
// of the original and of the reconstruction is taken to 8 bits (value / white x 255, clipped to
// [0, 255], rounded), its mean squared error over pixels and channels is averaged over the
// lights, and PSNR = 20 log10(255) - 10 log10(mean MSE). Over the whole frame and inside the
// mask. Unlike the paper's relative Eq. 16 error, a noisy dark pixel weighs what its few levels
// of error weigh.
#pragma once

#include <cstddef>
#include <limits>
#include <relume/compressed_field.hpp>
#include <relume/field.hpp>
#include <vector>

namespace relume {

struct Psnr8 {
  // dB; +infinity where the 8-bit images are identical; NaN inside an empty mask.
  double whole_frame = 0;
  double masked = 0;
};

// The squared 8-bit errors per light of a block of functions, added one function at a time, and
// the blocks merged in order into the PSNR: what psnr_8bit measures, for a caller that
// reconstructs each function once for several measures (compress/field_errors.hpp).
struct Psnr8Sums {
  std::vector<double> all, inside;  // per light: over every function, over those in the region
  std::size_t inside_count = 0;     // functions in the region
  // One function as stored and as reconstructed; `scale` = 255 / white.
  void add(const float* exact, const float* approximate, int lights, double scale,
           bool in_region);
};
// `functions`: all the blocks' functions.
Psnr8 psnr_of_sums(const std::vector<Psnr8Sums>& blocks, int lights, std::size_t functions);

// Throws Error unless `white` is a positive finite number.
void check_psnr_white(double white);

// `white`: the field value that maps to 255 (1 for fields of 8-bit or normalised images).
// `mask`: width x height, non-zero inside, for the masked figure; empty: the compressed field's
// mask. Throws Error for fields of different shapes, a mask of another size, a negative cap or a
// white level that is not positive.
Psnr8 psnr_8bit(const ReflectanceField& original, const CompressedField& compressed,
                double white = 1.0, int residual_cap = all_residual_entries, unsigned threads = 0,
                const std::vector<std::uint8_t>& mask = {});

// psnr_8bit and the Eq. 16 error over the compressed field's mask (relative_error(original,
// compressed, true, residual_cap)) from one reconstruction of every function: a rate search
// measures every point it tries both ways. The same checks and errors as psnr_8bit.
struct PsnrAndError {
  Psnr8 psnr;
  RelativeError error;
};
PsnrAndError psnr_8bit_and_error(const ReflectanceField& original,
                                 const CompressedField& compressed, double white = 1.0,
                                 int residual_cap = all_residual_entries, unsigned threads = 0,
                                 const std::vector<std::uint8_t>& mask = {});

// The same with every stored row taken as exact (its residual included): the error of what the
// field does not store row by row (dark pixels, all-zero functions), the most PSNR that any model
// with the field's dark pixels reaches.
Psnr8 psnr_8bit_of_unstored(const ReflectanceField& original, const CompressedField& compressed,
                            double white = 1.0, unsigned threads = 0,
                            const std::vector<std::uint8_t>& mask = {});

}  // namespace relume
