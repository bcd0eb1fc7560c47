// Implementation of the public compress() (relume/compress.hpp) over compress_field and the
// target-error search, with the options mapped as `relume compress` maps its own, and the
// progress callback installed as the listener of the work's ProgressReporters.
#include <cmath>
#include <memory>
#include <relume/compress.hpp>
#include <relume/error.hpp>

#include "compress/clustered_factorization.hpp"
#include "compress/compression_target.hpp"
#include "compress/opencl_assignment.hpp"
#include "compress/storage_precision.hpp"
#include "container/container.hpp"
#include "core/progress.hpp"

namespace relume {

CompressedField compress(const ReflectanceField& field, const CompressOptions& options) {
  if (!(options.residual_percent >= 0 && options.residual_percent <= 100) &&
      options.residual_entries < 0)
    throw Error("the residual percentage must be in [0, 100], got " +
                std::to_string(options.residual_percent));
  if (options.irls_iterations < 0)
    throw Error("IRLS iterations must be >= 0, got " + std::to_string(options.irls_iterations));
  if (options.target_error < 0 || !std::isfinite(options.target_error))
    throw Error("the target error must be a relative error > 0 (or 0: none), got " +
                std::to_string(options.target_error));
  CompressionOptions internal;
  ClusteringOptions& clustering = internal.clustering;
  clustering.clusters = options.clusters;
  clustering.terms = options.terms;
  clustering.max_iterations = options.iterations;
  clustering.candidates = options.candidates;
  clustering.weight_fit.iterations = options.irls_iterations;
  clustering.basis_fit.iterations = options.irls_iterations;
  clustering.sizes.minimum = options.min_cluster_size;
  clustering.sizes.maximum = options.max_cluster_size;
  if (options.solver != "irls") clustering.exact_refit = parse_l1_method(options.solver);
  clustering.seed = options.seed;
  clustering.threads = options.threads;
  clustering.quiet = options.quiet;
  internal.residual = options.residual_entries >= 0 ? ResidualBudget{options.residual_entries}
                                                    : ResidualBudget{0, options.residual_percent};
  internal.residual_threshold = options.residual_threshold;
  internal.noise_floor = options.noise_floor;
  internal.transform = options.transform;
  internal.light_weighting = options.light_weighting;
  internal.multires_levels = options.multires_levels;
  internal.refine_iterations = options.refine_iterations;

  std::unique_ptr<OpenClAssigner> assigner;
  if (options.opencl_assignment) {
    assigner = make_opencl_assigner(options.device, clustering);
    clustering.assign = assigner->function();
  }
  StoragePrecision storage;
  storage.weights = options.weights_precision;
  storage.residual = options.residual_precision;
  storage.quantize_bases = options.quantize_bases;
  storage.budget = options.quantization_budget;
  storage.term_budget = options.term_budget;
  storage.threads = options.threads;
  const QuantizationBudget budget = storage.quantization_budget();  // checks it before the work
  const ProgressListenerScope listening(options.progress);
  CompressionStats stats;
  if (options.target_error > 0) {
    CompressedField stored =
        compress_to_target_error(field, internal, options.target_error, storage.container_options(),
                                 storage.quantizes() ? &budget : nullptr, stats)
            .field;
    return quantize_for_container(stored, storage.container_options());
  }
  CompressedField stored = compress_field(field, internal, stats);
  store_with_precision(field, stored, storage);
  return stored;
}

}  // namespace relume
