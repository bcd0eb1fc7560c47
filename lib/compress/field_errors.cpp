// Implementation of the report's error measures and their merging over strips
// (see field_errors.hpp).
#include "compress/field_errors.hpp"

#include <cmath>

namespace relume {
namespace {

constexpr int prefix_caps[] = {0, 1, 3, 5, 10, 20};

}  // namespace

void merge_relative_errors(RelativeError& total, const RelativeError& part) {
  const std::int64_t n = total.functions_averaged + part.functions_averaged;
  if (n > 0)
    total.mean = (total.mean * double(total.functions_averaged) +
                  part.mean * double(part.functions_averaged)) /
                 double(n);
  total.functions_averaged = n;
  total.zero_energy_skipped += part.zero_energy_skipped;
}

namespace {

void merge(PerLightError& total, const PerLightError& part, std::int64_t first_function) {
  if (part.function >= 0 && (total.function < 0 || part.largest > total.largest)) {
    total.largest = part.largest;
    total.function = first_function + part.function;
    total.light = part.light;
  }
  const std::int64_t n = total.functions_measured + part.functions_measured;
  if (total.functions_above.empty()) total.functions_above = part.functions_above;
  if (n > 0) {
    const double a = double(total.functions_measured) / double(n);
    const double b = double(part.functions_measured) / double(n);
    total.mean_of_largest = a * total.mean_of_largest + b * part.mean_of_largest;
    for (std::size_t level = 0; level < total.functions_above.size(); ++level)
      total.functions_above[level] =
          a * total.functions_above[level] + b * part.functions_above[level];
  }
  total.functions_measured = n;
  total.zero_peak_skipped += part.zero_peak_skipped;
  total.negative_values += part.negative_values;
  total.values_measured += part.values_measured;
  total.most_negative = std::min(total.most_negative, part.most_negative);
}

// The mean squared 8-bit error behind a PSNR (0 for identical images).
double mean_squared_error(double psnr) { return 255.0 * 255.0 * std::pow(10.0, -psnr / 10.0); }

// Merges one PSNR region: NaN for an empty region, +infinity for no error.
double merge_psnr(double total, std::int64_t total_pixels, double part, std::int64_t part_pixels) {
  if (part_pixels == 0) return total;
  if (total_pixels == 0) return part;
  const double mse = (mean_squared_error(total) * double(total_pixels) +
                      mean_squared_error(part) * double(part_pixels)) /
                     double(total_pixels + part_pixels);
  return 20.0 * std::log10(255.0) - 10.0 * std::log10(mse);
}

}  // namespace

FieldErrors measure_field_errors(const ReflectanceField& original,
                                 const CompressedField& compressed, int residual_entries,
                                 double white, const std::vector<std::uint8_t>& psnr_mask,
                                 unsigned threads) {
  FieldErrors errors;
  errors.all = relative_error(original, compressed, false, all_residual_entries, threads);
  errors.masked = relative_error(original, compressed, true, all_residual_entries, threads);
  for (const int cap : prefix_caps) {
    if (cap >= residual_entries) break;
    errors.masked_by_prefix.emplace_back(cap,
                                         relative_error(original, compressed, true, cap, threads));
  }
  errors.per_light = per_light_error(original, compressed, true, all_residual_entries, threads);
  errors.psnr = psnr_8bit(original, compressed, white, all_residual_entries, threads, psnr_mask);
  errors.psnr_pixels = original.pixels();
  const std::vector<std::uint8_t>& region = psnr_mask.empty() ? compressed.mask : psnr_mask;
  for (const std::uint8_t inside : region) errors.psnr_mask_pixels += inside != 0;
  return errors;
}

void merge_field_errors(FieldErrors& total, const FieldErrors& strip, std::int64_t first_function) {
  merge_relative_errors(total.all, strip.all);
  merge_relative_errors(total.masked, strip.masked);
  if (total.masked_by_prefix.empty()) {
    total.masked_by_prefix = strip.masked_by_prefix;
  } else if (!strip.masked_by_prefix.empty()) {  // empty: nothing was measured
    for (std::size_t i = 0; i < total.masked_by_prefix.size(); ++i)
      merge_relative_errors(total.masked_by_prefix[i].second, strip.masked_by_prefix[i].second);
  }
  merge(total.per_light, strip.per_light, first_function);
  total.psnr.whole_frame = merge_psnr(total.psnr.whole_frame, total.psnr_pixels,
                                      strip.psnr.whole_frame, strip.psnr_pixels);
  total.psnr.masked = merge_psnr(total.psnr.masked, total.psnr_mask_pixels, strip.psnr.masked,
                                 strip.psnr_mask_pixels);
  total.psnr_pixels += strip.psnr_pixels;
  total.psnr_mask_pixels += strip.psnr_mask_pixels;
}

}  // namespace relume
