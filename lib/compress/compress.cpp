// Implementation of the public compress() (relume/compress.hpp) over compress_field.
#include <cmath>
#include <memory>
#include <relume/compress.hpp>
#include <relume/error.hpp>

#include "compress/clustered_factorization.hpp"
#include "compress/opencl_assignment.hpp"

namespace relume {

CompressedField compress(const ReflectanceField& field, const CompressOptions& options) {
  if (!(options.residual_percent >= 0 && options.residual_percent <= 100) &&
      options.residual_entries < 0)
    throw Error("the residual percentage must be in [0, 100], got " +
                std::to_string(options.residual_percent));
  CompressionOptions internal;
  internal.clustering.clusters = options.clusters;
  internal.clustering.terms = options.terms;
  internal.clustering.max_iterations = options.iterations;
  internal.clustering.seed = options.seed;
  internal.clustering.threads = options.threads;
  internal.clustering.quiet = options.quiet;
  internal.residual = options.residual_entries >= 0 ? ResidualBudget{options.residual_entries}
                                                    : ResidualBudget{0, options.residual_percent};
  internal.residual_threshold = options.residual_threshold;
  internal.transform = options.transform;
  internal.multires_levels = options.multires_levels;

  std::unique_ptr<OpenClAssigner> assigner;
  if (options.opencl_assignment) {
    assigner = make_opencl_assigner(options.device, internal.clustering);
    internal.clustering.assign = assigner->function();
  }
  CompressionStats stats;
  return compress_field(field, internal, stats);
}

}  // namespace relume
