// `relume eval`: the paper's results reproduced on one field, relume against clustered PCA, with
// every knob swept: for a grid of (clusters, terms) the L1 method, clustered PCA (two forms) and
// the L1 method refitted for small residual budgets are made on the same rows; their Eq. 16
// error against residual entries (all functions and two subsets), the ratio of the methods'
// errors, the residual's sparseness, a per-pixel error difference, relighting speed and error per
// residual cap (OpenCL), rate against distortion as the containers store it, compression times
// and relit images go to CSV, NPY, PNG and one JSON summary (apps/commands/eval/ holds the parts;
// scripts/plot_eval.py draws the plots).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <relume/error.hpp>
#include <relume/field.hpp>
#include <relume/lighting.hpp>
#include <sstream>

#include "command_registry.hpp"
#include "compress/clustered_factorization.hpp"
#include "compress/opencl_assignment.hpp"
#include "compress/storage_precision.hpp"
#include "container/container.hpp"
#include "core/console.hpp"
#include "core/elapsed_time.hpp"
#include "core/progress.hpp"
#include "commands/eval/csv_table.hpp"
#include "commands/eval/eval_plots.hpp"
#include "commands/eval/eval_relighting.hpp"
#include "commands/eval/eval_runs.hpp"
#include "commands/eval/function_classes.hpp"
#include "field/npy.hpp"
#include "options/json_report.hpp"
#include "lighting/environment_map.hpp"
#include "model/field_psnr.hpp"

namespace relume {
namespace {

namespace fs = std::filesystem;

const std::vector<std::string> known_methods = {"l1", "cpca", "cpca-mean", "l1-refit"};

struct EvalArguments {
  std::string input, output;
  std::vector<int> clusters{32, 64}, terms{2, 4};
  std::vector<int> entries{0, 1, 2, 3, 5, 10, 20};
  std::vector<int> refit_entries{0, 1, 2, 3, 5};
  std::vector<int> rate_entries;  // empty: --entries
  std::vector<std::string> methods = known_methods;
  std::string primary;  // "KxT"; empty: the last clusters and terms of the grid
  int compare_entries = 5;
  int refit_rounds = 2;
  int pca_iterations = ClusteredPcaOptions{}.iterations;
  std::string environment, layout = "auto";
  double rotate = 0, exposure = 0;
  int frames = 8;
  int timed_calls = RelightingSetup{}.timed_calls;
  std::string device, assign = "opencl";
  double diffuse_threshold = 0.02;
  double psnr_white = 1.0;
  double quantization_budget = QuantizationBudget{}.relative_increase;
  std::uint64_t seed = 1;
  unsigned threads = 0;
  bool no_plots = false;
};

// Ascending, without repeats; throws Error naming `option` for a value below `minimum`.
std::vector<int> sorted_list(std::vector<int> values, const std::string& option, int minimum) {
  if (values.empty()) throw Error(option + " needs at least one value");
  for (const int value : values)
    if (value < minimum)
      throw Error(option + " value " + std::to_string(value) +
                  " (expected >= " + std::to_string(minimum) + ")");
  std::sort(values.begin(), values.end());
  values.erase(std::unique(values.begin(), values.end()), values.end());
  return values;
}

bool has_method(const EvalArguments& arguments, const std::string& method) {
  return std::find(arguments.methods.begin(), arguments.methods.end(), method) !=
         arguments.methods.end();
}

// Mean of one column of `errors` over all rows and over each class of rows.
struct SubsetErrors {
  double all = 0, diffuse = NAN, specular = NAN;
};

SubsetErrors subset_means(const Eigen::MatrixXd& errors, Eigen::Index column,
                          const FunctionClasses& classes) {
  double all = 0, diffuse = 0, specular = 0;
  for (Eigen::Index r = 0; r < errors.rows(); ++r) {
    const double value = errors(r, column);
    all += value;
    (classes.diffuse[static_cast<std::size_t>(r)] ? diffuse : specular) += value;
  }
  const std::size_t rows = static_cast<std::size_t>(errors.rows());
  const std::size_t specular_count = rows - classes.diffuse_count;
  SubsetErrors out;
  out.all = rows ? all / double(rows) : 0.0;
  if (classes.diffuse_count) out.diffuse = diffuse / double(classes.diffuse_count);
  if (specular_count) out.specular = specular / double(specular_count);
  return out;
}

// A run's errors at every cap it is measured at (dynamic runs: all caps; l1-refit: its budget).
struct MeasuredRun {
  const EvalRun* run = nullptr;
  std::vector<int> caps;
  Eigen::MatrixXd errors;  // stored rows x caps
};

const MeasuredRun* find_run(const std::vector<MeasuredRun>& measured, const std::string& method,
                            int clusters, int terms, int budget = -1) {
  for (const MeasuredRun& m : measured)
    if (m.run->method == method && m.run->clusters_asked == clusters && m.run->terms == terms &&
        m.run->budget == budget)
      return &m;
  return nullptr;
}

std::optional<double> error_at(const MeasuredRun* measured, int cap,
                               const FunctionClasses& classes) {
  if (!measured) return std::nullopt;
  const auto at = std::find(measured->caps.begin(), measured->caps.end(), cap);
  if (at == measured->caps.end()) return std::nullopt;
  return subset_means(measured->errors, at - measured->caps.begin(), classes).all;
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

EnvironmentMap evaluation_map(const EvalArguments& arguments) {
  if (arguments.environment.empty())
    return make_environment_map(render_sky({}), EnvironmentLayout::latlong, "the built-in sky");
  return load_environment_map(arguments.environment, parse_layout_option(arguments.layout));
}

void run_eval(EvalArguments& arguments) {
  const auto start = Clock::now();
  arguments.clusters = sorted_list(arguments.clusters, "--clusters", 1);
  arguments.terms = sorted_list(arguments.terms, "--terms", 1);
  arguments.entries = sorted_list(arguments.entries, "--entries", 0);
  const bool refits = has_method(arguments, "l1-refit");
  if (refits) arguments.refit_entries = sorted_list(arguments.refit_entries, "--refit-entries", 0);
  arguments.rate_entries = arguments.rate_entries.empty()
                               ? arguments.entries
                               : sorted_list(arguments.rate_entries, "--rate-entries", 0);
  for (const std::string& method : arguments.methods)
    if (std::find(known_methods.begin(), known_methods.end(), method) == known_methods.end())
      throw Error("--methods: unknown method '" + method + "' (expected l1, cpca, cpca-mean, " +
                  "l1-refit)");
  if (!has_method(arguments, "l1") || !has_method(arguments, "cpca"))
    throw Error("--methods must include l1 and cpca, the two methods every table compares");
  if (arguments.compare_entries < 0)
    throw Error("--compare-entries " + std::to_string(arguments.compare_entries) +
                " (expected >= 0)");
  if (arguments.refit_rounds < 0)
    throw Error("--refit-rounds " + std::to_string(arguments.refit_rounds) + " (expected >= 0)");
  if (arguments.frames < 1 || arguments.timed_calls < 1)
    throw Error("--frames and --timed-calls must be >= 1, got " + std::to_string(arguments.frames) +
                " and " + std::to_string(arguments.timed_calls));
  if (arguments.assign != "opencl" && arguments.assign != "cpu")
    throw Error("--assign must be 'cpu' or 'opencl', got '" + arguments.assign + "'");
  int primary_clusters = arguments.clusters.back(), primary_terms = arguments.terms.back();
  if (!arguments.primary.empty()) {
    char by = 0;
    std::istringstream text(arguments.primary);
    if (!(text >> primary_clusters >> by >> primary_terms) || by != 'x' || !text.eof() ||
        std::find(arguments.clusters.begin(), arguments.clusters.end(), primary_clusters) ==
            arguments.clusters.end() ||
        std::find(arguments.terms.begin(), arguments.terms.end(), primary_terms) ==
            arguments.terms.end())
      throw Error("--primary '" + arguments.primary +
                  "' must be CLUSTERSxTERMS of the grid (for example 64x4)");
  }
  const EnvironmentMap map = evaluation_map(arguments);  // a bad map fails before the work
  const fs::path out = arguments.output;
  fs::create_directories(out);

  FieldLoadOptions load;
  load.threads = arguments.threads;
  const ReflectanceField field = load_field(arguments.input, load);
  note("eval: %s: %dx%d, %d channels, %d lights", arguments.input.c_str(), field.width,
       field.height, field.channels, field.lights());
  for (const int terms : arguments.terms)
    if (terms > max_cluster_terms || terms >= field.lights())
      throw Error("--terms " + std::to_string(terms) + " (expected 1 to " +
                  std::to_string(std::min(max_cluster_terms, field.lights() - 1)) + " for " +
                  std::to_string(field.lights()) + " lights)");
  const PreparedRows prepared = prepare_rows(field, false, field.noise_floor, arguments.threads);
  if (prepared.functions.empty())
    throw Error(arguments.input + ": no function to evaluate (all are outside the mask or zero)");
  const FunctionClasses classes =
      classify_functions(field, prepared.functions, arguments.diffuse_threshold, arguments.threads);
  note(
      "eval: %zu stored functions, %zu mostly diffuse (max(0, a + b.l) leaves <= %g of the "
      "energy), "
      "%zu mostly specular or shadowed",
      prepared.functions.size(), classes.diffuse_count, classes.threshold,
      prepared.functions.size() - classes.diffuse_count);

  // The runs.
  EvalGrid grid;
  grid.clusters = arguments.clusters;
  grid.terms = arguments.terms;
  grid.refit_entries = arguments.refit_entries;
  grid.refit_rounds = arguments.refit_rounds;
  grid.methods = arguments.methods;
  grid.clustering.seed = arguments.seed;
  grid.clustering.threads = arguments.threads;
  grid.clustering.quiet = true;
  grid.pca.iterations = arguments.pca_iterations;
  std::unique_ptr<OpenClAssigner> opencl;
  if (arguments.assign == "opencl") {
    opencl = make_opencl_assigner(arguments.device, grid.clustering);
    grid.clustering.assign = opencl->function();
  }
  const std::vector<EvalRun> runs = run_grid(prepared.rows, grid, [](const EvalRun& run) {
    note("eval: %-9s %3d clusters, %2d terms%s: %.1f s", run.method.c_str(), run.clusters_asked,
         run.terms,
         run.budget >= 0 ? (", refit for " + std::to_string(run.budget) + " entries").c_str() : "",
         run.seconds);
  });

  std::vector<int> caps = arguments.entries;
  caps.push_back(arguments.compare_entries);
  caps = sorted_list(caps, "--entries", 0);
  std::vector<MeasuredRun> measured;
  for (const EvalRun& run : runs) {
    MeasuredRun m;
    m.run = &run;
    m.caps = run.budget >= 0 ? std::vector<int>{run.budget} : caps;
    m.errors = row_errors(prepared.rows, run.model, m.caps, arguments.threads);
    measured.push_back(std::move(m));
  }

  // Fig. 4 a-c and Fig. 5.
  CsvTable errors({"method", "clusters", "terms", "clusters_used", "refit_for", "entries",
                   "error_all", "error_diffuse", "error_specular"});
  for (const MeasuredRun& m : measured) {
    for (std::size_t c = 0; c < m.caps.size(); ++c) {
      if (m.run->budget < 0 && std::find(arguments.entries.begin(), arguments.entries.end(),
                                         m.caps[c]) == arguments.entries.end())
        continue;  // only measured for the images
      const SubsetErrors e = subset_means(m.errors, Eigen::Index(c), classes);
      errors.row()
          .cell(m.run->method)
          .cell(m.run->clusters_asked)
          .cell(m.run->terms)
          .cell(m.run->model.clusters)
          .cell(m.run->budget >= 0 ? std::to_string(m.run->budget) : std::string())
          .cell(m.caps[c])
          .cell(e.all)
          .cell(e.diffuse)
          .cell(e.specular);
    }
  }
  CsvTable ratios(
      {"clusters", "terms", "entries", "method", "ratio_all", "ratio_diffuse", "ratio_specular"});
  const auto ratio = [](double baseline, double method) {
    return method > 0 ? baseline / method : NAN;
  };
  for (const int clusters : arguments.clusters)
    for (const int terms : arguments.terms) {
      const MeasuredRun* cpca = find_run(measured, "cpca", clusters, terms);
      const MeasuredRun* l1 = find_run(measured, "l1", clusters, terms);
      for (const int entries : arguments.entries) {
        const Eigen::Index at = std::find(caps.begin(), caps.end(), entries) - caps.begin();
        const SubsetErrors base = subset_means(cpca->errors, at, classes);
        const auto add = [&](const std::string& method, const SubsetErrors& e) {
          ratios.row()
              .cell(clusters)
              .cell(terms)
              .cell(entries)
              .cell(method)
              .cell(ratio(base.all, e.all))
              .cell(ratio(base.diffuse, e.diffuse))
              .cell(ratio(base.specular, e.specular));
        };
        add("l1", subset_means(l1->errors, at, classes));
        if (const MeasuredRun* refit = find_run(measured, "l1-refit", clusters, terms, entries))
          add("l1-refit", subset_means(refit->errors, 0, classes));
      }
    }

  // Fig. 4d: sparseness of the full residual.
  std::vector<double> thresholds;
  for (int k = 0; k <= 24; ++k) thresholds.push_back(std::pow(10.0, -4.0 + k / 6.0));
  CsvTable sparseness({"method", "clusters", "terms", "threshold", "fraction_at_or_below"});
  for (const EvalRun& run : runs) {
    if (run.budget >= 0) continue;
    const std::vector<double> fractions =
        residual_sparseness(prepared.rows, run.model, thresholds, arguments.threads);
    for (std::size_t t = 0; t < thresholds.size(); ++t)
      sparseness.row()
          .cell(run.method)
          .cell(run.clusters_asked)
          .cell(run.terms)
          .cell(thresholds[t])
          .cell(fractions[t]);
  }

  // Fig. 6: per-pixel error difference of the primary configuration.
  const MeasuredRun* primary_l1 = find_run(measured, "l1", primary_clusters, primary_terms);
  const MeasuredRun* primary_cpca = find_run(measured, "cpca", primary_clusters, primary_terms);
  const MeasuredRun* primary_refit =
      find_run(measured, "l1-refit", primary_clusters, primary_terms, arguments.compare_entries);
  const Eigen::Index compare_at =
      std::find(caps.begin(), caps.end(), arguments.compare_entries) - caps.begin();
  const Eigen::VectorXd cpca_rows = primary_cpca->errors.col(compare_at);
  const Eigen::MatrixXd difference =
      pixel_difference(field, prepared, cpca_rows, primary_l1->errors.col(compare_at));
  write_npy_matrix(out / "error_difference.npy", difference, NpyDtype::float32);
  if (primary_refit)
    write_npy_matrix(out / "error_difference_refit.npy",
                     pixel_difference(field, prepared, cpca_rows, primary_refit->errors.col(0)),
                     NpyDtype::float32);
  std::size_t pixels = 0, relume_better = 0;
  for (Eigen::Index v = 0; v < difference.size(); ++v) {
    if (std::isnan(difference.data()[v])) continue;
    ++pixels;
    relume_better += difference.data()[v] > 0;
  }

  // Rate against distortion, as stored; the stored fields of the primary configuration are kept
  // for the relighting.
  StoragePrecision precision;
  precision.budget = arguments.quantization_budget;
  precision.threads = arguments.threads;
  const ContainerOptions container = precision.container_options();
  CsvTable rate({"method", "clusters", "terms", "entries", "bytes", "bytes_per_pixel", "ratio",
                 "error_masked", "psnr_mask", "psnr_frame"});
  std::size_t points = 0;
  for (const EvalRun& run : runs) points += run.budget >= 0 ? 1 : arguments.rate_entries.size();
  ProgressReporter progress("eval: storing containers", points, verbosity() == Verbosity::quiet);
  const int longest = caps.back();
  std::map<std::string, CompressedField> primary_fields;
  const auto store = [&](const EvalRun& run, int entries) {
    CompressionStats stats;
    CompressedField stored =
        build_compressed_field(field, prepared, run.model, BasisTransform::identity, entries,
                               field.noise_floor, {}, stats, arguments.threads);
    store_with_precision(field, stored, precision);
    return stored;
  };
  for (const EvalRun& run : runs) {
    const std::vector<int> budgets =
        run.budget >= 0 ? std::vector<int>{run.budget} : arguments.rate_entries;
    for (const int entries : budgets) {
      const CompressedField stored = store(run, entries);
      const std::uint64_t bytes = plan_container(stored, container).file_bytes;
      const Psnr8 psnr =
          psnr_8bit(field, stored, arguments.psnr_white, all_residual_entries, arguments.threads);
      rate.row()
          .cell(run.method)
          .cell(run.clusters_asked)
          .cell(run.terms)
          .cell(entries)
          .cell(static_cast<long long>(bytes))
          .cell(double(bytes) / double(field.pixels()))
          .cell(double(bytes) / (double(field.functions()) * field.lights() * 4))
          .cell(relative_error(field, stored, true, all_residual_entries, arguments.threads).mean)
          .cell(psnr.masked)
          .cell(psnr.whole_frame);
      progress.advance();
    }
    if (run.clusters_asked == primary_clusters && run.terms == primary_terms) {
      if (run.budget < 0 && run.method != "cpca-mean")
        primary_fields[run.method] = store(run, longest);
      else if (run.budget == arguments.compare_entries)
        primary_fields["l1-refit"] = store(run, run.budget);
    }
  }
  progress.finish();

  // Table 1 and the relit images.
  RelightingSetup setup;
  setup.original = &field;
  setup.map = &map;
  setup.rotate_degrees = arguments.rotate;
  setup.frames = arguments.frames;
  setup.timed_calls = arguments.timed_calls;
  setup.caps = caps;
  setup.image_cap = arguments.compare_entries;
  setup.device = arguments.device;
  setup.threads = arguments.threads;
  RelightingResult relit =
      measure_relighting({{"l1", &primary_fields["l1"]}, {"cpca", &primary_fields["cpca"]}}, setup);
  if (primary_fields.count("l1-refit")) {
    RelightingSetup once = setup;
    once.caps = {arguments.compare_entries};
    once.frames = 1;
    once.timed_calls = 1;
    const RelightingResult refit_relit =
        measure_relighting({{"l1-refit", &primary_fields["l1-refit"]}}, once);
    relit.images.insert(relit.images.end(), refit_relit.images.begin(), refit_relit.images.end());
  }
  CsvTable relighting({"method", "clusters", "terms", "cap", "frames", "frames_per_second",
                       "kernel_ms", "relit_error", "error_masked", "device"});
  for (const RelightingRow& row : relit.rows)
    relighting.row()
        .cell(row.method)
        .cell(primary_clusters)
        .cell(primary_terms)
        .cell(row.cap)
        .cell(arguments.frames)
        .cell(row.frames_per_second)
        .cell(row.kernel_ms)
        .cell(row.relit_error)
        .cell(relative_error(field, primary_fields[row.method], true, row.cap, arguments.threads)
                  .mean)
        .cell(relit.device);
  const ImageWriteOptions exposure{arguments.exposure};
  write_image(out / "relit_reference.png", relit.reference, exposure);
  nlohmann::ordered_json relit_files = nlohmann::ordered_json::object();
  nlohmann::ordered_json difference_files = nlohmann::ordered_json::object();
  for (const auto& [method, image] : relit.images) {
    const std::string name = "relit_" + method + ".png", diff = "difference10_" + method + ".png";
    write_image(out / name, image, exposure);
    write_image(out / diff, scaled_difference(image, relit.reference, 10.0f), exposure);
    relit_files[method] = name;
    difference_files[method] = diff;
  }

  CsvTable times({"method", "clusters", "terms", "refit_for", "seconds", "refit_seconds",
                  "iterations", "clusters_used"});
  for (const EvalRun& run : runs)
    times.row()
        .cell(run.method)
        .cell(run.clusters_asked)
        .cell(run.terms)
        .cell(run.budget >= 0 ? std::to_string(run.budget) : std::string())
        .cell(run.seconds)
        .cell(run.refit_seconds)
        .cell(run.iterations)
        .cell(run.model.clusters);

  errors.write(out / "error_vs_entries.csv");
  ratios.write(out / "error_ratio.csv");
  sparseness.write(out / "sparseness.csv");
  rate.write(out / "rate_distortion.csv");
  relighting.write(out / "relighting.csv");
  times.write(out / "compression_time.csv");

  // The summary: settings, classes, and the headline comparison of every configuration.
  nlohmann::ordered_json configurations = nlohmann::ordered_json::array();
  for (const int clusters : arguments.clusters)
    for (const int terms : arguments.terms) {
      nlohmann::ordered_json entry = {{"clusters", clusters}, {"terms", terms}};
      for (const int entries : {0, arguments.compare_entries}) {
        nlohmann::ordered_json at = nlohmann::ordered_json::object();
        for (const std::string method : {"l1", "cpca", "cpca-mean"})
          if (const auto e =
                  error_at(find_run(measured, method, clusters, terms), entries, classes))
            at[method] = *e;
        if (const auto e = error_at(find_run(measured, "l1-refit", clusters, terms, entries),
                                    entries, classes))
          at["l1-refit"] = *e;
        entry["error_at_" + std::to_string(entries) + "_entries"] = at;
      }
      configurations.push_back(entry);
    }
  const std::vector<std::string> plots = {"error_vs_entries.png", "sparseness.png",
                                          "error_ratio.png",      "error_difference.png",
                                          "relighting.png",       "rate_distortion.png",
                                          "compression_time.png", "relit_side_by_side.png"};
  nlohmann::ordered_json summary = {
      {"input", arguments.input},
      {"field",
       {{"width", field.width},
        {"height", field.height},
        {"channels", field.channels},
        {"lights", field.lights()},
        {"stored_functions", prepared.functions.size()},
        {"noise_floor", field.noise_floor},
        {"dark_pixels", prepared.dark_pixels.size()}}},
      {"settings",
       {{"clusters", arguments.clusters},
        {"terms", arguments.terms},
        {"entries", arguments.entries},
        {"refit_entries", refits ? arguments.refit_entries : std::vector<int>{}},
        {"refit_rounds", arguments.refit_rounds},
        {"rate_entries", arguments.rate_entries},
        {"methods", arguments.methods},
        {"primary", std::to_string(primary_clusters) + "x" + std::to_string(primary_terms)},
        {"pca_iterations", arguments.pca_iterations},
        {"quantization_budget", arguments.quantization_budget},
        {"psnr_white", arguments.psnr_white},
        {"seed", arguments.seed},
        {"assignment", opencl ? opencl->device_label() : "cpu"}}},
      {"classes",
       {{"rule",
         "diffuse when max(0, a + b.l) over the light directions l, a and b fitted in least "
         "squares over the lights above 5% of the function's largest value, leaves at most "
         "`threshold` of the function's energy"},
        {"threshold", classes.threshold},
        {"diffuse", classes.diffuse_count},
        {"specular_or_shadowed", prepared.functions.size() - classes.diffuse_count}}},
      {"error_measure",
       "paper Eq. 16 over the stored functions (masked, non-zero, not of a dark pixel at or "
       "below the field's noise floor), float values (rate_distortion.csv: as the containers "
       "store them, dark pixels included)"},
      {"configurations", configurations},
      {"error_difference",
       {{"entries", arguments.compare_entries},
        {"pixels", pixels},
        {"fraction_where_relume_is_better", pixels ? double(relume_better) / pixels : 0.0}}},
      {"relighting",
       {{"device", relit.device},
        {"frames", arguments.frames},
        {"timed_calls", arguments.timed_calls}}},
      {"images",
       {{"environment", map.name},
        {"rotate", arguments.rotate},
        {"entries", arguments.compare_entries},
        {"reference", "relit_reference.png"},
        {"relit", relit_files},
        {"difference10", difference_files}}},
      {"files",
       {{"csv",
         {"error_vs_entries.csv", "error_ratio.csv", "sparseness.csv", "rate_distortion.csv",
          "relighting.csv", "compression_time.csv"}},
        {"npy", primary_refit
                    ? std::vector<std::string>{"error_difference.npy", "error_difference_refit.npy"}
                    : std::vector<std::string>{"error_difference.npy"}},
        {"plots", arguments.no_plots ? std::vector<std::string>{} : plots}}},
      {"seconds", seconds_since(start)}};
  write_json_report((out / "eval.json").string(), summary);
  if (!arguments.no_plots) draw_eval_plots(out);
  say("eval %s -> %s: %zu runs, %.1f s", arguments.input.c_str(), out.c_str(), runs.size(),
      seconds_since(start));
}

const CommandRegistration registration{
    75, [](CLI::App& app) {
      auto arguments = std::make_shared<EvalArguments>();
      auto* command = app.add_subcommand(
          "eval",
          "Reproduce the paper's comparisons on one field: relume's L1 method against clustered\n"
          "PCA for a grid of clusters and terms, written as CSV, JSON and PNG plots.\n"
          "Example: relume eval ../shared/data/olat/diligent-bear-crop8 -o eval/bear\n"
          "         --clusters 32,64 --terms 2,4 --env ../shared/data/envmaps/grace_cross.hdr "
          "--rotate 180");
      command->add_option("input", arguments->input, "Field folder or .lp file")->required();
      command->add_option("-o,--output", arguments->output, "Output folder")->required();
      command->add_option("--clusters", arguments->clusters, "Cluster counts of the grid")
          ->delimiter(',')
          ->capture_default_str();
      command->add_option("--terms", arguments->terms, "Terms per cluster of the grid")
          ->delimiter(',')
          ->capture_default_str();
      command
          ->add_option("--entries", arguments->entries,
                       "Residual entries per function the errors are measured at")
          ->delimiter(',')
          ->capture_default_str();
      command
          ->add_option("--refit-entries", arguments->refit_entries,
                       "Residual budgets an l1-refit run is made for (one run each)")
          ->delimiter(',')
          ->capture_default_str();
      command
          ->add_option("--refit-rounds", arguments->refit_rounds,
                       "Rounds of the trimmed least-squares refit (as compress --trimmed-refit)")
          ->capture_default_str();
      command
          ->add_option("--rate-entries", arguments->rate_entries,
                       "Residual budgets of the rate-distortion containers (default: --entries)")
          ->delimiter(',');
      command
          ->add_option("--methods", arguments->methods,
                       "Methods: l1 (relume), cpca (clustered PCA, terms components), "
                       "cpca-mean (a mean plus terms - 1 components), l1-refit (l1 refitted "
                       "for each --refit-entries budget); l1 and cpca are required")
          ->delimiter(',')
          ->capture_default_str();
      command->add_option("--primary", arguments->primary,
                          "CLUSTERSxTERMS of the per-pixel map, the relighting table and the "
                          "images (default: the largest of the grid)");
      command
          ->add_option("--compare-entries", arguments->compare_entries,
                       "Residual entries of the per-pixel map and the relit images")
          ->capture_default_str();
      command->add_option("--env", arguments->environment,
                          "Environment map of the relighting (default: the built-in sky)");
      command
          ->add_option("--layout", arguments->layout, "Map layout: auto, latlong, angular, cross")
          ->capture_default_str();
      command->add_option("--rotate", arguments->rotate, "Rotate the map about +y, degrees")
          ->capture_default_str();
      command->add_option("--exposure", arguments->exposure, "Exposure of the PNG images, stops")
          ->capture_default_str();
      command
          ->add_option("--frames", arguments->frames,
                       "Relit frames per residual cap (the map turned by 360/frames each)")
          ->capture_default_str();
      command
          ->add_option("--timed-calls", arguments->timed_calls,
                       "relight() calls timed per residual cap (frames/s is 1 / their median)")
          ->capture_default_str();
      command->add_option("--device", arguments->device,
                          "OpenCL device of the relighting and the L1 assignment (a substring of "
                          "'platform / device')");
      command
          ->add_option("--assign", arguments->assign,
                       "Where the L1 reassignment fits run: opencl or cpu")
          ->capture_default_str();
      command
          ->add_option("--diffuse-threshold", arguments->diffuse_threshold,
                       "A function is mostly diffuse when the clamped linear fit "
                       "max(0, a + b.l) over the light directions (a Lambertian function with "
                       "its attached shadow) leaves at most this fraction of its energy")
          ->capture_default_str();
      command
          ->add_option("--pca-iterations", arguments->pca_iterations,
                       "Cap on clustered PCA's fit + reassignment rounds")
          ->capture_default_str();
      command
          ->add_option("--psnr-white", arguments->psnr_white,
                       "The field value that is 255 in the 8-bit PSNR")
          ->capture_default_str();
      command
          ->add_option("--quantization-budget", arguments->quantization_budget,
                       "Quantization budget of the stored containers (as compress)")
          ->capture_default_str();
      command->add_option("--seed", arguments->seed, "Seed of the cluster seeding")
          ->capture_default_str();
      command->add_option("--threads", arguments->threads, "Worker threads (default: all cores)");
      command->add_flag("--no-plots", arguments->no_plots,
                        "Write the CSV, NPY, JSON and images but draw no plots (no Python)");
      command->callback([arguments] { run_eval(*arguments); });
    }};

}  // namespace
}  // namespace relume
