// PSNR on the 8-bit scale, the way RTI tools quote quality (GUIDE section 3b): every light's image
// of the original and of the reconstruction is taken to 8 bits (value / white x 255, clipped to
// [0, 255], rounded), its mean squared error over pixels and channels is averaged over the
// lights, and PSNR = 20 log10(255) - 10 log10(mean MSE). Over the whole frame and inside the
// mask. Unlike the paper's relative Eq. 16 error, a noisy dark pixel weighs what its few levels
// of error weigh.
#pragma once

#include <limits>
#include <relume/compressed_field.hpp>
#include <relume/field.hpp>

namespace relume {

struct Psnr8 {
  // dB; +infinity where the 8-bit images are identical; NaN inside an empty mask.
  double whole_frame = 0;
  double masked = 0;
};

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
