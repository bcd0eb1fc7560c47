// Implementation of the worst per-light errors (see per_light_error.hpp).
#include "model/per_light_error.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "model/compressed_field_checks.hpp"
#include "model/reconstruct_field.hpp"

namespace relume {
namespace {

constexpr std::size_t levels = std::size(per_light_error_levels);

}  // namespace

void PerLightErrorSum::add(std::int64_t p, const float* exact, const float* rebuilt, int lights) {
  double peak = 0, largest = 0;
  int largest_light = 0;
  for (int i = 0; i < lights; ++i) peak = std::max(peak, std::abs(double(exact[i])));
  error.values_measured += lights;
  for (int i = 0; i < lights; ++i) {
    const double difference = std::abs(double(exact[i]) - rebuilt[i]);
    if (difference > largest) {
      largest = difference;
      largest_light = i;
    }
    if (exact[i] >= 0 && rebuilt[i] < 0) {
      ++error.negative_values;
      if (peak > 0) error.most_negative = std::min(error.most_negative, rebuilt[i] / peak);
    }
  }
  if (peak == 0) {
    ++error.zero_peak_skipped;
    return;
  }
  const double relative = largest / peak;
  ++error.functions_measured;
  error.mean_of_largest += relative;
  for (std::size_t level = 0; level < levels; ++level)
    above[level] += relative > per_light_error_levels[level];
  if (relative > error.largest) {
    error.largest = relative;
    error.function = p;
    error.light = largest_light;
  }
}

PerLightError per_light_error_of(const std::vector<PerLightErrorSum>& blocks) {
  PerLightError total;
  std::int64_t above[levels] = {};
  for (const PerLightErrorSum& part : blocks) {  // in block order: ties keep the first function
    const PerLightError& e = part.error;
    if (e.largest > total.largest) {
      total.largest = e.largest;
      total.function = e.function;
      total.light = e.light;
    }
    total.mean_of_largest += e.mean_of_largest;
    total.functions_measured += e.functions_measured;
    total.zero_peak_skipped += e.zero_peak_skipped;
    total.negative_values += e.negative_values;
    total.values_measured += e.values_measured;
    total.most_negative = std::min(total.most_negative, e.most_negative);
    for (std::size_t level = 0; level < levels; ++level) above[level] += part.above[level];
  }
  const double measured = double(std::max<std::int64_t>(total.functions_measured, 1));
  total.mean_of_largest /= measured;
  for (std::size_t level = 0; level < levels; ++level)
    total.functions_above.push_back(double(above[level]) / measured);
  return total;
}

PerLightError per_light_error(const ReflectanceField& original, const CompressedField& compressed,
                              bool masked_only, int residual_cap, unsigned threads) {
  validate_compressed_field(compressed, "cannot measure the per-light error of the field");
  check_original_matches(original, compressed, residual_cap);
  const int lights = compressed.lights;
  const std::vector<std::int64_t> row_of = stored_row_of_function(compressed);
  constexpr std::size_t block = 1024;
  const std::size_t functions = std::size_t(original.functions());
  std::vector<PerLightErrorSum> partial(item_blocks(functions, block));
  for_each_item_in_blocks(
      functions, block, lights, threads, [&](std::size_t b, std::size_t p, FunctionScratch& rows) {
        if (masked_only && !compressed.mask[p / compressed.channels]) return;
        reconstruct_function(compressed, row_of[p], residual_cap, rows.sum.data(),
                             rows.approx.data());
        partial[b].add(std::int64_t(p), original.values.row(Eigen::Index(p)).data(),
                       rows.approx.data(), lights);
      });
  return per_light_error_of(partial);
}

}  // namespace relume
