// Implementation of the target-error search (see compression_target.hpp).
#include "compress/compression_target.hpp"

#include <algorithm>
#include <cstdio>
#include <functional>
#include <optional>
#include <relume/error.hpp>

namespace relume {

void for_each_grid_candidate(const ReflectanceField& field, const CompressionOptions& options,
                             const std::function<void(GridCandidate&)>& visit,
                             const std::function<bool(int terms, int clusters)>& skip,
                             const PreparedField* prepared) {
  std::optional<PreparedField> own;  // prepared here at the first pair factored, when not given
  for (const int terms : {2, 4, 8}) {
    if (terms >= field.lights()) continue;
    for (const int clusters : {32, 64, 128}) {
      if (skip && skip(terms, clusters)) continue;
      GridCandidate candidate;
      candidate.options = options;
      candidate.options.clustering.terms = terms;
      candidate.options.clustering.clusters = clusters;
      candidate.options.residual = ResidualBudget{0, 100.0};
      if (!prepared) prepared = &own.emplace(prepare_field(field, options));
      candidate.full =
          compress_prepared_field(field, *prepared, candidate.options, candidate.stats);
      candidate.energy.resize(candidate.full.stored_rows());
      for (std::size_t r = 0; r < candidate.energy.size(); ++r)
        candidate.energy[r] =
            field.values.row(candidate.full.stored_function[r]).cast<double>().squaredNorm();
      visit(candidate);
    }
  }
}

std::vector<float> residual_gains(const ResidualRows& residual,
                                  const std::vector<double>& row_weight) {
  std::vector<float> gains(residual.nonzeros());
  for (std::size_t r = 0; r < residual.rows(); ++r)
    for (std::uint32_t k = residual.row_offsets[r]; k < residual.row_offsets[r + 1]; ++k)
      gains[k] =
          static_cast<float>(double(residual.values[k]) * residual.values[k] * row_weight[r]);
  return gains;
}

double keep_entries_with_gain(ResidualRows& residual, const std::vector<float>& gains, float cut) {
  ResidualRows out;
  out.row_offsets.push_back(0);
  double kept = 0;
  for (std::size_t r = 0; r < residual.rows(); ++r) {
    for (std::uint32_t k = residual.row_offsets[r]; k < residual.row_offsets[r + 1]; ++k) {
      if (gains[k] < cut) break;  // rows are sorted by |value|: the rest gain less
      out.light_index.push_back(residual.light_index[k]);
      out.values.push_back(residual.values[k]);
      kept += gains[k];
    }
    out.row_offsets.push_back(static_cast<std::uint32_t>(out.values.size()));
  }
  residual = std::move(out);
  return kept;
}

double cut_residual_to_error(CompressedField& field, const std::vector<double>& energy,
                             double target_error) {
  ResidualRows& residual = field.residual;
  const std::size_t rows = residual.rows();
  if (rows == 0) return 0.0;
  std::vector<double> inverse_energy(rows);
  for (std::size_t r = 0; r < rows; ++r) inverse_energy[r] = 1.0 / energy[r];
  const std::vector<float> gains = residual_gains(residual, inverse_energy);
  double total = 0;
  for (const float gain : gains) total += gain;
  const double allowed = target_error * double(rows);
  const double needed = total - allowed;  // error reduction the kept entries must bring
  float cut = HUGE_VALF;                  // keep entries with gain >= cut
  if (needed > 0) {
    std::vector<float> sorted = gains;
    std::sort(sorted.begin(), sorted.end(), std::greater<float>());
    double kept = 0;
    cut = sorted.empty() ? 0.0f : sorted.back();
    for (const float gain : sorted) {
      kept += gain;
      if (kept >= needed) {
        cut = gain;
        break;
      }
    }
  }
  const double kept = keep_entries_with_gain(residual, gains, cut);
  return std::max(0.0, (total - kept) / double(rows));
}

namespace {

// `full` cut to the target and, with a budget, quantized; the error reached over its stored rows.
struct Candidate {
  CompressedField field;
  double reached = 0;
  std::optional<QuantizationChoice> quantization;
};

Candidate cut_and_store(const ReflectanceField& original, const CompressedField& full,
                        const std::vector<double>& energy, double target_error,
                        const QuantizationBudget* quantization) {
  Candidate candidate;
  std::optional<QuantizationBudget> budget;  // held on Eq. 16, the target's measure
  if (quantization) budget = *quantization, budget->eq16 = true;
  double aim = budget ? target_error / (1 + budget->relative_increase) : target_error;
  for (int round = 0; round < 4; ++round) {
    candidate.field = full;
    candidate.reached = cut_residual_to_error(candidate.field, energy, aim);
    if (!budget) return candidate;
    candidate.quantization = quantize_with_budget(original, candidate.field, *budget);
    candidate.reached = relative_error(original, candidate.field, true).mean;
    if (candidate.reached <= target_error) break;
    aim *= target_error / candidate.reached;  // quantization added more than its share: aim lower
  }
  return candidate;
}

}  // namespace

TargetSearch compress_to_target_error(const ReflectanceField& field,
                                      const CompressionOptions& options, double target_error,
                                      const ContainerOptions& container,
                                      const QuantizationBudget* quantization,
                                      CompressionStats& stats) {
  if (!(target_error > 0))
    throw Error("target error must be > 0, got " + std::to_string(target_error));
  TargetSearch best;
  std::uint64_t best_bytes = 0;
  nlohmann::ordered_json tried = nlohmann::ordered_json::array();
  for_each_grid_candidate(field, options, [&](GridCandidate& grid) {
    const int terms = grid.options.clustering.terms;
    Candidate stored = cut_and_store(field, grid.full, grid.energy, target_error, quantization);
    CompressedField& compressed = stored.field;
    const double reached = stored.reached;
    grid.stats.residual_nonzeros = compressed.residual.nonzeros();
    const std::uint64_t bytes = plan_container(compressed, container).file_bytes;
    const double mean_entries =
        compressed.stored_rows() ? double(compressed.residual.nonzeros()) / compressed.stored_rows()
                                 : 0;
    tried.push_back({{"terms", terms},
                     {"clusters", compressed.clusters},
                     {"bytes", bytes},
                     {"mean_residual_entries", mean_entries},
                     {"error_over_stored_rows", reached}});
    if (!options.clustering.quiet)
      std::fprintf(stderr,
                   "compress: target %.4g: %d terms, %d clusters -> %llu bytes "
                   "(%.2f residual entries per function)\n",
                   target_error, terms, compressed.clusters, static_cast<unsigned long long>(bytes),
                   mean_entries);
    if (best_bytes == 0 || bytes < best_bytes) {
      best_bytes = bytes;
      best.field = std::move(compressed);
      best.quantization = stored.quantization;
      best.options = grid.options;
      stats = grid.stats;
    }
  });
  best.explanation = {
      {"target", target_error},
      {"method",
       "each (terms, clusters) pair factored once with its full residual; the residual entries "
       "with the largest e^2/||R[p,:]||^2 kept across all functions until the mean relative error "
       "(Eq. 16) over the stored functions reaches the target; the smallest container wins"},
      {"tried", tried},
      {"chosen",
       {{"terms", best.options.clustering.terms},
        {"clusters", best.field.clusters},
        {"bytes", best_bytes}}}};
  return best;
}

}  // namespace relume
