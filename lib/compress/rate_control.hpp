// `relume compress --target-bytes N | --target-bytes-per-pixel B | --target-psnr DB`: rate
// control over the grid of --target-error (compression_target.hpp). Each (terms, clusters) pair
// is factored once with its full residual and stored with the asked precision (quantized within
// the budget by default), in each of the target's ways (term and quantization budgets). Its
// residual entries are ranked by the squared error each removes inside the PSNR region, and the
// number kept is found by bisection: the most entries whose container fits the bytes, or the
// fewest whose 8-bit PSNR reaches the target; no bisection where even the full residual's PSNR
// (no residual's bytes) cannot beat the best choice so far. Of the ways that meet the target, the
// highest PSNR (bytes) or the fewest bytes (PSNR) wins; when none does, the closest, and the
// explanation says so. Beside them, the one-basis model (global_basis.hpp), its weights coded as
// JPEG 2000 planes fitted to the target (global_basis_rate.hpp), competes by the same rule, at
// basis sizes found by hill climbing. It is weighed first: a pair whose smallest container is
// already larger than the target's bytes (or than the fewest bytes that reached the target PSNR)
// ends the pairs with at least its terms and clusters, which are not factored; for a byte target,
// no pair is factored once the dark pixels' error alone (model/field_psnr.hpp,
// psnr_8bit_of_unstored) leaves less PSNR than the best choice, and a factored pair whose float
// model does not beat it, with its whole residual or with the most entries the target's bytes can
// hold (at half the fewest bytes an entry cost in the containers stored so far), is not stored.
// Every rate-distortion point tried is in the explanation.
#pragma once

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "compress/compression_target.hpp"

namespace relume {

// One way to store a candidate: its term budget (QuantizationBudget::term_increase,
// model/cluster_terms.hpp) and quantization budget (relative_increase, model/quantization.hpp).
// Coarser quantization is the first way to a lower rate, as in every image codec.
struct StoredAs {
  double term_budget = 0;
  double quantization_budget = QuantizationBudget{}.relative_increase;
};

struct RateTarget {
  std::uint64_t bytes = 0;  // > 0: the container may have at most this many bytes
  double psnr = 0;          // > 0: the 8-bit PSNR in dB (model/field_psnr.hpp) to reach
  double psnr_white = 1.0;  // the field value that is 255 for the PSNR
  // width * height, non-zero where the PSNR is measured; empty: the field's mask.
  std::vector<std::uint8_t> region;
  // The models weighed: the clustered grid, the one-basis model (at least one of them).
  bool clustered = true;
  bool one_basis = true;
  // With quantized storage, each candidate is stored in each of these ways and the best counts.
  std::vector<StoredAs> stored_as{StoredAs{}};
  // The parameter record the caller's container will carry (ContainerOptions::parameters_json)
  // for a candidate's options and statistics, so that the bytes measured are the file's.
  std::function<std::string(const CompressionOptions&, const CompressionStats&)> parameters_json;
};

// A candidate as stored: its container's bytes (written with `container`), Eq. 16 over the
// masked functions and the 8-bit PSNR inside the target's region. Every rate-target point is
// measured so.
struct StoredMeasure {
  std::uint64_t bytes = 0;
  double error = 0;
  double psnr = 0;
};
StoredMeasure measure_stored(const ReflectanceField& original, const CompressedField& field,
                             const RateTarget& target, const ContainerOptions& container,
                             unsigned threads);

// Exactly one of target.bytes and target.psnr must be > 0 (Error otherwise). `options` gives
// everything but terms, clusters and the residual budget; with `quantization`, every candidate is
// quantized within it before its residual is cut. `stats` receives the chosen run's statistics.
TargetSearch compress_to_rate_target(const ReflectanceField& field,
                                     const CompressionOptions& options, const RateTarget& target,
                                     const ContainerOptions& container,
                                     const QuantizationBudget* quantization,
                                     CompressionStats& stats);

}  // namespace relume
