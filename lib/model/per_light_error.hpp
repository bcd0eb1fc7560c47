// The worst per-light errors of a compressed field against its original, the failure mode that
// the Eq. 16 average hides: under concentrated light (a sun) a relit pixel is mostly one light's
// value, so one large per-light error shows undiluted, and undershoot goes below zero. Measured
// in the light basis, over every function or only those inside the mask:
// - the largest |R[p,i] - R~[p,i]| / max_i |R[p,i]| over functions p and lights i (relative to
//   each function's peak, so it does not depend on the field's scale), where it is, and the share
//   of functions whose own largest relative error is above a few levels;
// - how many values R~[p,i] are negative where R[p,i] >= 0, and the most negative one relative
//   to its function's peak.
#pragma once

#include <cstdint>
#include <iterator>
#include <relume/compressed_field.hpp>
#include <relume/field.hpp>
#include <vector>

namespace relume {

// Levels of a function's largest peak-relative error counted in functions_above.
inline constexpr double per_light_error_levels[] = {0.05, 0.1, 0.25};

struct PerLightError {
  double largest = 0;          // max over functions and lights of |R - R~| / peak of R[p,:]
  std::int64_t function = -1;  // where: function p (pixel p / channels, channel p % channels)
  int light = -1;              // and light i; -1 when nothing was measured
  double mean_of_largest = 0;  // mean over functions of each one's largest relative error
  std::vector<double> functions_above;  // share of functions above each per_light_error_levels
  std::int64_t functions_measured = 0;
  std::int64_t zero_peak_skipped = 0;  // functions whose original is all zero (no peak)
  std::int64_t negative_values = 0;    // R~ < 0 where R >= 0
  std::int64_t values_measured = 0;    // lights x functions measured (zero-peak ones included)
  double most_negative = 0;            // min over those of R~ / peak of R[p,:] (<= 0)
};

// The figures of a block of functions, added one function at a time, and the blocks merged in
// order into the result: what per_light_error measures, for a caller that reconstructs each
// function once for several measures (compress/field_errors.hpp).
struct PerLightErrorSum {
  PerLightError error;  // its functions_above left empty: `above` counts them
  std::int64_t above[std::size(per_light_error_levels)] = {};
  // Function p (its index in the field) as stored and as reconstructed, `lights` values each.
  void add(std::int64_t p, const float* exact, const float* rebuilt, int lights);
};
PerLightError per_light_error_of(const std::vector<PerLightErrorSum>& blocks);

// masked_only: only functions whose pixel is inside the compressed field's mask. Throws Error
// unless `original` has the compressed field's shape and lights, for an inconsistent compressed
// field or a negative cap. The result does not depend on `threads` (0 = all cores).
PerLightError per_light_error(const ReflectanceField& original, const CompressedField& compressed,
                              bool masked_only, int residual_cap = all_residual_entries,
                              unsigned threads = 0);

}  // namespace relume
