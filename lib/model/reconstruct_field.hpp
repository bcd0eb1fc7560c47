// Reconstruction of one stored row of a compressed field, R~[p,:] = W[p,:] F^{c(p)} + E[p,:] (with
// the residual cut to its first `residual_cap` entries: the dynamic residual). The whole-field
// reconstruction and the error measure are declared in relume/compressed_field.hpp.
#pragma once

#include <algorithm>
#include <cstdint>
#include <relume/compressed_field.hpp>
#include <vector>

#include "core/parallel.hpp"

namespace relume {

// Stored row `row` of `field` in the basis the field is stored in (before any inverse transform):
// out[i] = sum_j W[row,j] F^{c(row)}[j][i] + sum_{k < cap} E values at their lights. Accumulates
// in double. `out` holds field.lights floats. Throws Error for a row out of range; the field itself
// is trusted (validated fields only).
void reconstruct_stored_row(const CompressedField& field, std::size_t row, int residual_cap,
                            float* out);

// How stored_row_of_function marks a function without a stored row: -1 when it relights to zero,
// dark_model_row(d, channels, c) when it is channel c of dark pixel number d (its index in
// dark_pixels) and relights as that pixel's gain times the dark model of channel c.
inline constexpr std::int64_t unstored_row = -1;
constexpr std::int64_t dark_model_row(std::size_t dark_index, int channels, int channel) {
  return -2 - (std::int64_t(dark_index) * channels + channel);
}

// Function p's reconstruction in the light basis into `out` (field.lights floats), given what
// stored_row_of_function says of it; `sum` is scratch of field.lights doubles. The field is
// trusted (validated fields only).
void reconstruct_function(const CompressedField& field, std::int64_t stored_row, int residual_cap,
                          double* sum, float* out);

// Adds one function's Eq. 16 term |exact - approx|^2 / |exact|^2 (lights values each, summed in
// double) to sum.mean and counts it, or counts it as skipped when its energy is zero.
void add_relative_error(RelativeError& sum, const float* exact, const float* approx, int lights);

// The Eq. 16 error of add_relative_error's sums (of blocks of functions, added in order): their
// terms over their count.
RelativeError average_of(const std::vector<RelativeError>& sums);

// Stored row of every function, or unstored_row / dark_model_row(...) where it has none.
std::vector<std::int64_t> stored_row_of_function(const CompressedField& field);

// Per-worker buffers for comparing one function at a time: `sum` is reconstruct_function's
// scratch, `exact` and `approx` (and `second`, for another reconstruction of the same function)
// hold lights values each.
struct FunctionScratch {
  explicit FunctionScratch(int lights)
      : sum(lights), exact(lights), approx(lights), second(lights) {}
  std::vector<double> sum;
  std::vector<float> exact, approx, second;
};

// How many blocks of `block` items for_each_item_in_blocks makes of `count` items.
constexpr std::size_t item_blocks(std::size_t count, std::size_t block) {
  return (count + block - 1) / block;
}

// Calls visit(b, item, scratch) for every item in [0, count), in blocks of `block` items (block b
// holds items b * block onwards) spread over the threads, each block's items in order and with
// its worker's scratch: sums kept per block and added in block order do not depend on the
// thread count.
template <class Visit>
void for_each_item_in_blocks(std::size_t count, std::size_t block, int lights, unsigned threads,
                             Visit visit) {
  std::vector<FunctionScratch> scratch(resolve_thread_count(threads), FunctionScratch(lights));
  parallel_for(item_blocks(count, block), threads, [&](std::size_t b, unsigned worker) {
    for (std::size_t item = b * block; item < std::min(count, (b + 1) * block); ++item)
      visit(b, item, scratch[worker]);
  });
}

// Throws Error for a negative residual cap (all_residual_entries keeps every entry).
void check_residual_cap(int residual_cap);

// What every measure of `compressed` against its `original` checks first: throws Error unless
// the two have the same size, channels and lights (naming both shapes), or for a negative
// residual cap.
void check_original_matches(const ReflectanceField& original, const CompressedField& compressed,
                            int residual_cap);

}  // namespace relume
