// Implementation of the one mapping from CompressOptions to the stages' settings.
#include "compress/compress_settings.hpp"

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <relume/error.hpp>

#include "container/container.hpp"
#include "field/input_encoding.hpp"

namespace relume {
namespace {

void check_choice(const char* option, const std::string& value,
                  std::initializer_list<const char*> choices) {
  std::string listed;
  for (const char* choice : choices) {
    if (value == choice) return;
    listed += std::string(listed.empty() ? "'" : "' or '") + choice;
  }
  throw Error(std::string(option) + " must be " + listed + "', got '" + value + "'");
}

// At most one target, each finite and >= 0.
void check_targets(const CompressOptions& options) {
  const std::pair<const char*, double> targets[] = {
      {"--target-error", options.target_error},
      {"--target-bytes", double(options.target_bytes)},
      {"--target-bytes-per-pixel", options.target_bytes_per_pixel},
      {"--target-psnr", options.target_psnr}};
  const char* given = nullptr;
  for (const auto& [option, value] : targets) {
    if (value < 0 || !std::isfinite(value))
      throw Error(std::string(option) + " must be a finite number > 0, got " +
                  std::to_string(value));
    if (value == 0) continue;
    if (given) throw Error(std::string(given) + " and " + option + " are two targets: give one");
    given = option;
  }
  if (given && options.residual_allocation != "per-function")
    throw Error("--residual-allocation " + options.residual_allocation + " does not apply with " +
                given + ", which chooses every function's residual length itself");
  if (!(options.psnr_white > 0) || !std::isfinite(options.psnr_white))
    throw Error("--psnr-white must be a finite number > 0, got " +
                std::to_string(options.psnr_white));
}

StoragePrecision storage_precision(const CompressOptions& options) {
  check_choice("--bases-precision", options.bases_precision, {"quantized", "float32"});
  StoragePrecision precision;
  precision.weights = parse_value_precision(options.weights_precision);
  precision.residual = parse_value_precision(options.residual_precision);
  precision.quantize_bases = options.bases_precision == "quantized";
  precision.budget = options.quantization_budget < 0 ? default_quantization_budget
                                                    : options.quantization_budget;
  precision.term_budget = options.term_budget < 0 ? 0.0 : options.term_budget;
  precision.threads = options.threads;
  precision.quantization_budget();  // throws Error for a bad budget before any work
  return precision;
}

}  // namespace

CompressSettings compress_settings(const CompressOptions& options) {
  check_choice("--transform", options.transform, {"identity", "haar"});
  check_choice("--assign", options.assign, {"opencl", "cpu"});
  check_choice("--target-region", options.target_region, {"frame", "mask"});
  check_choice("--channel-clusters", options.channel_clusters, {"shared", "separate"});
  check_choice("--target-models", options.target_models, {"all", "clustered", "one-basis"});
  parse_input_encoding(options.input_encoding);
  if (options.irls_iterations < 0)
    throw Error("--irls-iterations must be >= 0, got " + std::to_string(options.irls_iterations));
  check_targets(options);

  CompressSettings settings;
  CompressionOptions& compression = settings.compression;
  compression.method = parse_compression_method(options.method);
  compression.pca.centering = parse_pca_centering(options.pca_center);
  compression.pca.iterations = options.pca_iterations;
  compression.trimmed_refit_rounds = options.trimmed_refit;
  compression.refit_chooses_clusters = options.refit_chooses_clusters;
  compression.residual = options.residual;
  compression.residual_allocation = parse_residual_allocation(options.residual_allocation);
  compression.noise_floor = options.noise_floor;
  compression.residual_threshold = options.threshold;
  compression.transform =
      options.transform == "haar" ? BasisTransform::haar : BasisTransform::identity;
  compression.light_weighting = options.light_weighting;
  compression.multires_levels = options.multires;
  if (options.refine >= 0) compression.refine_iterations = options.refine;

  ClusteringOptions& clustering = compression.clustering;
  clustering.clusters = options.clusters;
  clustering.terms = options.terms;
  clustering.max_iterations = options.iterations;
  clustering.candidates = options.candidates;
  clustering.shared_pixel_clusters = options.channel_clusters == "shared";
  clustering.weight_fit.iterations = options.irls_iterations;
  clustering.basis_fit.iterations = options.irls_iterations;
  clustering.sizes.minimum = options.min_cluster_size;
  clustering.sizes.maximum = options.max_cluster_size;
  clustering.seed = options.seed;
  clustering.threads = options.threads;
  clustering.quiet = options.quiet;
  settings.solver = options.solver;
  if (options.solver != "irls") clustering.exact_refit = parse_l1_method(options.solver);
  validate_compression_options(compression);
  settings.precision = storage_precision(options);
  return settings;
}

bool has_rate_target(const CompressOptions& options) {
  return options.target_bytes > 0 || options.target_bytes_per_pixel > 0 || options.target_psnr > 0;
}

void check_streamable(const CompressOptions& options, const CompressionOptions& compression) {
  const char* option = options.target_error > 0   ? "--target-error"
                       : has_rate_target(options) ? "a rate target (--target-bytes, --target-psnr)"
                       : options.term_budget > 0  ? "--term-budget"
                                                  : nullptr;
  if (option)
    throw Error(std::string(option) +
                " measures many compressions against the whole field, which does not fit the "
                "memory budget here (the plan is streamed): leave it out, or raise "
                "--memory-limit");
  check_streamable_options(compression);
}

std::string checkpoint_fingerprint(const std::string& input, const CompressOptions& options,
                                   const CompressionOptions& compression) {
  const ClusteringOptions& clustering = compression.clustering;
  const std::string mask = !options.use_mask           ? "none"
                           : options.mask_file.empty() ? "the folder's"
                                                       : options.mask_file.string();
  return nlohmann::json{{"input", std::filesystem::absolute(input).lexically_normal().string()},
                        {"field_input", "mask " + mask + ", encoding " + options.input_encoding},
                        {"clusters", clustering.clusters},
                        {"terms", clustering.terms},
                        {"transform", options.transform},
                        {"light_weighting", compression.light_weighting},
                        {"shared_pixel_clusters", clustering.shared_pixel_clusters},
                        {"multires", compression.multires_levels},
                        {"candidates", clustering.candidates},
                        {"min", clustering.sizes.minimum},
                        {"max", clustering.sizes.maximum},
                        {"seed", clustering.seed}}
      .dump();
}

}  // namespace relume
