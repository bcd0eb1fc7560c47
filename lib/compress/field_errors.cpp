// Implementation of the report's error measures and their merging over strips
// (see field_errors.hpp).
#include "compress/field_errors.hpp"

#include <cmath>
#include <relume/error.hpp>
#include <string>

#include "model/compressed_field_checks.hpp"
#include "model/reconstruct_field.hpp"

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
  validate_compressed_field(compressed, "cannot measure the errors of the compressed field");
  check_original_matches(original, compressed, all_residual_entries);
  check_psnr_white(white);
  const std::vector<std::uint8_t>& region = psnr_mask.empty() ? compressed.mask : psnr_mask;
  if (region.size() != compressed.mask.size())
    throw Error("cannot measure the PSNR inside a mask of " + std::to_string(region.size()) +
                " pixels: the field has " + std::to_string(compressed.mask.size()));
  std::vector<int> caps;  // the prefixes measured: those below the entries kept
  for (const int cap : prefix_caps)
    if (cap < residual_entries) caps.push_back(cap);
  const int lights = compressed.lights;
  const double scale = 255.0 / white;
  const std::vector<std::int64_t> row_of = stored_row_of_function(compressed);

  // One reconstruction of each function serves every measure (and one more per prefix cap, for
  // masked functions); blocks of functions summed in order, so the result does not depend on the
  // thread count.
  struct Block {
    RelativeError all, masked;
    std::vector<RelativeError> by_prefix;
    PerLightErrorSum per_light;
    Psnr8Sums psnr;
  };
  constexpr std::size_t block = 1024;
  const std::size_t functions = std::size_t(original.functions());
  const std::size_t blocks = item_blocks(functions, block);
  std::vector<Block> parts(blocks);
  for (Block& part : parts) part.by_prefix.resize(caps.size());
  for_each_item_in_blocks(
      functions, block, lights, threads, [&](std::size_t b, std::size_t p, FunctionScratch& rows) {
        Block& part = parts[b];
        const float* exact = original.values.row(Eigen::Index(p)).data();
        const float* approximate = rows.approx.data();
        reconstruct_function(compressed, row_of[p], all_residual_entries, rows.sum.data(),
                             rows.approx.data());
        const std::size_t pixel = p / std::size_t(compressed.channels);
        add_relative_error(part.all, exact, approximate, lights);
        part.psnr.add(exact, approximate, lights, scale, region[pixel] != 0);
        if (!compressed.mask[pixel]) return;
        add_relative_error(part.masked, exact, approximate, lights);
        part.per_light.add(std::int64_t(p), exact, approximate, lights);
        for (std::size_t k = 0; k < caps.size(); ++k) {
          reconstruct_function(compressed, row_of[p], caps[k], rows.sum.data(), rows.second.data());
          add_relative_error(part.by_prefix[k], exact, rows.second.data(), lights);
        }
      });
  FieldErrors errors;
  std::vector<RelativeError> all(blocks), masked(blocks);
  std::vector<PerLightErrorSum> per_light(blocks);
  std::vector<Psnr8Sums> psnr(blocks);
  for (std::size_t b = 0; b < blocks; ++b) {
    all[b] = parts[b].all;
    masked[b] = parts[b].masked;
    per_light[b] = std::move(parts[b].per_light);
    psnr[b] = std::move(parts[b].psnr);
  }
  errors.all = average_of(all);
  errors.masked = average_of(masked);
  for (std::size_t k = 0; k < caps.size(); ++k) {
    std::vector<RelativeError> cut(blocks);
    for (std::size_t b = 0; b < blocks; ++b) cut[b] = parts[b].by_prefix[k];
    errors.masked_by_prefix.emplace_back(caps[k], average_of(cut));
  }
  errors.per_light = per_light_error_of(per_light);
  errors.psnr = psnr_of_sums(psnr, lights, functions);
  errors.psnr_pixels = original.pixels();
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
