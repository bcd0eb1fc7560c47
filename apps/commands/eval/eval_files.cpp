// Implementation of writing the eval's tables, maps and images (see eval_files.hpp).
#include "commands/eval/eval_files.hpp"

#include "commands/eval/csv_table.hpp"
#include "field/npy.hpp"
#include "image/image_difference.hpp"

namespace relume {
namespace {

namespace fs = std::filesystem;

std::string refit_for(const EvalRun& run) {
  return run.budget >= 0 ? std::to_string(run.budget) : std::string();
}

// Fig. 4 a-c.
CsvTable error_table(const EvaluationResult& result) {
  CsvTable errors({"method", "clusters", "terms", "clusters_used", "refit_for", "entries",
                   "error_all", "error_diffuse", "error_specular"});
  for (const ErrorPoint& point : result.errors) {
    const EvalRun& run = result.runs[point.run];
    errors.row()
        .cell(run.method)
        .cell(run.clusters_asked)
        .cell(run.terms)
        .cell(run.model.clusters)
        .cell(refit_for(run))
        .cell(point.entries)
        .cell(point.error.all)
        .cell(point.error.diffuse)
        .cell(point.error.specular);
  }
  return errors;
}

// Fig. 5.
CsvTable ratio_table(const EvaluationResult& result) {
  CsvTable ratios(
      {"clusters", "terms", "entries", "method", "ratio_all", "ratio_diffuse", "ratio_specular"});
  for (const ErrorRatio& ratio : result.ratios)
    ratios.row()
        .cell(ratio.clusters)
        .cell(ratio.terms)
        .cell(ratio.entries)
        .cell(ratio.method)
        .cell(ratio.ratio.all)
        .cell(ratio.ratio.diffuse)
        .cell(ratio.ratio.specular);
  return ratios;
}

// Fig. 4d.
CsvTable sparseness_table(const EvaluationResult& result) {
  CsvTable sparseness({"method", "clusters", "terms", "threshold", "fraction_at_or_below"});
  for (const SparsenessPoint& point : result.sparseness) {
    const EvalRun& run = result.runs[point.run];
    sparseness.row()
        .cell(run.method)
        .cell(run.clusters_asked)
        .cell(run.terms)
        .cell(point.threshold)
        .cell(point.fraction);
  }
  return sparseness;
}

CsvTable rate_table(const EvaluationResult& result) {
  CsvTable rate({"method", "clusters", "terms", "entries", "bytes", "bytes_per_pixel", "ratio",
                 "error_masked", "psnr_mask", "psnr_frame"});
  for (const RatePoint& point : result.rate) {
    const EvalRun& run = result.runs[point.run];
    rate.row()
        .cell(run.method)
        .cell(run.clusters_asked)
        .cell(run.terms)
        .cell(point.entries)
        .cell(static_cast<long long>(point.bytes))
        .cell(point.bytes_per_pixel)
        .cell(point.ratio)
        .cell(point.error_masked)
        .cell(point.psnr.masked)
        .cell(point.psnr.whole_frame);
  }
  return rate;
}

// Table 1.
CsvTable relighting_table(const EvaluationResult& result) {
  const EvaluationOptions& settings = result.settings;
  CsvTable relighting({"method", "clusters", "terms", "cap", "frames", "frames_per_second",
                       "kernel_ms", "relit_error", "error_masked", "device"});
  for (const RelightingRow& row : result.relighting.rows)
    relighting.row()
        .cell(row.method)
        .cell(settings.primary_clusters)
        .cell(settings.primary_terms)
        .cell(row.cap)
        .cell(settings.frames)
        .cell(row.frames_per_second)
        .cell(row.kernel_ms)
        .cell(row.relit_error)
        .cell(row.error_masked)
        .cell(result.relighting.device);
  return relighting;
}

CsvTable time_table(const EvaluationResult& result) {
  CsvTable times({"method", "clusters", "terms", "refit_for", "seconds", "refit_seconds",
                  "iterations", "clusters_used"});
  for (const EvalRun& run : result.runs)
    times.row()
        .cell(run.method)
        .cell(run.clusters_asked)
        .cell(run.terms)
        .cell(refit_for(run))
        .cell(run.seconds)
        .cell(run.refit_seconds)
        .cell(run.iterations)
        .cell(run.model.clusters);
  return times;
}

}  // namespace

EvalFiles write_eval_files(const fs::path& directory, const EvaluationResult& result,
                           const ImageWriteOptions& images) {
  EvalFiles files;
  const std::pair<std::string, CsvTable> tables[] = {
      {"error_vs_entries.csv", error_table(result)}, {"error_ratio.csv", ratio_table(result)},
      {"sparseness.csv", sparseness_table(result)},  {"rate_distortion.csv", rate_table(result)},
      {"relighting.csv", relighting_table(result)},  {"compression_time.csv", time_table(result)}};
  for (const auto& [name, table] : tables) {
    table.write(directory / name);
    files.csv.push_back(name);
  }

  write_npy_matrix(directory / "error_difference.npy", result.difference.l1, NpyDtype::float32);
  files.npy = {"error_difference.npy"};
  if (result.difference.l1_refit.size()) {
    write_npy_matrix(directory / "error_difference_refit.npy", result.difference.l1_refit,
                     NpyDtype::float32);
    files.npy.push_back("error_difference_refit.npy");
  }

  const RelightingResult& relit = result.relighting;
  files.reference = "relit_reference.png";
  write_image(directory / files.reference, relit.reference, images);
  files.relit = files.difference10 = nlohmann::ordered_json::object();
  for (const auto& [method, image] : relit.images) {
    const std::string name = "relit_" + method + ".png", diff = "difference10_" + method + ".png";
    write_image(directory / name, image, images);
    write_image(directory / diff, scaled_difference(image, relit.reference, 10.0f), images);
    files.relit[method] = name;
    files.difference10[method] = diff;
  }
  return files;
}

}  // namespace relume
