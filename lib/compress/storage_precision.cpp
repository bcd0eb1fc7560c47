// Implementation of the storage step of compression.
#include "compress/storage_precision.hpp"

#include <cmath>
#include <relume/error.hpp>

#include "container/container.hpp"

namespace relume {

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
  field = quantize_for_container(field, precision.container_options());
  return choice;
}

}  // namespace relume
