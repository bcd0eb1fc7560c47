// `relume eval`: the paper's results reproduced on one field, relume against clustered PCA, with
// every knob swept (eval/evaluation.hpp does the work): the errors against residual entries, their
// ratios, the residual's sparseness, a per-pixel error difference, rate against distortion,
// relighting speed and error, compression times and relit images go to CSV, NPY, PNG and one JSON
// summary (eval_files.hpp, eval_summary.hpp); scripts/plot_eval.py draws the plots.
#include <filesystem>
#include <memory>
#include <relume/error.hpp>
#include <relume/field.hpp>
#include <relume/lighting.hpp>
#include <sstream>

#include "command_registry.hpp"
#include "commands/eval/eval_files.hpp"
#include "commands/eval/eval_plots.hpp"
#include "commands/eval/eval_summary.hpp"
#include "core/console.hpp"
#include "core/elapsed_time.hpp"
#include "core/json_report.hpp"
#include "eval/evaluation.hpp"
#include "lighting/environment_map.hpp"

namespace relume {
namespace {

namespace fs = std::filesystem;

struct EvalArguments {
  std::string input, output;
  EvaluationOptions options;
  std::string primary;  // "KxT"; empty: the last clusters and terms of the grid
  std::string environment, layout = "auto";
  double exposure = 0;
  bool no_plots = false;
};

// --primary KxT into the options; throws Error for another form.
void set_primary(EvalArguments& arguments) {
  if (arguments.primary.empty()) return;
  char by = 0;
  std::istringstream text(arguments.primary);
  if (!(text >> arguments.options.primary_clusters >> by >> arguments.options.primary_terms) ||
      by != 'x' || !text.eof())
    throw Error("--primary '" + arguments.primary +
                "' must be CLUSTERSxTERMS of the grid (for example 64x4)");
}

EnvironmentMap evaluation_map(const EvalArguments& arguments) {
  if (arguments.environment.empty())
    return make_environment_map(render_sky({}), EnvironmentLayout::latlong, "the built-in sky");
  return load_environment_map(arguments.environment, parse_layout_option(arguments.layout));
}

void run_eval(EvalArguments& arguments) {
  const auto start = Clock::now();
  set_primary(arguments);
  EvaluationOptions& options = arguments.options;
  options = resolve_evaluation_options(options);         // bad settings fail before the work
  const EnvironmentMap map = evaluation_map(arguments);  // so does a bad map
  const fs::path out = arguments.output;
  fs::create_directories(out);

  FieldLoadOptions load;
  load.threads = options.threads;
  const ReflectanceField field = load_field(arguments.input, load);
  note("eval: %s: %dx%d, %d channels, %d lights", arguments.input.c_str(), field.width,
       field.height, field.channels, field.lights());
  options.quiet = false;
  options.on_classes = [](std::size_t stored, const FunctionClasses& classes) {
    note(
        "eval: %zu stored functions, %zu mostly diffuse (max(0, a + b.l) leaves <= %g of the "
        "energy), %zu mostly specular or shadowed",
        stored, classes.diffuse_count, classes.threshold, stored - classes.diffuse_count);
  };
  options.on_run = [](const EvalRun& run) {
    note("eval: %-9s %3d clusters, %2d terms%s: %.1f s", run.method.c_str(), run.clusters_asked,
         run.terms,
         run.budget >= 0 ? (", refit for " + std::to_string(run.budget) + " entries").c_str() : "",
         run.seconds);
  };
  options.on_relit = [](const RelightingRow& row) {
    detail("eval: relit %s with %d entries: %.1f frames/s, relit error %.5f", row.method.c_str(),
           row.cap, row.frames_per_second, row.relit_error);
  };
  const EvaluationResult result = evaluate_field(field, map, options);

  const EvalFiles files = write_eval_files(out, result, ImageWriteOptions{arguments.exposure});
  const std::vector<std::string> plots =
      arguments.no_plots ? std::vector<std::string>{} : eval_plot_files();
  write_json_report(
      (out / "eval.json").string(),
      eval_summary(arguments.input, field, map.name, result, files, plots, seconds_since(start)));
  if (!arguments.no_plots) draw_eval_plots(out);
  say("eval %s -> %s: %zu runs, %.1f s", arguments.input.c_str(), out.c_str(), result.runs.size(),
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
      command->add_option("--clusters", arguments->options.clusters, "Cluster counts of the grid")
          ->delimiter(',')
          ->capture_default_str();
      command->add_option("--terms", arguments->options.terms, "Terms per cluster of the grid")
          ->delimiter(',')
          ->capture_default_str();
      command
          ->add_option("--entries", arguments->options.entries,
                       "Residual entries per function the errors are measured at")
          ->delimiter(',')
          ->capture_default_str();
      command
          ->add_option("--refit-entries", arguments->options.refit_entries,
                       "Residual budgets an l1-refit run is made for (one run each)")
          ->delimiter(',')
          ->capture_default_str();
      command
          ->add_option("--refit-rounds", arguments->options.refit_rounds,
                       "Rounds of the trimmed least-squares refit (as compress --trimmed-refit)")
          ->capture_default_str();
      command
          ->add_option("--rate-entries", arguments->options.rate_entries,
                       "Residual budgets of the rate-distortion containers (default: --entries)")
          ->delimiter(',');
      command
          ->add_option("--methods", arguments->options.methods,
                       "Methods: l1 (relume), cpca (clustered PCA, terms components), "
                       "cpca-mean (a mean plus terms - 1 components), l1-refit (l1 refitted "
                       "for each --refit-entries budget); l1 and cpca are required")
          ->delimiter(',')
          ->capture_default_str();
      command->add_option("--primary", arguments->primary,
                          "CLUSTERSxTERMS of the per-pixel map, the relighting table and the "
                          "images (default: the largest of the grid)");
      command
          ->add_option("--compare-entries", arguments->options.compare_entries,
                       "Residual entries of the per-pixel map and the relit images")
          ->capture_default_str();
      command->add_option("--env", arguments->environment,
                          "Environment map of the relighting (default: the built-in sky)");
      command
          ->add_option("--layout", arguments->layout, "Map layout: auto, latlong, angular, cross")
          ->capture_default_str();
      command
          ->add_option("--rotate", arguments->options.rotate_degrees,
                       "Rotate the map about +y, degrees")
          ->capture_default_str();
      command->add_option("--exposure", arguments->exposure, "Exposure of the PNG images, stops")
          ->check(CLI::Range(-max_exposure_stops, max_exposure_stops))
          ->capture_default_str();
      command
          ->add_option("--frames", arguments->options.frames,
                       "Relit frames per residual cap (the map turned by 360/frames each)")
          ->capture_default_str();
      command
          ->add_option("--timed-calls", arguments->options.timed_calls,
                       "relight() calls timed per residual cap (frames/s is 1 / their median)")
          ->capture_default_str();
      command->add_option("--device", arguments->options.device,
                          "OpenCL device of the relighting and the L1 assignment (a substring of "
                          "'platform / device')");
      command
          ->add_option("--assign", arguments->options.assign,
                       "Where the L1 reassignment fits run: opencl or cpu")
          ->capture_default_str();
      command
          ->add_option("--diffuse-threshold", arguments->options.diffuse_threshold,
                       "A function is mostly diffuse when the clamped linear fit "
                       "max(0, a + b.l) over the light directions (a Lambertian function with "
                       "its attached shadow) leaves at most this fraction of its energy")
          ->capture_default_str();
      command
          ->add_option("--pca-iterations", arguments->options.pca_iterations,
                       "Cap on clustered PCA's fit + reassignment rounds")
          ->capture_default_str();
      command
          ->add_option("--psnr-white", arguments->options.psnr_white,
                       "The field value that is 255 in the 8-bit PSNR")
          ->capture_default_str();
      command
          ->add_option("--quantization-budget", arguments->options.quantization_budget,
                       "Quantization budget of the stored containers (as compress)")
          ->capture_default_str();
      command->add_option("--seed", arguments->options.seed, "Seed of the cluster seeding")
          ->capture_default_str();
      command->add_option("--threads", arguments->options.threads,
                          "Worker threads (default: all cores)");
      command->add_flag("--no-plots", arguments->no_plots,
                        "Write the CSV, NPY, JSON and images but draw no plots (no Python)");
      command->callback([arguments] { run_eval(*arguments); });
    }};

}  // namespace
}  // namespace relume
