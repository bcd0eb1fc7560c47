// Implementation of quantized storage and the error-budget choice of its steps.
#include "model/quantization.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <relume/error.hpp>
#include <vector>

#include "core/parallel.hpp"
#include "model/basis_alignment.hpp"
#include "model/cluster_terms.hpp"
#include "model/reconstruct_field.hpp"

namespace relume {
namespace {

// An integer multiple of `step` in [-max_quantized_value, max_quantized_value]; throws naming
// `what` when the value is beyond that range.
template <class Describe>
float round_to_step(float value, float step, const Describe& what) {
  const double q = std::nearbyint(double(value) / step);
  if (std::abs(q) > max_quantized_value)
    throw Error("cannot quantize " + what() + " (" + std::to_string(value) + ") with step " +
                std::to_string(step) + ": it needs more than 16 bits");
  return float(q * step);
}

void quantize_bases(CompressedField& field, int bits) {
  if (bits < 8 || bits > 16) throw Error("basis bits must be 8 to 16, got " + std::to_string(bits));
  const double largest_integer = std::ldexp(1.0, bits - 1) - 1;
  field.quantization.basis_bits = bits;
  field.quantization.basis_scales.assign(std::size_t(field.clusters) * field.terms, 0.0f);
  for (std::size_t row = 0; row < field.quantization.basis_scales.size(); ++row) {
    float* f = field.bases.data() + row * field.lights;
    float peak = 0;
    for (int i = 0; i < field.lights; ++i) peak = std::max(peak, std::abs(f[i]));
    const float scale = peak > 0 ? float(peak / largest_integer) : 1.0f;
    field.quantization.basis_scales[row] = scale;
    for (int i = 0; i < field.lights; ++i) f[i] = float(std::nearbyint(f[i] / scale) * scale);
  }
}

void quantize_residual(CompressedField& field, float step) {
  ResidualRows& e = field.residual;
  ResidualRows kept;
  kept.row_offsets.assign(1, 0);
  for (std::size_t r = 0; r < e.rows(); ++r) {
    for (std::uint32_t k = e.row_offsets[r]; k < e.row_offsets[r + 1]; ++k) {
      const float value = round_to_step(e.values[k], step, [&] {
        return "residual entry " + std::to_string(k - e.row_offsets[r]) + " of stored row " +
               std::to_string(r);
      });
      if (value == 0) continue;  // rounding keeps |value| order, so the zeros are the row's end
      kept.values.push_back(value);
      kept.light_index.push_back(e.light_index[k]);
    }
    kept.row_offsets.push_back(std::uint32_t(kept.values.size()));
  }
  e = std::move(kept);
  field.quantization.residual_step = step;
}

// Evenly spaced stored rows, at most `count`.
std::vector<std::size_t> sample_rows(std::size_t rows, std::size_t count) {
  std::vector<std::size_t> sample;
  const std::size_t stride = std::max<std::size_t>(1, rows / std::max<std::size_t>(count, 1));
  for (std::size_t r = 0; r < rows; r += stride) sample.push_back(r);
  return sample;
}

// The squared error over the sampled stored rows relative to their energy: the measure PSNR
// takes, where a function's share is its squared error, not (as in Eq. 16) its error relative to
// its own norm, which would let the faintest, noisiest functions choose the steps. With `eq16`,
// Eq. 16 over the sample (zero-energy functions left out).
double sampled_error(const ReflectanceField& original, const CompressedField& field,
                     const std::vector<std::size_t>& rows, bool eq16, unsigned threads) {
  const unsigned workers = resolve_thread_count(threads);
  std::vector<std::vector<double>> sums(workers, std::vector<double>(field.lights));
  std::vector<std::vector<float>> approx(workers, std::vector<float>(field.lights));
  std::vector<double> energy(rows.size()), difference(rows.size());
  parallel_for(rows.size(), threads, [&](std::size_t s, unsigned worker) {
    const std::size_t r = rows[s];
    reconstruct_function(field, std::int64_t(r), all_residual_entries, sums[worker].data(),
                         approx[worker].data());
    const float* exact = original.values.row(Eigen::Index(field.stored_function[r])).data();
    for (int i = 0; i < field.lights; ++i) {
      energy[s] += double(exact[i]) * exact[i];
      difference[s] += std::pow(double(exact[i]) - approx[worker][i], 2);
    }
  });
  if (eq16) {
    double total = 0;
    std::size_t counted = 0;
    for (std::size_t s = 0; s < rows.size(); ++s)
      if (energy[s] > 0) total += difference[s] / energy[s], ++counted;
    return counted ? total / double(counted) : 0.0;
  }
  const double total_energy = std::accumulate(energy.begin(), energy.end(), 0.0);
  return total_energy > 0
             ? std::accumulate(difference.begin(), difference.end(), 0.0) / total_energy
             : 0.0;
}

// The field restricted to `rows` (for measuring a sample quickly).
CompressedField rows_subset(const CompressedField& field, const std::vector<std::size_t>& rows) {
  CompressedField subset = field;
  subset.stored_function.clear();
  subset.cluster.clear();
  subset.weights.resize(Eigen::Index(rows.size()), field.terms);
  subset.residual = {};
  subset.residual.row_offsets.assign(1, 0);
  for (std::size_t s = 0; s < rows.size(); ++s) {
    const std::size_t r = rows[s];
    subset.stored_function.push_back(field.stored_function[r]);
    subset.cluster.push_back(field.cluster[r]);
    subset.weights.row(Eigen::Index(s)) = field.weights.row(Eigen::Index(r));
    for (std::uint32_t k = field.residual.row_offsets[r]; k < field.residual.row_offsets[r + 1];
         ++k) {
      subset.residual.values.push_back(field.residual.values[k]);
      subset.residual.light_index.push_back(field.residual.light_index[k]);
    }
    subset.residual.row_offsets.push_back(std::uint32_t(subset.residual.values.size()));
  }
  return subset;
}

// The largest |value| of W or the residual (0 when there is none).
float largest_weight(const CompressedField& field) {
  return field.weights.size() ? field.weights.cwiseAbs().maxCoeff() : 0.0f;
}
float largest_residual(const CompressedField& field) {
  float largest = 0;
  for (float v : field.residual.values) largest = std::max(largest, std::abs(v));
  return largest;
}

// The finest step that still keeps `largest` within the integers (with room for rounding).
float finest_step(float largest) { return largest / float(max_quantized_value - 1); }

}  // namespace

CompressedField quantize_values(CompressedField quantized, const QuantizationSteps& steps) {
  if (steps.basis_bits > 0) quantize_bases(quantized, steps.basis_bits);
  if (steps.weight_step > 0) {
    for (Eigen::Index r = 0; r < quantized.weights.rows(); ++r)
      for (int j = 0; j < quantized.terms; ++j)
        quantized.weights(r, j) = round_to_step(quantized.weights(r, j), steps.weight_step, [&] {
          return "the weight of stored row " + std::to_string(r) + " term " + std::to_string(j);
        });
    quantized.quantization.weight_step = steps.weight_step;
  }
  if (steps.residual_step > 0) quantize_residual(quantized, steps.residual_step);
  return quantized;
}

QuantizationSteps steps_that_fit(const CompressedField& field, QuantizationSteps steps) {
  if (steps.weight_step > 0)
    steps.weight_step = std::max(steps.weight_step, finest_step(largest_weight(field)));
  if (steps.residual_step > 0)
    steps.residual_step = std::max(steps.residual_step, finest_step(largest_residual(field)));
  return steps;
}

QuantizationChoice choose_quantization(const ReflectanceField& original,
                                       const CompressedField& field,
                                       const QuantizationBudget& budget) {
  const std::vector<std::size_t> rows = sample_rows(field.stored_rows(), budget.sample_rows);
  const CompressedField sample = rows_subset(field, rows);
  std::vector<std::size_t> all(rows.size());
  for (std::size_t s = 0; s < all.size(); ++s) all[s] = s;
  QuantizationChoice choice;
  choice.error_unquantized = sampled_error(original, sample, all, budget.eq16, budget.threads);
  const double allowed = choice.error_unquantized * budget.relative_increase;
  auto increase = [&](const QuantizationSteps& steps) {
    return sampled_error(original, quantize_values(sample, steps), all, budget.eq16,
                         budget.threads) -
           choice.error_unquantized;
  };

  // Bases: the fewest bits within a quarter of the budget.
  QuantizationSteps steps;
  if (budget.bases) {
    steps.basis_bits = 16;
    for (int bits = 8; bits < 16; ++bits)
      if (increase({0, 0, bits}) <= 0.25 * allowed) {
        steps.basis_bits = bits;
        break;
      }
  }
  // Weights and residual: the coarsest step (bisection over log2 of the step) within their share;
  // the finest allowed step is the one that puts the largest value at the 16-bit limit.
  auto coarsest = [&](float largest, double share, auto make) {
    if (largest == 0) return 0.0f;
    double fine = std::log2(finest_step(largest)), coarse = std::log2(largest);
    if (increase(make(float(std::exp2(fine)))) > share * allowed) return float(std::exp2(fine));
    for (int step = 0; step < 24; ++step) {
      const double middle = 0.5 * (fine + coarse);
      (increase(make(float(std::exp2(middle)))) <= share * allowed ? fine : coarse) = middle;
    }
    return float(std::exp2(fine));
  };
  if (budget.weights)
    steps.weight_step = coarsest(largest_weight(sample), 0.4, [](float s) {
      return QuantizationSteps{s, 0, 0};
    });
  if (budget.residual)
    steps.residual_step = coarsest(largest_residual(sample), 0.35, [](float s) {
      return QuantizationSteps{0, s, 0};
    });
  // Together they may interact: halve the value steps until the whole budget holds.
  for (int round = 0; round < 8 && increase(steps) > allowed; ++round) {
    if (steps.weight_step > 0)
      steps.weight_step = std::max(steps.weight_step * 0.5f, finest_step(largest_weight(field)));
    if (steps.residual_step > 0)
      steps.residual_step =
          std::max(steps.residual_step * 0.5f, finest_step(largest_residual(field)));
  }
  choice.steps = steps_that_fit(field, steps);
  choice.error_quantized = choice.error_unquantized + increase(choice.steps);
  return choice;
}

QuantizationChoice quantize_with_budget(const ReflectanceField& original, CompressedField& field,
                                        const QuantizationBudget& budget) {
  TermChoice terms;
  if (budget.term_increase > 0)
    terms = drop_unneeded_terms(original, field, budget.term_increase, budget.threads);
  align_cluster_bases(field);
  QuantizationChoice choice = choose_quantization(original, field, budget);
  if (terms.dropped > 0) {
    choice.cluster_terms = terms.cluster_terms;
    choice.error_all_terms = terms.error_all_terms;
  }
  field = quantize_values(std::move(field), choice.steps);
  return choice;
}

}  // namespace relume
