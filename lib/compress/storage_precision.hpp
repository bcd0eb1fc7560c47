// The last step of compression, shared by `relume compress` and compress(): the field made into
// what the container stores. Parts asked for as `quantized` become integers times steps within
// the error budget (model/quantization.hpp: quantize_with_budget); float16 parts are rounded
// through half (quantize_for_container). What it returns is what read_container gives back.
#pragma once

#include <optional>
#include <relume/container.hpp>
#include <utility>
#include <vector>

#include "compress/compressed_strip_file.hpp"
#include "container/container_strips.hpp"
#include "model/basis_alignment.hpp"
#include "model/quantization.hpp"

namespace relume {

struct StoragePrecision {
  ValuePrecision weights = ValuePrecision::quantized;
  ValuePrecision residual = ValuePrecision::quantized;
  bool quantize_bases = true;
  double budget = QuantizationBudget{}.relative_increase;   // of the squared error
  double term_budget = QuantizationBudget{}.term_increase;  // 0: every cluster keeps all terms
  unsigned threads = 0;

  bool quantizes() const {
    return weights == ValuePrecision::quantized || residual == ValuePrecision::quantized ||
           quantize_bases;
  }
  QuantizationBudget quantization_budget() const;
  ContainerOptions container_options() const;  // the precisions, for the float parts
};

// `field`, compressed from `original`, as stored; the quantization chosen, if any. Throws Error
// for a budget that is not a positive number or a term budget that is negative.
std::optional<QuantizationChoice> store_with_precision(const ReflectanceField& original,
                                                       CompressedField& field,
                                                       const StoragePrecision& precision);

// As store_with_precision for a field whose original is too large to hold: the quantization is
// chosen against `sample`, pixel-row strips of the original stacked in order, whose rows of the
// field are `strips` (first row, rows). Throws Error for a term budget (choosing terms per
// cluster needs the whole original) and as store_with_precision.
std::optional<QuantizationChoice> store_with_precision_on_strips(
    const ReflectanceField& sample, const std::vector<std::pair<int, int>>& strips,
    CompressedField& field, const StoragePrecision& precision);

// How every strip of a field whose compressed strips are on disk (compress/compressed_strip_file.hpp)
// is stored, as store_with_precision_on_strips stores a field in memory: its bases aligned and its
// values rounded to the steps, then through the container's float16 where asked. The same for
// every strip, so that several ranks store their own strips alike (compress/rank_exchange.hpp).
struct StripStorage {
  bool quantized = false;  // aligned and rounded to `steps`
  BasisAlignment alignment;
  QuantizationSteps steps;
  ValuePrecision weights = ValuePrecision::float32, residual = ValuePrecision::float32;

  // `strip` (or the strips' shell) as stored.
  CompressedField store(CompressedField strip) const;
};

// The storage of `strips`: the bases aligned for the clusters' sizes, the steps chosen against
// `sample` (pixel rows of the original) and `sampled` (the same rows of the field as built), then
// widened in one pass over the strips until every value fits. `choice` receives the quantization
// chosen, if any. Throws Error as store_with_precision_on_strips.
StripStorage choose_strip_storage(const ReflectanceField& sample, const CompressedField& sampled,
                                  const CompressedStripFile& strips,
                                  const StoragePrecision& precision,
                                  std::optional<QuantizationChoice>& choice);

// `strips` as `storage` stores them, each strip stored as it is read (by the container writer,
// the error measure); both must outlive the result.
CompressedFieldStrips stored_strips(const CompressedStripFile& strips, const StripStorage& storage);

}  // namespace relume
