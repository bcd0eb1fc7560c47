// Implementation of the run report's plan, streamed, precision and summary parts.
#include "compress/run_report_sections.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "container/container.hpp"
#include "container/container_sections.hpp"
#include "core/ranks.hpp"

namespace relume {

nlohmann::ordered_json plan_json(const CompressionPlan& plan) {
  nlohmann::ordered_json json = {{"streamed", plan.streamed},
                                 {"ranks", process_ranks().size()},
                                 {"budget_bytes", plan.budget},
                                 {"budget_source", plan.budget_source},
                                 {"field_bytes", plan.field_bytes},
                                 {"in_memory_bytes", plan.in_memory_bytes},
                                 {"resident_bytes_at_plan", plan.resident_bytes}};
  if (plan.streamed) {
    json["strip_rows"] = plan.strip_rows;
    json["sample_rows"] = plan.sample_rows;
    json["quantization_rows"] = plan.quantization_rows;
    json["model_bytes"] = plan.model_bytes;
    json["scratch_bytes_at_most"] = plan.scratch_bytes;
    json["scratch_folder"] = plan.scratch_folder.string();
    json["compressed_on_disk"] = plan.compressed_on_disk;
  }
  return json;
}

nlohmann::ordered_json streamed_json(const StreamedTrace& trace) {
  nlohmann::ordered_json passes = nlohmann::ordered_json::array();
  for (const StreamedPass& pass : trace.passes)
    passes.push_back({{"pass", pass.pass},
                      {"l1_objective", pass.objective},
                      {"changed", pass.changed},
                      {"seconds", pass.seconds}});
  return {{"strips", trace.strips},
          {"rank_stored_functions", trace.rank_stored_rows},
          {"rank_compute_seconds", trace.rank_compute_seconds},
          {"rank_bytes_sent", trace.rank_bytes_sent},
          {"rank_build_seconds", trace.rank_build_seconds},
          {"sample_rows", trace.sample_rows},
          {"sample_clustering_threads", trace.sample_clustering_threads},
          {"sample_clustering_cores", trace.sample_clustering_cores},
          {"scratch_bytes", trace.scratch_bytes},
          {"passes", passes},
          {"seconds",
           {{"read", trace.read_seconds},
            {"sample_clustering", trace.sample_clustering_seconds},
            {"refine", trace.refine_seconds},
            {"build", trace.build_seconds}}}};
}

nlohmann::ordered_json precision_cost_json(const nlohmann::ordered_json& report,
                                           const CompressedField& stored,
                                           const ContainerOptions& container,
                                           const StoragePrecision& precision,
                                           const std::optional<QuantizationChoice>& quantization,
                                           double error_masked_float32, double quantization_error) {
  nlohmann::ordered_json cost = {
      {"weights", to_string(stored_weight_precision(stored, container))},
      {"residual_values", to_string(stored_residual_precision(stored, container))},
      {"basis_bits", stored.quantization.basis_bits},
      {"error_masked_stored", report["error_masked"]},
      {"error_masked_float32", error_masked_float32}};
  if (!std::isnan(quantization_error)) cost["quantization_error"] = quantization_error;
  if (quantization)
    cost["quantization"] = {{"budget", precision.budget},
                            {"weight_step", quantization->steps.weight_step},
                            {"residual_step", quantization->steps.residual_step},
                            {"basis_bits", quantization->steps.basis_bits},
                            {"sample_error_unquantized", quantization->error_unquantized},
                            {"sample_error_quantized", quantization->error_quantized}};
  if (quantization && !quantization->cluster_terms.empty())
    cost["terms_per_cluster"] = {{"budget", precision.term_budget},
                                 {"error_all_terms", quantization->error_all_terms},
                                 {"terms", quantization->cluster_terms}};
  return cost;
}

namespace {

// "N clusters", and when fewer than asked, why: the size rules merged clusters of too few
// functions (--clusters 2048 ending with 243 said nothing), or fewer functions than clusters.
std::string clusters_text(const nlohmann::ordered_json& report, int clusters) {
  const nlohmann::ordered_json& parameters = report["parameters"];
  const int asked = parameters.value("clusters_asked", clusters);
  std::string text = std::to_string(clusters) + " clusters";
  if (clusters >= asked) return text;
  long long merged = 0;
  const auto count_merged = [&](const nlohmann::ordered_json& clustering) {
    if (clustering.contains("iterations"))
      for (const auto& iteration : clustering["iterations"])
        merged += iteration.value("merged", 0LL);
  };
  if (report.contains("clustering")) count_merged(report["clustering"]);
  if (report.contains("multires")) count_merged(report["multires"]["low_clustering"]);
  text += " of the " + std::to_string(asked) + " asked";
  if (merged > 0)
    text += " (" + std::to_string(merged) + " merged into others for having fewer than " +
            std::to_string(parameters.value("min_cluster_size", 0)) + " functions)";
  else if (report["field"].value("stored_rows", std::int64_t(asked)) < asked)
    text += " (only " + std::to_string(report["field"]["stored_rows"].get<std::int64_t>()) +
            " functions are stored)";
  return text;
}

// The model stored: its clusters, or the one basis and its terms.
std::string model_text(const nlohmann::ordered_json& report, int clusters) {
  const nlohmann::ordered_json& parameters = report["parameters"];
  if (parameters.value("model", "") == "one_basis")
    return "one basis of " + std::to_string(parameters["terms"].get<int>()) +
           " terms, weights as JPEG 2000 planes";
  return clusters_text(report, clusters);
}

}  // namespace

std::string summary_line(const nlohmann::ordered_json& report, int clusters) {
  char error[200];
  const auto outside = report["field"]["outside_mask"].get<std::int64_t>();
  if (outside == 0)
    std::snprintf(error, sizeof error, "error %.5f", report["error_masked"].get<double>());
  else
    std::snprintf(error, sizeof error,
                  "error %.5f over the stored object (whole frame %.5f: %lld background "
                  "functions not stored)",
                  report["error_masked"].get<double>(), report["error_all"].get<double>(),
                  static_cast<long long>(outside));
  // The clustered model's dark pixels and the noise floor that chose them (the one-basis model
  // has neither).
  std::string dark;
  const nlohmann::ordered_json& parameters = report["parameters"];
  if (parameters.contains("noise")) {
    const nlohmann::ordered_json& noise = parameters["noise"];
    std::string thresholds;
    for (const auto& t : noise["dark_threshold"]) {
      char value[32];
      std::snprintf(value, sizeof value, "%s%.3g", thresholds.empty() ? "" : "/", t.get<double>());
      thresholds += value;
    }
    char text[200];
    std::snprintf(text, sizeof text, ", %lld dark pixels (noise floor %s, %s)",
                  static_cast<long long>(report["field"]["dark_pixels"].get<std::int64_t>()),
                  thresholds.c_str(), noise["estimated"].get<bool>() ? "estimated" : "given");
    dark = text;
  }
  const nlohmann::ordered_json& per_light = report["per_light_error_masked"];
  const std::string output = report["output"].get<std::string>();
  char line[1024];
  std::snprintf(
      line, sizeof line,
      "compressed %s -> %s: %llu bytes (%.3g B/px, 1/%.0f of float32), %s, largest per-light error "
      "%.3g of its function's peak, %lld negative values, %s%s, %.1f s",
      report["input"].get<std::string>().c_str(), output.empty() ? "memory" : output.c_str(),
      static_cast<unsigned long long>(report["bytes"].get<std::uint64_t>()),
      report["bytes_per_pixel"].get<double>(), 1 / report["ratio"].get<double>(), error,
      per_light["largest_relative"].get<double>(),
      static_cast<long long>(per_light["negative_values"].get<std::int64_t>()),
      model_text(report, clusters).c_str(), dark.c_str(), report["seconds"].get<double>());
  return line;
}

}  // namespace relume
