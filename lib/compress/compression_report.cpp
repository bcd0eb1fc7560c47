// Implementation of the compression report (see compression_report.hpp).
#include "compress/compression_report.hpp"

#include <sys/resource.h>

#include <cmath>
#include <cstdio>

namespace relume {
namespace {

// JSON has no infinity or NaN: identical images (infinite PSNR) and empty masks are null.
nlohmann::ordered_json finite_or_null(double value) {
  return std::isfinite(value) ? nlohmann::ordered_json(value) : nlohmann::ordered_json();
}

nlohmann::ordered_json error_json(const RelativeError& error) {
  return {{"mean", error.mean},
          {"functions_averaged", error.functions_averaged},
          {"zero_energy_skipped", error.zero_energy_skipped}};
}

nlohmann::ordered_json clustering_json(const ClusteringTrace& trace) {
  nlohmann::ordered_json iterations = nlohmann::ordered_json::array();
  for (const IterationRecord& record : trace.iterations)
    iterations.push_back({{"iteration", record.iteration},
                          {"l1_objective", record.objective},
                          {"changed", record.changed},
                          {"split_pixels", record.split_pixels},
                          {"clusters", record.clusters},
                          {"merged", record.size_rules.merged},
                          {"split", record.size_rules.split},
                          {"seconds", record.seconds}});
  nlohmann::ordered_json json = {{"iterations", iterations},
                                 {"settled", trace.settled},
                                 {"seconds",
                                  {{"seeding", trace.seeding_seconds},
                                   {"basis_fit", trace.basis_seconds},
                                   {"candidates", trace.candidate_seconds},
                                   {"assignment", trace.assignment_seconds},
                                   {"size_rules", trace.size_rule_seconds},
                                   {"exact_refit", trace.exact_refit_seconds}}}};
  if (trace.exact_refit_objective_before)
    json["exact_refit"] = {{"l1_objective_before", *trace.exact_refit_objective_before},
                           {"l1_objective_after", *trace.exact_refit_objective_after}};
  return json;
}

nlohmann::ordered_json per_light_error_json(const PerLightError& error,
                                            const CompressedField& field) {
  nlohmann::ordered_json at;
  if (error.function >= 0) {
    const std::int64_t pixel = error.function / field.channels;
    at = {{"x", pixel % field.width},
          {"y", pixel / field.width},
          {"channel", error.function % field.channels},
          {"light", error.light}};
  }
  nlohmann::ordered_json above = nlohmann::ordered_json::object();
  for (std::size_t level = 0; level < error.functions_above.size(); ++level) {
    char name[16];
    std::snprintf(name, sizeof name, "%g", per_light_error_levels[level]);
    above[name] = error.functions_above[level];
  }
  return {{"largest_relative", error.largest},
          {"largest_at", at},
          {"mean_of_function_largest", error.mean_of_largest},
          {"share_of_functions_above", above},
          {"functions_measured", error.functions_measured},
          {"zero_peak_skipped", error.zero_peak_skipped},
          {"negative_values", error.negative_values},
          {"values_measured", error.values_measured},
          {"most_negative_relative", error.most_negative}};
}

}  // namespace

std::uint64_t peak_memory_bytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return std::uint64_t(usage.ru_maxrss) * 1024;  // Linux reports kilobytes
}

namespace {

// The noise model the run used (noise_model.hpp).
nlohmann::ordered_json noise_json(const NoiseModel& noise) {
  return {{"estimated", noise.estimated},
          {"sigma", noise.sigma},
          {"dark_threshold", noise.threshold},
          {"dark_threshold_sigmas", noise.estimated ? dark_threshold_sigmas : 0.0f}};
}

}  // namespace

nlohmann::ordered_json compression_parameters(const CompressionOptions& options,
                                              const CompressionStats& stats,
                                              const std::string& solver) {
  const ClusteringOptions& clustering = options.clustering;
  if (stats.one_basis)
    return {{"model", "one_basis"},
            {"clusters", 1},
            {"terms", clustering.terms},
            {"basis",
             "the leading right singular vectors of the stored functions, integers of at "
             "most 12 bits with one step per term"},
            {"weights", "JPEG 2000 planes, coded to the rate target's bytes"}};
  return {{"model", "clustered"},
          {"method", to_string(options.method)},
          {"clusters_asked", clustering.clusters},
          {"clusters", stats.clusters},
          {"terms", clustering.terms},
          {"residual", options.residual.describe()},
          {"residual_entries", stats.residual_entries},
          {"residual_allocation", to_string(options.residual_allocation)},
          {"residual_threshold", stats.residual_threshold},
          {"noise", noise_json(stats.noise)},
          {"transform", options.transform == BasisTransform::haar ? "haar" : "identity"},
          {"light_weighting", options.light_weighting},
          {"channel_clusters", stats.shared_pixel_clusters ? "shared" : "separate"},
          {"solver", solver},
          {"multires_levels", options.multires_levels},
          {"refine_iterations", options.refine_iterations},
          {"max_iterations", clustering.max_iterations},
          {"candidates", clustering.candidates},
          {"min_cluster_size", clustering.sizes.minimum_for(clustering.terms)},
          {"max_cluster_size", clustering.sizes.maximum},
          {"seed", clustering.seed},
          {"pca_centering", to_string(options.pca.centering)},  // cpca, and the refit's choice
          {"pca_iterations", options.pca.iterations},
          {"trimmed_refit_rounds", options.trimmed_refit_rounds},
          {"refit_chooses_clusters", options.refit_chooses_clusters}};
}

nlohmann::ordered_json compression_report(const CompressionReportInputs& run) {
  const CompressedField& compressed = *run.compressed;
  const CompressionStats& stats = *run.stats;
  const FieldErrors& errors = run.errors;
  nlohmann::ordered_json by_prefix = nlohmann::ordered_json::object();
  for (const auto& [cap, error] : errors.masked_by_prefix)
    by_prefix[std::to_string(cap)] = error.mean;
  by_prefix[std::to_string(stats.residual_entries)] = errors.masked.mean;

  const std::uint64_t input_bytes =
      std::uint64_t(compressed.functions()) * std::uint64_t(compressed.lights) * 4;
  nlohmann::ordered_json sections = nlohmann::ordered_json::object();
  sections["preamble"] = run.layout.preamble_bytes;
  for (const ContainerSection& section : run.layout.sections)
    sections[section.name] = section.bytes;
  nlohmann::ordered_json sparseness = nlohmann::ordered_json::array();
  for (std::size_t level = 0; level < stats.sparseness.size(); ++level)
    sparseness.push_back({{"threshold_relative_to_norm", sparseness_thresholds[level]},
                          {"fraction_at_or_below", stats.sparseness[level]}});

  nlohmann::ordered_json phases = {{"prepare", stats.prepare_seconds},
                                   {"clustering", stats.clustering_seconds},
                                   {"residual", stats.residual_seconds}};
  for (const auto& [name, seconds] : run.extra_seconds) phases[name] = seconds;

  nlohmann::ordered_json report = {
      {"input", run.input},
      {"output", run.output},
      {"seconds", run.total_seconds},
      {"bytes", run.layout.file_bytes},
      {"ratio", double(run.layout.file_bytes) / double(input_bytes)},
      {"error_all", errors.all.mean},
      {"error_masked", errors.masked.mean},
      {"psnr_8bit",
       {{"whole_frame", finite_or_null(errors.psnr.whole_frame)},
        {"mask", finite_or_null(errors.psnr.masked)},
        {"white", run.psnr_white}}},
      {"bytes_per_pixel",
       double(run.layout.file_bytes) / (double(compressed.width) * double(compressed.height))},
      {"float32_input_bytes", input_bytes},
      {"sections", sections},
      {"error_masked_by_residual_entries", by_prefix},
      {"per_light_error_masked", per_light_error_json(errors.per_light, compressed)},
      {"error_all_detail", error_json(errors.all)},
      {"error_masked_detail", error_json(errors.masked)},
      {"field",
       {{"width", compressed.width},
        {"height", compressed.height},
        {"channels", compressed.channels},
        {"lights", compressed.lights},
        {"functions", stats.functions},
        {"stored_rows", stats.stored_rows},
        {"outside_mask", stats.outside_mask},
        {"all_zero", stats.all_zero},
        {"dark_pixels", stats.dark_pixels}}},
      {"parameters", compression_parameters(*run.options, stats, run.solver)},
      {"residual_nonzeros", stats.residual_nonzeros},
      {"sparseness", sparseness},
      {"phases_seconds", phases},
      {"clustering", clustering_json(stats.clustering)},
      {"threads", run.threads},
      {"assignment_device", run.assignment_device},
      {"peak_memory_bytes", peak_memory_bytes()}};
  if (stats.multires) {
    const MultiresTrace& multires = *stats.multires;
    report["multires"] = {{"levels", multires.levels},
                          {"low_width", multires.low_width},
                          {"low_height", multires.low_height},
                          {"low_rows", multires.low_rows},
                          {"downsample_seconds", multires.downsample_seconds},
                          {"low_clustering", clustering_json(multires.low)},
                          {"full_assignment_seconds", multires.assignment_seconds},
                          {"mean_pool_size", multires.mean_pool_size}};
  }
  if (stats.trimmed_refit) {
    const TrimmedRefitTrace& refit = *stats.trimmed_refit;
    report["trimmed_refit"] = {
        {"entries", stats.residual_entries},
        {"objective_before_choice", refit.objective_before_choice
                                        ? nlohmann::ordered_json(*refit.objective_before_choice)
                                        : nlohmann::ordered_json()},
        {"objective_before", refit.objective_before},
        {"objective_after", refit.objective_after},
        {"rows_changed", refit.changed},
        {"clusters_removed", refit.clusters_removed},
        {"seconds", refit.seconds}};
  }
  return report;
}

}  // namespace relume
