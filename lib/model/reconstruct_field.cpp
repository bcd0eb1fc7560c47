// Implementation of field reconstruction and the Eq. 16 error (see reconstruct_field.hpp).
#include "model/reconstruct_field.hpp"

#include <algorithm>
#include <relume/error.hpp>
#include <string>
#include <vector>

#include "core/parallel.hpp"
#include "model/compressed_field_checks.hpp"
#include "model/haar_transform.hpp"

namespace relume {

void check_residual_cap(int residual_cap) {
  if (residual_cap < 0)
    throw Error("residual cap " + std::to_string(residual_cap) +
                " is invalid: expected a count of entries >= 0 (all_residual_entries: all)");
}

namespace {

// sum[i] = (W[row,:] F^{c(row)})[i] + the row's first `residual_cap` residual entries, in double.
// Built also for AVX2 on x86-64 (chosen at run time where the CPU has it): four doubles a step
// instead of two, the same sums in the same order (no FMA), so the same values on every machine.
#if defined(__x86_64__) && defined(__GNUC__)
__attribute__((target_clones("avx2", "default")))
#endif
void accumulate_stored_row(const CompressedField& field, std::size_t row, int residual_cap,
                           double* sum) {
  const int lights = field.lights;
  std::fill(sum, sum + lights, 0.0);
  const float* basis = field.basis(static_cast<int>(field.cluster[row]));
  for (int j = 0; j < field.terms; ++j) {
    const double w = field.weights(static_cast<Eigen::Index>(row), j);
    const float* f = basis + std::size_t(j) * lights;
    for (int i = 0; i < lights; ++i) sum[i] += w * f[i];
  }
  const std::uint32_t begin = field.residual.row_offsets[row];
  const std::uint32_t length = field.residual.row_offsets[row + 1] - begin;
  const std::uint32_t kept = std::min<std::uint32_t>(length, residual_cap);
  for (std::uint32_t k = begin; k < begin + kept; ++k)
    sum[field.residual.light_index[k]] += field.residual.values[k];
}

// Eq. 16 over items [0, count): fill(item, scratch) puts the exact and approximate rows in
// scratch.exact / scratch.approx and returns false to leave the item out entirely. Items are
// summed in fixed blocks in order, so the result does not depend on the thread count.
template <class Fill>
RelativeError average_relative_error(std::size_t count, int lights, unsigned threads, Fill fill) {
  constexpr std::size_t block = 1024;
  std::vector<RelativeError> partial(item_blocks(count, block));
  for_each_item_in_blocks(
      count, block, lights, threads, [&](std::size_t b, std::size_t item, FunctionScratch& rows) {
        if (fill(item, rows))
          add_relative_error(partial[b], rows.exact.data(), rows.approx.data(), lights);
      });
  return average_of(partial);
}

std::string shape_text(int width, int height, int channels, int lights) {
  return std::to_string(width) + "x" + std::to_string(height) + "x" + std::to_string(channels) +
         " with " + std::to_string(lights) + " lights";
}

}  // namespace

void add_relative_error(RelativeError& sum, const float* exact, const float* approx, int lights) {
  double energy = 0, error = 0;
  for (int i = 0; i < lights; ++i) {
    const double value = exact[i];
    energy += value * value;
    error += (value - approx[i]) * (value - approx[i]);
  }
  if (energy == 0) {
    ++sum.zero_energy_skipped;
    return;
  }
  sum.mean += error / energy;
  ++sum.functions_averaged;
}

RelativeError average_of(const std::vector<RelativeError>& sums) {
  RelativeError total;
  for (const RelativeError& part : sums) {
    total.mean += part.mean;
    total.functions_averaged += part.functions_averaged;
    total.zero_energy_skipped += part.zero_energy_skipped;
  }
  if (total.functions_averaged > 0) total.mean /= double(total.functions_averaged);
  return total;
}

void reconstruct_function(const CompressedField& field, std::int64_t stored_row, int residual_cap,
                          double* sum, float* out) {
  if (stored_row == unstored_row) {
    std::fill(out, out + field.lights, 0.0f);
    return;
  }
  if (stored_row < 0) {  // dark_model_row(d, channels, c)
    const std::size_t code = std::size_t(-2 - stored_row);
    const int c = int(code % std::size_t(field.channels));
    const float gain = dark_gain(field, code / std::size_t(field.channels), c);
    const float* dark = field.dark.data() + std::size_t(c) * field.lights;
    for (int i = 0; i < field.lights; ++i) out[i] = gain * dark[i];
  } else {
    accumulate_stored_row(field, std::size_t(stored_row), residual_cap, sum);
    std::copy(sum, sum + field.lights, out);
  }
  if (field.transform == BasisTransform::haar) haar_inverse(out, field.lights, 1);
}

std::vector<std::int64_t> stored_row_of_function(const CompressedField& field) {
  std::vector<std::int64_t> row_of(static_cast<std::size_t>(field.functions()), unstored_row);
  for (std::size_t r = 0; r < field.stored_rows(); ++r)
    row_of[field.stored_function[r]] = std::int64_t(r);
  for (std::size_t d = 0; d < field.dark_pixels.size(); ++d)
    for (int c = 0; c < field.channels; ++c)
      row_of[std::size_t(field.dark_pixels[d]) * field.channels + c] =
          dark_model_row(d, field.channels, c);
  return row_of;
}

void reconstruct_stored_row(const CompressedField& field, std::size_t row, int residual_cap,
                            float* out) {
  check_residual_cap(residual_cap);
  if (row >= field.stored_rows())
    throw Error("stored row " + std::to_string(row) + " is out of range: the field stores " +
                std::to_string(field.stored_rows()) + " rows");
  std::vector<double> sum(field.lights);
  accumulate_stored_row(field, row, residual_cap, sum.data());
  std::copy(sum.begin(), sum.end(), out);
}

ReflectanceField reconstruct_field(const CompressedField& field, int residual_cap) {
  check_residual_cap(residual_cap);
  validate_compressed_field(field, "cannot reconstruct the compressed field");
  ReflectanceField result;
  result.width = field.width;
  result.height = field.height;
  result.channels = field.channels;
  result.values = RowMatrixF::Zero(field.functions(), field.lights);
  result.mask = field.mask;
  result.directions = field.directions;
  result.intensities = field.intensities;
  std::vector<std::vector<double>> scratch(resolve_thread_count(0),
                                           std::vector<double>(field.lights));
  parallel_for(field.stored_rows(), 0, [&](std::size_t r, unsigned worker) {
    reconstruct_function(field, std::int64_t(r), residual_cap, scratch[worker].data(),
                         result.values.row(field.stored_function[r]).data());
  });
  for (std::size_t d = 0; d < field.dark_pixels.size(); ++d)
    for (int c = 0; c < field.channels; ++c)
      reconstruct_function(
          field, dark_model_row(d, field.channels, c), residual_cap, nullptr,
          result.values.row(Eigen::Index(field.dark_pixels[d]) * field.channels + c).data());
  return result;
}

void check_original_matches(const ReflectanceField& original, const CompressedField& compressed,
                            int residual_cap) {
  check_residual_cap(residual_cap);
  if (original.width != compressed.width || original.height != compressed.height ||
      original.channels != compressed.channels || original.lights() != compressed.lights ||
      original.functions() != compressed.functions())
    throw Error(
        "cannot compare fields of different shapes: the original is " +
        shape_text(original.width, original.height, original.channels, original.lights()) +
        ", the compressed one " +
        shape_text(compressed.width, compressed.height, compressed.channels, compressed.lights));
}

RelativeError relative_error(const ReflectanceField& original, const CompressedField& compressed,
                             bool masked_only, int residual_cap, unsigned threads) {
  check_residual_cap(residual_cap);
  validate_compressed_field(compressed, "cannot measure the error of the compressed field");
  check_original_matches(original, compressed, residual_cap);
  const std::vector<std::int64_t> row_of = stored_row_of_function(compressed);
  return average_relative_error(std::size_t(original.functions()), compressed.lights, threads,
                                [&](std::size_t p, FunctionScratch& rows) {
                                  if (masked_only && !compressed.mask[p / compressed.channels])
                                    return false;
                                  const float* exact = original.values.row(Eigen::Index(p)).data();
                                  std::copy(exact, exact + compressed.lights, rows.exact.begin());
                                  reconstruct_function(compressed, row_of[p], residual_cap,
                                                       rows.sum.data(), rows.approx.data());
                                  return true;
                                });
}

RelativeError relative_error(const CompressedField& reference, const CompressedField& approximation,
                             int approximation_cap, unsigned threads) {
  check_residual_cap(approximation_cap);
  validate_compressed_field(reference, "cannot measure the error: the reference field");
  validate_compressed_field(approximation, "cannot measure the error: the approximation");
  if (reference.width != approximation.width || reference.height != approximation.height ||
      reference.channels != approximation.channels || reference.lights != approximation.lights)
    throw Error(
        "cannot compare compressed fields of different shapes: " +
        shape_text(reference.width, reference.height, reference.channels, reference.lights) +
        " and " +
        shape_text(approximation.width, approximation.height, approximation.channels,
                   approximation.lights));
  const std::vector<std::int64_t> approximation_row = stored_row_of_function(approximation);
  return average_relative_error(
      reference.stored_rows(), reference.lights, threads,
      [&](std::size_t r, FunctionScratch& rows) {
        reconstruct_function(reference, std::int64_t(r), all_residual_entries, rows.sum.data(),
                             rows.exact.data());
        reconstruct_function(approximation, approximation_row[reference.stored_function[r]],
                             approximation_cap, rows.sum.data(), rows.approx.data());
        return true;
      });
}

}  // namespace relume
