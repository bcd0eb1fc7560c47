// Implementation of the evaluation of one field (see evaluation.hpp).
#include "eval/evaluation.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <relume/error.hpp>

#include "compress/clustered_factorization.hpp"
#include "compress/opencl_assignment.hpp"
#include "compress/storage_precision.hpp"
#include "container/container.hpp"
#include "core/progress.hpp"

namespace relume {
namespace {

// A run's errors at every cap it is measured at (l1-refit: its budget; the others: every cap of
// entries and compare_entries).
struct RunErrors {
  std::vector<int> caps;
  Eigen::MatrixXd errors;  // stored rows x caps
};

// The column of `run.errors` with `cap` entries, or none where it was not measured at `cap`.
std::optional<Eigen::Index> column_of(const RunErrors& run, int cap) {
  const auto at = std::find(run.caps.begin(), run.caps.end(), cap);
  if (at == run.caps.end()) return std::nullopt;
  return at - run.caps.begin();
}

// The means of `run`'s errors with `cap` entries, or none where it was not measured at `cap`.
std::optional<SubsetErrors> errors_at(const RunErrors& run, int cap,
                                      const FunctionClasses& classes) {
  const std::optional<Eigen::Index> at = column_of(run, cap);
  if (!at) return std::nullopt;
  const Eigen::Index column = *at;
  double all = 0, diffuse = 0, specular = 0;
  for (Eigen::Index r = 0; r < run.errors.rows(); ++r) {
    const double value = run.errors(r, column);
    all += value;
    (classes.diffuse[static_cast<std::size_t>(r)] ? diffuse : specular) += value;
  }
  const std::size_t rows = static_cast<std::size_t>(run.errors.rows());
  const std::size_t specular_count = rows - classes.diffuse_count;
  SubsetErrors out;
  out.all = rows ? all / double(rows) : 0.0;
  if (classes.diffuse_count) out.diffuse = diffuse / double(classes.diffuse_count);
  if (specular_count) out.specular = specular / double(specular_count);
  return out;
}

std::optional<std::size_t> find_run(const std::vector<EvalRun>& runs, const std::string& method,
                                    int clusters, int terms, int budget = -1) {
  for (std::size_t i = 0; i < runs.size(); ++i)
    if (runs[i].method == method && runs[i].clusters_asked == clusters && runs[i].terms == terms &&
        runs[i].budget == budget)
      return i;
  return std::nullopt;
}

// The caps the runs with their full residual are measured and relit at: entries and
// compare_entries, ascending.
std::vector<int> measured_caps(const EvaluationOptions& options) {
  std::vector<int> caps = options.entries;
  caps.push_back(options.compare_entries);
  std::sort(caps.begin(), caps.end());
  caps.erase(std::unique(caps.begin(), caps.end()), caps.end());
  return caps;
}

bool is_primary(const EvaluationOptions& options, const EvalRun& run) {
  return run.clusters_asked == options.primary_clusters && run.terms == options.primary_terms;
}

// The per-pixel mean over a pixel's stored functions of `a - b` (NaN where none is stored).
Eigen::MatrixXd pixel_difference(const ReflectanceField& field, const PreparedRows& prepared,
                                 const Eigen::VectorXd& a, const Eigen::VectorXd& b) {
  Eigen::MatrixXd sum = Eigen::MatrixXd::Zero(field.height, field.width);
  Eigen::MatrixXi count = Eigen::MatrixXi::Zero(field.height, field.width);
  for (std::size_t r = 0; r < prepared.functions.size(); ++r) {
    const std::int64_t pixel = prepared.functions[r] / field.channels;
    const int y = static_cast<int>(pixel / field.width), x = static_cast<int>(pixel % field.width);
    sum(y, x) += a[static_cast<Eigen::Index>(r)] - b[static_cast<Eigen::Index>(r)];
    ++count(y, x);
  }
  for (Eigen::Index y = 0; y < sum.rows(); ++y)
    for (Eigen::Index x = 0; x < sum.cols(); ++x)
      sum(y, x) = count(y, x) ? sum(y, x) / count(y, x) : NAN;
  return sum;
}

std::vector<EvalRun> run_compressions(const WorkingRows& rows, const EvaluationOptions& options,
                                      std::string& assignment) {
  EvalGrid grid;
  grid.clusters = options.clusters;
  grid.terms = options.terms;
  grid.refit_entries = options.refit_entries;
  grid.refit_rounds = options.refit_rounds;
  grid.methods = options.methods;
  grid.clustering.seed = options.seed;
  grid.clustering.threads = options.threads;
  grid.clustering.quiet = true;
  grid.pca.iterations = options.pca_iterations;
  const std::unique_ptr<OpenClAssigner> opencl =
      make_assigner(options.assign, options.device, grid.clustering);
  if (opencl) grid.clustering.assign = opencl->function();
  assignment = opencl ? opencl->device_label() : "cpu";
  return run_grid(rows, grid, options.on_run);
}

// Every run's row errors at its caps, and the sparseness of the full residuals (Fig. 4d).
std::vector<RunErrors> measure_runs(EvaluationResult& result, const WorkingRows& rows) {
  const EvaluationOptions& options = result.settings;
  const std::vector<int> caps = measured_caps(options);
  std::vector<double> thresholds;
  for (int k = 0; k <= 24; ++k) thresholds.push_back(std::pow(10.0, -4.0 + k / 6.0));
  std::vector<RunErrors> measured;
  ProgressReporter progress("eval: measuring errors", result.runs.size(), true);
  for (std::size_t i = 0; i < result.runs.size(); ++i) {
    const EvalRun& run = result.runs[i];
    RunErrors m;
    m.caps = run.budget >= 0 ? std::vector<int>{run.budget} : caps;
    m.errors = row_errors(rows, run.model, m.caps, options.threads);
    measured.push_back(std::move(m));
    if (run.budget < 0) {
      const std::vector<double> fractions =
          residual_sparseness(rows, run.model, thresholds, options.threads);
      for (std::size_t t = 0; t < thresholds.size(); ++t)
        result.sparseness.push_back({i, thresholds[t], fractions[t]});
    }
    progress.advance();
  }
  progress.finish();
  return measured;
}

// Fig. 4 a-c and Fig. 5, and each configuration's headline errors.
void tabulate_errors(EvaluationResult& result, const std::vector<RunErrors>& measured) {
  const EvaluationOptions& options = result.settings;
  const std::vector<EvalRun>& runs = result.runs;
  const FunctionClasses& classes = result.classes;
  for (std::size_t i = 0; i < runs.size(); ++i)
    for (const int cap : measured[i].caps)
      if (runs[i].budget >= 0 ||
          std::find(options.entries.begin(), options.entries.end(), cap) != options.entries.end())
        result.errors.push_back({i, cap, *errors_at(measured[i], cap, classes)});
  const auto ratio = [](double baseline, double method) {
    return method > 0 ? baseline / method : NAN;
  };
  const auto method_errors = [&](int clusters, int terms, int entries) {
    MethodErrors at{entries, {}};
    for (const std::string& method : evaluation_methods) {
      const auto run = find_run(runs, method, clusters, terms, method == "l1-refit" ? entries : -1);
      if (!run) continue;
      if (const auto e = errors_at(measured[*run], entries, classes))
        at.errors.emplace_back(method, e->all);
    }
    return at;
  };
  for (const int clusters : options.clusters)
    for (const int terms : options.terms) {
      const RunErrors& cpca = measured[*find_run(runs, "cpca", clusters, terms)];
      const RunErrors& l1 = measured[*find_run(runs, "l1", clusters, terms)];
      for (const int entries : options.entries) {
        const SubsetErrors base = *errors_at(cpca, entries, classes);
        const auto add = [&](const std::string& method, const SubsetErrors& e) {
          result.ratios.push_back({clusters,
                                   terms,
                                   entries,
                                   method,
                                   {ratio(base.all, e.all), ratio(base.diffuse, e.diffuse),
                                    ratio(base.specular, e.specular)}});
        };
        add("l1", *errors_at(l1, entries, classes));
        if (const auto refit = find_run(runs, "l1-refit", clusters, terms, entries))
          add("l1-refit", *errors_at(measured[*refit], entries, classes));
      }
      result.configurations.push_back({clusters, terms, method_errors(clusters, terms, 0),
                                       method_errors(clusters, terms, options.compare_entries)});
    }
}

// Fig. 6: the primary configuration's per-pixel error difference.
ErrorDifference difference_per_pixel(const EvaluationResult& result,
                                     const std::vector<RunErrors>& measured,
                                     const ReflectanceField& field, const PreparedRows& prepared) {
  const EvaluationOptions& options = result.settings;
  const int clusters = options.primary_clusters, terms = options.primary_terms;
  const auto column = [&](std::size_t run, int cap) {
    return measured[run].errors.col(*column_of(measured[run], cap));
  };
  const Eigen::VectorXd cpca =
      column(*find_run(result.runs, "cpca", clusters, terms), options.compare_entries);
  ErrorDifference difference;
  difference.l1 = pixel_difference(
      field, prepared, cpca,
      column(*find_run(result.runs, "l1", clusters, terms), options.compare_entries));
  if (const auto refit =
          find_run(result.runs, "l1-refit", clusters, terms, options.compare_entries))
    difference.l1_refit =
        pixel_difference(field, prepared, cpca, column(*refit, options.compare_entries));
  for (Eigen::Index v = 0; v < difference.l1.size(); ++v) {
    if (std::isnan(difference.l1.data()[v])) continue;
    ++difference.pixels;
    difference.l1_better += difference.l1.data()[v] > 0;
  }
  return difference;
}

// Rate against distortion, as stored; returns the stored fields of the primary configuration
// that are relit: l1 and cpca with their longest cap, l1-refit with compare_entries.
std::map<std::string, CompressedField> store_containers(EvaluationResult& result,
                                                        const ReflectanceField& field,
                                                        const PreparedRows& prepared) {
  const EvaluationOptions& options = result.settings;
  StoragePrecision precision;
  precision.budget = options.quantization_budget;
  precision.threads = options.threads;
  const ContainerOptions container = precision.container_options();
  std::size_t points = 0;
  for (const EvalRun& run : result.runs)
    points += run.budget >= 0 ? 1 : options.rate_entries.size();
  ProgressReporter progress("eval: storing containers", points, options.quiet);
  const int longest = measured_caps(options).back();
  std::map<std::string, CompressedField> primary_fields;
  const auto store = [&](const EvalRun& run, int entries) {
    CompressionStats stats;
    CompressedField stored =
        build_compressed_field(field, prepared, run.model, BasisTransform::identity, entries,
                               result.residual_threshold, {}, stats, options.threads);
    store_with_precision(field, stored, precision);
    return stored;
  };
  for (std::size_t i = 0; i < result.runs.size(); ++i) {
    const EvalRun& run = result.runs[i];
    const std::vector<int> budgets =
        run.budget >= 0 ? std::vector<int>{run.budget} : options.rate_entries;
    for (const int entries : budgets) {
      const CompressedField stored = store(run, entries);
      const std::uint64_t bytes = plan_container(stored, container).file_bytes;
      RatePoint point;
      point.run = i;
      point.entries = entries;
      point.bytes = bytes;
      point.bytes_per_pixel = double(bytes) / double(field.pixels());
      point.ratio = double(bytes) / (double(field.functions()) * field.lights() * 4);
      point.error_masked =
          relative_error(field, stored, true, all_residual_entries, options.threads).mean;
      point.psnr =
          psnr_8bit(field, stored, options.psnr_white, all_residual_entries, options.threads);
      result.rate.push_back(point);
      progress.advance();
    }
    if (is_primary(options, run)) {
      if (run.budget < 0 && run.method != "cpca-mean")
        primary_fields[run.method] = store(run, longest);
      else if (run.budget == options.compare_entries)
        primary_fields["l1-refit"] = store(run, run.budget);
    }
  }
  progress.finish();
  return primary_fields;
}

// Table 1 and the relit images.
RelightingResult relight(const EvaluationOptions& options, const ReflectanceField& field,
                         const EnvironmentMap& map,
                         std::map<std::string, CompressedField>& primary_fields) {
  RelightingSetup setup;
  setup.original = &field;
  setup.map = &map;
  setup.rotate_degrees = options.rotate_degrees;
  setup.frames = options.frames;
  setup.timed_calls = options.timed_calls;
  setup.caps = measured_caps(options);
  setup.image_cap = options.compare_entries;
  setup.device = options.device;
  setup.threads = options.threads;
  setup.on_row = options.on_relit;
  RelightingResult relit =
      measure_relighting({{"l1", &primary_fields["l1"]}, {"cpca", &primary_fields["cpca"]}}, setup);
  if (primary_fields.count("l1-refit")) {
    RelightingSetup once = setup;
    once.caps = {options.compare_entries};
    once.frames = 1;
    once.timed_calls = 1;
    const RelightingResult refit_relit =
        measure_relighting({{"l1-refit", &primary_fields["l1-refit"]}}, once);
    relit.images.insert(relit.images.end(), refit_relit.images.begin(), refit_relit.images.end());
  }
  return relit;
}

}  // namespace

EvaluationResult evaluate_field(const ReflectanceField& field, const EnvironmentMap& map,
                                const EvaluationOptions& asked) {
  const ProgressListenerScope listening(asked.progress);
  EvaluationResult result;
  result.settings = resolve_evaluation_options(asked);
  const EvaluationOptions& options = result.settings;
  for (const int terms : options.terms)
    if (terms > max_cluster_terms || terms >= field.lights())
      throw Error("--terms " + std::to_string(terms) + " (expected 1 to " +
                  std::to_string(std::min(max_cluster_terms, field.lights() - 1)) + " for " +
                  std::to_string(field.lights()) + " lights)");
  result.noise = estimate_noise(field, options.threads);
  result.residual_threshold = default_residual_threshold(result.noise, field);
  const PreparedRows prepared = prepare_rows(field, false, result.noise, options.threads);
  if (prepared.functions.empty())
    throw Error("the field has no function to evaluate (all are outside the mask or zero)");
  result.stored_functions = prepared.functions.size();
  result.dark_pixels = prepared.dark_pixels.size();
  result.classes =
      classify_functions(field, prepared.functions, options.diffuse_threshold, options.threads);
  if (options.on_classes) options.on_classes(result.stored_functions, result.classes);

  result.runs = run_compressions(prepared.rows, options, result.assignment);
  const std::vector<RunErrors> measured = measure_runs(result, prepared.rows);
  tabulate_errors(result, measured);
  result.difference = difference_per_pixel(result, measured, field, prepared);
  std::map<std::string, CompressedField> primary_fields = store_containers(result, field, prepared);
  result.relighting = relight(options, field, map, primary_fields);
  return result;
}

}  // namespace relume
