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
#include "model/quantization.hpp"

namespace relume {

struct StoragePrecision {
  ValuePrecision weights = ValuePrecision::quantized;
  ValuePrecision residual = ValuePrecision::quantized;
  bool quantize_bases = true;
  double budget = QuantizationBudget{}.relative_increase;   // of the Eq. 16 error
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

// The stored form of a field whose compressed strips are on disk (compress/compressed_strip_file.hpp),
// as store_with_precision_on_strips makes it of one in memory: the bases aligned for the clusters'
// sizes, the steps chosen against `sample` (pixel rows of the original) and `sampled` (the same
// rows of the field as built), then widened in one pass over the strips until every value fits.
// The result's strips are aligned and rounded as they are read (by the container writer, the
// error measure); `strips` must outlive it. `choice` receives the quantization chosen, if any.
// Throws Error as store_with_precision_on_strips.
CompressedFieldStrips stored_strips(const ReflectanceField& sample, const CompressedField& sampled,
                                    const CompressedStripFile& strips,
                                    const StoragePrecision& precision,
                                    std::optional<QuantizationChoice>& choice);

}  // namespace relume
