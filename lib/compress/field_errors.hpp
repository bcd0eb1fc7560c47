// The errors a compression report gives of a compressed field against its original: the paper's
// Eq. 16 over all functions and over the masked ones (also at shorter residual prefixes), the
// per-light error relative to each function's peak and the 8-bit PSNR. Measured on a whole field
// in memory, or strip by strip for a field larger than memory and merged into the same figures.
#pragma once

#include <cstdint>
#include <relume/compressed_field.hpp>
#include <relume/field.hpp>
#include <utility>
#include <vector>

#include "model/field_psnr.hpp"
#include "model/per_light_error.hpp"

namespace relume {

struct FieldErrors {
  RelativeError all, masked;
  // The masked error with each row's residual cut to a prefix (the report's caps below the
  // residual entries kept), in ascending cap order.
  std::vector<std::pair<int, RelativeError>> masked_by_prefix;
  PerLightError per_light;  // masked functions
  Psnr8 psnr;
  // Pixels in the PSNR's two regions (the whole frame, the mask), to merge strips by.
  std::int64_t psnr_pixels = 0, psnr_mask_pixels = 0;
};

// Measures `compressed` against `original`. `residual_entries`: the residual kept per function
// (prefix caps below it are measured too); `white` and `psnr_mask` as psnr_8bit takes them.
FieldErrors measure_field_errors(const ReflectanceField& original,
                                 const CompressedField& compressed, int residual_entries,
                                 double white, const std::vector<std::uint8_t>& psnr_mask,
                                 unsigned threads);

// Adds the Eq. 16 error of other functions to `total`: the mean over both sets.
void merge_relative_errors(RelativeError& total, const RelativeError& part);

// Adds the errors of a strip measured on its own (its function p being the field's
// first_function + p) to `total`, the errors of the strips above it: the result is what
// measuring the stacked strips at once gives (up to rounding).
void merge_field_errors(FieldErrors& total, const FieldErrors& strip, std::int64_t first_function);

}  // namespace relume
