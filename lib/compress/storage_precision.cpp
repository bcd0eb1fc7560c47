// Implementation of the storage step of compression.
#include "compress/storage_precision.hpp"

#include <cmath>
#include <relume/error.hpp>

#include "container/container.hpp"
#include "core/progress.hpp"
#include "model/basis_alignment.hpp"
#include "model/compressed_field_rows.hpp"

namespace relume {
namespace {

// The budget of a streamed field's quantization: without a term budget.
QuantizationBudget streamed_quantization_budget(const StoragePrecision& precision) {
  const QuantizationBudget budget = precision.quantization_budget();
  if (budget.term_increase > 0)
    throw Error(
        "--term-budget chooses terms per cluster against the whole field, which does not fit "
        "the memory budget here: leave it at 0, or raise --memory-limit");
  return budget;
}

}  // namespace

QuantizationBudget StoragePrecision::quantization_budget() const {
  if (!(budget > 0) || !std::isfinite(budget))
    throw Error("the quantization budget must be a relative error increase > 0, got " +
                std::to_string(budget));
  if (!(term_budget >= 0) || !std::isfinite(term_budget))
    throw Error("the term budget must be a relative error increase >= 0, got " +
                std::to_string(term_budget));
  QuantizationBudget result;
  result.relative_increase = budget;
  result.term_increase = term_budget;
  result.weights = weights == ValuePrecision::quantized;
  result.residual = residual == ValuePrecision::quantized;
  result.bases = quantize_bases;
  result.threads = threads;
  return result;
}

ContainerOptions StoragePrecision::container_options() const {
  ContainerOptions options;
  options.weights = weights;
  options.residual = residual;
  return options;
}

std::optional<QuantizationChoice> store_with_precision(const ReflectanceField& original,
                                                       CompressedField& field,
                                                       const StoragePrecision& precision) {
  std::optional<QuantizationChoice> choice;
  if (precision.quantizes())
    choice = quantize_with_budget(original, field, precision.quantization_budget());
  field = quantize_for_container(std::move(field), precision.container_options());
  return choice;
}

std::optional<QuantizationChoice> store_with_precision_on_strips(
    const ReflectanceField& sample, const std::vector<std::pair<int, int>>& strips,
    CompressedField& field, const StoragePrecision& precision) {
  std::optional<QuantizationChoice> choice;
  if (precision.quantizes()) {
    const QuantizationBudget budget = streamed_quantization_budget(precision);
    align_cluster_bases(field);
    CompressedField sampled;
    for (const auto& [first_row, rows] : strips)
      append_compressed_rows(sampled, compressed_rows(field, first_row, rows));
    choice = choose_quantization(sample, sampled, budget);
    choice->steps = steps_that_fit(field, choice->steps);
    field = quantize_values(std::move(field), choice->steps);
  }
  field = quantize_for_container(std::move(field), precision.container_options());
  return choice;
}

CompressedField StripStorage::store(CompressedField strip) const {
  if (quantized) {
    apply_basis_alignment(alignment, strip);
    strip = quantize_values(std::move(strip), steps);
  }
  ContainerOptions options;
  options.weights = weights;
  options.residual = residual;
  return quantize_for_container(std::move(strip), options);
}

StripStorage choose_strip_storage(const ReflectanceField& sample, const CompressedField& sampled,
                                  const CompressedStripFile& strips,
                                  const StoragePrecision& precision,
                                  std::optional<QuantizationChoice>& choice) {
  StripStorage storage;
  storage.weights = precision.weights;
  storage.residual = precision.residual;
  if (!precision.quantizes()) return storage;
  const QuantizationBudget budget = streamed_quantization_budget(precision);
  storage.quantized = true;
  storage.alignment = cluster_basis_alignment(strips.shell(), strips.cluster_sizes());
  CompressedField aligned_sample = sampled;
  apply_basis_alignment(storage.alignment, aligned_sample);
  choice = choose_quantization(sample, aligned_sample, budget);
  ProgressReporter progress("compress: fitting the steps to every strip", strips.strips());
  for (std::size_t s = 0; s < strips.strips(); ++s) {
    progress.advance();
    CompressedField strip = strips.read(s);
    apply_basis_alignment(storage.alignment, strip);
    choice->steps = steps_that_fit(strip, choice->steps);
  }
  progress.finish();
  storage.steps = choice->steps;
  return storage;
}

CompressedFieldStrips stored_strips(const CompressedStripFile& strips,
                                    const StripStorage& storage) {
  CompressedFieldStrips stored;
  stored.shell = storage.store(strips.shell());
  stored.first_rows = strips.first_rows();
  stored.strip = [&strips, &storage](std::size_t s) { return storage.store(strips.read(s)); };
  return stored;
}

}  // namespace relume
