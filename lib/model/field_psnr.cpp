// Implementation of the 8-bit PSNR of a compressed field against its original.
#include "model/field_psnr.hpp"

#include <algorithm>
#include <cmath>
#include <relume/error.hpp>
#include <vector>

#include "model/compressed_field_checks.hpp"
#include "model/reconstruct_field.hpp"

namespace relume {
namespace {

// round(clamp(value * scale, 0, 255)) without the call to libm's round() that the compiler
// leaves for it (Psnr8Sums::add with that call: 13% of a rate target's CPU samples under perf,
// 8% without): for x >= 0 the fraction x - trunc(x) is exact and round() takes halves up, so
// this is the same value, and trunc() is inlined.
double to_8bit(double value, double scale) {
  const double x = std::clamp(value * scale, 0.0, 255.0);
  const double whole = std::trunc(x);
  return whole + (x - whole >= 0.5 ? 1.0 : 0.0);
}

double psnr_of(const std::vector<double>& squared_error_per_light, double samples) {
  if (samples == 0) return std::numeric_limits<double>::quiet_NaN();
  double mse = 0;
  for (double e : squared_error_per_light) mse += e / samples;
  mse /= double(squared_error_per_light.size());
  if (mse == 0) return std::numeric_limits<double>::infinity();
  return 20 * std::log10(255.0) - 10 * std::log10(mse);
}

}  // namespace

void Psnr8Sums::add(const float* exact, const float* approximate, int lights, double scale,
                    bool in_region) {
  if (all.empty()) {
    all.assign(lights, 0.0);
    inside.assign(lights, 0.0);
  }
  inside_count += in_region;
  for (int i = 0; i < lights; ++i) {
    const double d = to_8bit(exact[i], scale) - to_8bit(approximate[i], scale);
    all[i] += d * d;
    if (in_region) inside[i] += d * d;
  }
}

Psnr8 psnr_of_sums(const std::vector<Psnr8Sums>& blocks, int lights, std::size_t functions) {
  std::vector<double> all_total(lights, 0.0), inside_total(lights, 0.0);
  double inside_samples = 0;
  for (const Psnr8Sums& block : blocks) {
    for (std::size_t i = 0; i < block.all.size(); ++i) {
      all_total[i] += block.all[i];
      inside_total[i] += block.inside[i];
    }
    inside_samples += double(block.inside_count);
  }
  return {psnr_of(all_total, double(functions)), psnr_of(inside_total, inside_samples)};
}

void check_psnr_white(double white) {
  if (!(white > 0) || !std::isfinite(white))
    throw Error("the PSNR white level must be a positive number, got " + std::to_string(white));
}

namespace {

// The PSNR, and with `relative` also the Eq. 16 error over the compressed field's mask (as
// relative_error(original, compressed, true, residual_cap) defines it), from one reconstruction.
Psnr8 measure_psnr(const ReflectanceField& original, const CompressedField& compressed,
                   double white, int residual_cap, bool stored_rows_exact, unsigned threads,
                   const std::vector<std::uint8_t>& mask, RelativeError* relative = nullptr) {
  check_psnr_white(white);
  check_residual_cap(residual_cap);
  validate_compressed_field(compressed, "cannot measure the PSNR of the compressed field");
  if (original.width != compressed.width || original.height != compressed.height ||
      original.channels != compressed.channels || original.lights() != compressed.lights)
    throw Error("cannot measure the PSNR: the original and the compressed field differ in shape");
  const std::vector<std::uint8_t>& inside_mask = mask.empty() ? compressed.mask : mask;
  if (inside_mask.size() != compressed.mask.size())
    throw Error("cannot measure the PSNR inside a mask of " + std::to_string(inside_mask.size()) +
                " pixels: the field has " + std::to_string(compressed.mask.size()));
  const int lights = compressed.lights;
  const double scale = 255.0 / white;
  const std::vector<std::int64_t> row_of = stored_row_of_function(compressed);

  // Per block of functions, per light: squared 8-bit errors over all and over masked functions;
  // summed in block order, so the result does not depend on the thread count.
  constexpr std::size_t block = 4096;
  const std::size_t functions = std::size_t(original.functions());
  std::vector<Psnr8Sums> partial(item_blocks(functions, block));
  std::vector<RelativeError> relative_part(partial.size());
  for_each_item_in_blocks(
      functions, block, lights, threads, [&](std::size_t b, std::size_t p, FunctionScratch& rows) {
        const float* exact = original.values.row(Eigen::Index(p)).data();
        if (stored_rows_exact && row_of[p] >= 0)
          std::copy(exact, exact + lights, rows.approx.begin());
        else
          reconstruct_function(compressed, row_of[p], residual_cap, rows.sum.data(),
                               rows.approx.data());
        const std::size_t pixel = p / std::size_t(compressed.channels);
        partial[b].add(exact, rows.approx.data(), lights, scale, inside_mask[pixel] != 0);
        if (relative && compressed.mask[pixel])
          add_relative_error(relative_part[b], exact, rows.approx.data(), lights);
      });
  if (relative) *relative = average_of(relative_part);
  return psnr_of_sums(partial, lights, functions);
}

}  // namespace

Psnr8 psnr_8bit(const ReflectanceField& original, const CompressedField& compressed, double white,
                int residual_cap, unsigned threads, const std::vector<std::uint8_t>& mask) {
  return measure_psnr(original, compressed, white, residual_cap, false, threads, mask);
}

PsnrAndError psnr_8bit_and_error(const ReflectanceField& original,
                                 const CompressedField& compressed, double white, int residual_cap,
                                 unsigned threads, const std::vector<std::uint8_t>& mask) {
  PsnrAndError result;
  result.psnr =
      measure_psnr(original, compressed, white, residual_cap, false, threads, mask, &result.error);
  return result;
}

Psnr8 psnr_8bit_of_unstored(const ReflectanceField& original, const CompressedField& compressed,
                            double white, unsigned threads, const std::vector<std::uint8_t>& mask) {
  return measure_psnr(original, compressed, white, all_residual_entries, true, threads, mask);
}

}  // namespace relume
