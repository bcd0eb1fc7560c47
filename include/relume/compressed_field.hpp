// relume/compressed_field.hpp: a reflectance field compressed by clustered sparse residual
// factorization (paper Eq. 2):
//   R[p,:] ~ W[p,:] * F^{c(p)} + E[p,:]
// Only the functions that a scene needs are stored ("stored rows"): functions outside the mask and
// all-zero functions have no row and relight to zero, and pixels at the noise level ("dark
// pixels") are multiples of one dark model per channel. This is what the container file holds
// and what the relighting kernels read.
//
// reconstruct_field expands it back into a ReflectanceField; relative_error is the paper's error
// measure (Eq. 16) between an original field and its compressed form.
#pragma once

#include <algorithm>
#include <cstdint>
#include <limits>
#include <relume/field.hpp>
#include <vector>

namespace relume {

// Basis in which rows of F and the residual are expressed (paper Eq. 3). The relighter transforms
// the light vector the same way before use.
enum class BasisTransform : std::uint8_t { identity = 0, haar = 1 };

// Sparse residual rows in CSR form. Each row's entries are sorted by |value| descending, so every
// prefix of a row is the best residual of that length (the dynamic residual of paper section 4).
struct ResidualRows {
  std::vector<std::uint32_t> row_offsets;  // stored_rows + 1
  std::vector<std::uint32_t> light_index;  // nnz
  std::vector<float> values;               // nnz

  std::size_t rows() const { return row_offsets.empty() ? 0 : row_offsets.size() - 1; }
  std::size_t nonzeros() const { return values.size(); }
  std::uint32_t length(std::size_t row) const { return row_offsets[row + 1] - row_offsets[row]; }
  std::uint32_t longest_row() const {
    std::uint32_t longest = 0;
    for (std::size_t r = 0; r < rows(); ++r) longest = std::max(longest, length(r));
    return longest;
  }
};

// How a compressed field's values are stored (in the container and in the relighting kernels'
// memory). The floats of W, F and E are always exactly the values they stand for; these say that
// they are integers times a step, which is how they are stored. All zero / empty: float values.
struct ValueQuantization {
  float weight_step = 0;    // every weight is an integer in [-32767, 32767] times this
  float residual_step = 0;  // every residual value is an integer in [-32767, 32767] times this
  int basis_bits = 0;       // 8..16: basis row (k, j) is integers of this many bits times
  std::vector<float> basis_scales;  // basis_scales[k * terms + j]

  bool any() const { return weight_step > 0 || residual_step > 0 || basis_bits > 0; }
};

// W coded in the camera domain (container section 'weight_planes', docs/container.md): when
// `codestream` is not empty it is a JPEG 2000 codestream of channels x terms planes of 16-bit
// integers (lib/model/weight_planes.hpp says which plane is which), and W is exactly what it
// decodes to, times `step`, taken back from the colour transform to the channels.
struct CodedWeights {
  std::vector<std::uint8_t> codestream;
  float step = 0;
  // Three channels: each term's colour transform as three rotation angles (weight_planes.hpp);
  // empty: one fixed transform for every term (containers before version 6).
  std::vector<std::int16_t> colour_angles;

  bool empty() const { return codestream.empty(); }
};

struct CompressedField {
  int width = 0;
  int height = 0;
  int channels = 0;
  int lights = 0;    // m
  int terms = 0;     // t, basis functions per cluster
  int clusters = 0;  // K
  BasisTransform transform = BasisTransform::identity;
  std::vector<std::uint8_t> mask;  // width * height
  LightDirections directions;      // lights x 3
  LightRgb intensities;            // lights x 3

  std::vector<std::uint32_t> stored_function;  // stored row -> function index p, ascending
  std::vector<std::uint32_t> cluster;          // stored row -> cluster id in [0, clusters)
  RowMatrixF weights;                          // stored rows x terms (W)
  std::vector<float> bases;  // clusters * terms * lights: F^k[j][i] at (k * terms + j) * lights + i
  ResidualRows residual;     // stored rows, in the transformed basis
  ValueQuantization quantization;
  CodedWeights coded_weights;  // empty: W is stored as its values
  // The dark model: pixels whose functions are, within the noise, multiples of one shared
  // function per channel, dark[c * lights + i] (in the transformed basis), have no stored rows:
  // dark pixel d relights in channel c as dark_gains[d * channels + c] x that function. The
  // container stores the gains once per dark_gain_block x dark_gain_block block of pixels,
  // quantized with step dark_gain_step, so every dark pixel of a block has the same gain.
  // Empty gains: every gain is 1 (containers before version 4, where dark was the dark pixels'
  // mean).
  std::vector<std::uint32_t> dark_pixels;  // ascending pixel indices, inside the mask
  std::vector<float> dark;                 // channels x lights, empty when no pixel is dark
  std::vector<float> dark_gains;           // dark pixels x channels, or empty
  float dark_gain_step = 0;                // > 0 when there are gains
  // The field it was compressed from had no negative value (every capture does): a relit image
  // under a non-negative light vector is then non-negative too, and Relighter projects the
  // compressed field's undershoot below zero back to 0 (RelighterOptions::allow_negative).
  bool non_negative = false;

  std::size_t stored_rows() const { return stored_function.size(); }
  std::int64_t functions() const { return std::int64_t(width) * height * channels; }
  const float* basis(int k) const { return bases.data() + std::size_t(k) * terms * lights; }
};

// residual_cap: at most this many entries of each residual row are kept (its largest ones, since
// rows are sorted by |value| descending); a cap at or above a row's length keeps the whole row.
// Every function that takes a cap (reconstruction, the error measures, relighting) accepts
// all_residual_entries for "every entry" and refuses a negative cap.
inline constexpr int all_residual_entries = std::numeric_limits<int>::max();

// The side of the square pixel blocks that share one dark gain per channel in the container.
inline constexpr int dark_gain_block = 8;

// The gain of dark pixel number `d` (its index in dark_pixels) in channel c: 1 without gains.
inline float dark_gain(const CompressedField& field, std::size_t d, int c) {
  return field.dark_gains.empty()
             ? 1.0f
             : field.dark_gains[d * std::size_t(field.channels) + std::size_t(c)];
}

// The whole field in the original (light) basis: stored rows reconstructed, dark pixels as the
// dark model and, for a Haar-stored field, transformed back; other functions are zero. Mask,
// directions and intensities are copied; image_names are left empty (write_field_folder names the
// images). Throws Error for an inconsistent field (validate_compressed_field) or a negative cap.
ReflectanceField reconstruct_field(const CompressedField& field,
                                   int residual_cap = all_residual_entries);

// Paper Eq. 16: err = (1/n) sum_p ( sum_i (R[p,i] - R~[p,i])^2 / sum_i R[p,i]^2 ).
// Functions whose original energy sum_i R[p,i]^2 is zero have no defined relative error: they are
// left out of the average (n counts only the others) and counted in zero_energy_skipped.
struct RelativeError {
  double mean = 0;                       // the average above; 0 when nothing was averaged
  std::int64_t functions_averaged = 0;   // n
  std::int64_t zero_energy_skipped = 0;  // functions left out for having zero energy
};

// masked_only: average only over functions whose pixel is inside the compressed field's mask.
// Throws Error unless `original` has the compressed field's size, channels and lights, or for an
// inconsistent compressed field or a negative cap. Accumulates in double, in fixed blocks, so
// the result does not depend on `threads` (0 = all cores).
RelativeError relative_error(const ReflectanceField& original, const CompressedField& compressed,
                             bool masked_only, int residual_cap = all_residual_entries,
                             unsigned threads = 0);

// Eq. 16 of `approximation` against `reference`, two compressions of the same field (or one with
// itself at a shorter residual), over the functions `reference` stores (each with its full
// residual; functions `approximation` does not store count as zero), compared in the light basis.
// `approximation_cap`: residual entries per row of `approximation` (all_residual_entries: all).
RelativeError relative_error(const CompressedField& reference, const CompressedField& approximation,
                             int approximation_cap = all_residual_entries, unsigned threads = 0);

}  // namespace relume
