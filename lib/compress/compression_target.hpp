// `relume compress --target-error E`: the settings that reach a relative error E (paper Eq. 16,
// over the masked functions) with the fewest stored bytes. For each (terms, clusters) pair of a
// small grid the field is factored once; then, since the error is a mean of per-function relative
// errors and every residual entry costs the same bytes, the entries with the largest error
// reduction e^2 / ||R[p,:]||^2 are kept across all functions until the mean error reaches E: each
// function gets its own residual length (a prefix of its sorted row). The pair with the smallest
// container wins.
#pragma once

#include <functional>
#include <nlohmann/json.hpp>
#include <optional>

#include "compress/clustered_factorization.hpp"
#include "container/container.hpp"
#include "model/quantization.hpp"

namespace relume {

struct TargetSearch {
  CompressedField field;       // quantized when a budget was given
  CompressionOptions options;  // the chosen terms and clusters
  std::optional<QuantizationChoice> quantization;
  nlohmann::ordered_json explanation;  // every candidate tried, its bytes and the choice
};

// `options` gives everything but terms, clusters and the residual budget. With `quantization`,
// every candidate is stored quantized within that budget (quantize_with_budget) and measured so:
// its residual is cut to a lower target first, and again lower while the quantized field's error
// is above the target. `stats` receives the statistics of the chosen run.
TargetSearch compress_to_target_error(const ReflectanceField& field,
                                      const CompressionOptions& options, double target_error,
                                      const ContainerOptions& container,
                                      const QuantizationBudget* quantization,
                                      CompressionStats& stats);

// One (terms, clusters) pair of the grid the targets search, factored with its full residual.
struct GridCandidate {
  CompressionOptions options;  // the pair's terms and clusters, a full residual budget
  CompressedField full;
  CompressionStats stats;
  std::vector<double> energy;  // ||R[p,:]||^2 of each stored row
};

// Calls `visit` for every pair of terms {2, 4, 8} (below the light count) and clusters
// {32, 64, 128}, in that order, each factored as compress_field does with `options` otherwise,
// from rows prepared once (`prepared`, from prepare_field(field, options), when given); a pair
// for which `skip(terms, clusters)` (when given) is true is neither factored nor visited.
void for_each_grid_candidate(const ReflectanceField& field, const CompressionOptions& options,
                             const std::function<void(GridCandidate&)>& visit,
                             const std::function<bool(int terms, int clusters)>& skip = {},
                             const PreparedField* prepared = nullptr);

// Each residual entry's error reduction: value^2 times its row's weight (1 / ||R[p,:]||^2 for
// Eq. 16, 1 inside a PSNR region and 0 outside it). Within a row the gains descend, as the
// entries are sorted by |value|.
std::vector<float> residual_gains(const ResidualRows& residual,
                                  const std::vector<double>& row_weight);

// Keeps, of every row, the prefix of entries whose gain is >= cut; returns the sum of the kept
// gains.
double keep_entries_with_gain(ResidualRows& residual, const std::vector<float>& gains, float cut);

// Cuts every row of `field`'s residual to the shortest prefix such that the mean per-function
// relative error over its stored rows reaches `target_error` (rows sorted by |value|, as stored).
// `energy` holds each stored row's ||R[p,:]||^2. Returns the mean error reached.
double cut_residual_to_error(CompressedField& field, const std::vector<double>& energy,
                             double target_error);

}  // namespace relume
