// Quantized storage of a compressed field (relume/compressed_field.hpp ValueQuantization): W and
// the residual values as integers times one step each, every basis row as integers of a few bits
// times its own scale. Best after align_cluster_bases (model/basis_alignment.hpp), where one
// weight step means the same absolute error everywhere. The steps come from an error budget: the
// largest that keep the squared error of a sample of the stored rows against the original field
// within (1 + budget) of the unquantized field's. The squared error, not Eq. 16's mean of each
// function's error relative to its own norm: there the faintest functions, all sensor noise,
// would set the steps for the rows that carry the image.
#pragma once

#include <cstddef>
#include <relume/compressed_field.hpp>
#include <relume/field.hpp>
#include <vector>

namespace relume {

// The integer range of quantized weights and residual values.
inline constexpr int max_quantized_value = 32767;

struct QuantizationSteps {
  float weight_step = 0;    // 0: weights stay float
  float residual_step = 0;  // 0: residual values stay float
  int basis_bits = 0;       // 0: bases stay float; else 8..16
};

// The field with its values rounded to `steps` and field.quantization set to say so. Residual
// entries that round to zero are dropped (rows stay sorted by |value|). Throws Error when a step
// would make an integer beyond max_quantized_value or basis_bits is outside 8..16.
// Takes the field by value: pass it with std::move to quantize it without a copy.
CompressedField quantize_values(CompressedField field, const QuantizationSteps& steps);

// What quantization may add to the squared error of the stored rows, relative, by default: 1%,
// 0.04 dB of PSNR.
inline constexpr double default_quantization_budget = 0.01;

struct QuantizationBudget {
  // Of the squared error over the stored rows (sum over a sample of rows of ||R - R~||^2, relative
  // to their energy: what PSNR measures)
  double relative_increase = default_quantization_budget;
  // Hold the budget on Eq. 16 (the mean of each function's error relative to its own norm)
  // instead: for a target given in Eq. 16 (--target-error).
  bool eq16 = false;
  // The parts to quantize; the others keep float values.
  bool weights = true, residual = true, bases = true;
  // What dropping the terms each cluster does not need may add to the Eq. 16 error, relative,
  // before the quantization's own share (model/cluster_terms.hpp); 0 keeps every term.
  double term_increase = 0;
  std::size_t sample_rows = 20000;  // stored rows the error is measured on (evenly spaced)
  unsigned threads = 0;
};

struct QuantizationChoice {
  QuantizationSteps steps;
  // The terms each cluster kept (empty: every cluster kept all) and the Eq. 16 error over the
  // stored rows with all of them.
  std::vector<int> cluster_terms;
  double error_all_terms = 0;
  double error_unquantized = 0;  // Eq. 16 over the sample
  double error_quantized = 0;
};

// The coarsest steps within the budget: each part (bases, weights, residual) gets its share of
// the budget, then all together are checked and refined until they fit. `original` is the field
// `field` was compressed from.
QuantizationChoice choose_quantization(const ReflectanceField& original,
                                       const CompressedField& field,
                                       const QuantizationBudget& budget);

// `steps` widened where needed so that the field's largest weight and residual value fit the
// integers (a step chosen on a sample of the field may be too fine for the whole).
QuantizationSteps steps_that_fit(const CompressedField& field, QuantizationSteps steps);

// The whole step, in place: drop_unneeded_terms within budget.term_increase
// (model/cluster_terms.hpp), align_cluster_bases, choose_quantization, quantize_values.
QuantizationChoice quantize_with_budget(const ReflectanceField& original, CompressedField& field,
                                        const QuantizationBudget& budget);

}  // namespace relume
