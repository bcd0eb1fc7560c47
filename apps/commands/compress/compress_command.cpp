// `relume compress`: clustered sparse residual factorization of one or more reflectance fields
// into .relume containers, with a JSON report per run (lib/compress/compression_report.hpp),
// checkpoints after every clustering iteration (--resume continues an interrupted run) and, with
// several inputs, one container per input in the output folder: a failing input is reported and the
// others still run.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <relume/error.hpp>
#include <relume/field.hpp>

#include "command_registry.hpp"
#include "compress/checkpoint.hpp"
#include "compress/clustered_factorization.hpp"
#include "compress/compression_report.hpp"
#include "compress/compression_target.hpp"
#include "compress/opencl_assignment.hpp"
#include "compress/rank_exchange.hpp"
#include "compress/rate_control.hpp"
#include "compress/storage_precision.hpp"
#include "compress/streamed_compression.hpp"
#include "container/container.hpp"
#include "container/container_sections.hpp"
#include "container/container_strips.hpp"
#include "core/atomic_file.hpp"
#include "core/console.hpp"
#include "core/elapsed_time.hpp"
#include "core/memory_budget.hpp"
#include "core/parallel.hpp"
#include "core/progress.hpp"
#include "core/ranks.hpp"
#include "field/mask_file.hpp"
#include "options/field_input_options.hpp"
#include "options/json_report.hpp"
#include "model/reconstruct_field.hpp"
#include "options/output_paths.hpp"

namespace relume {
namespace {

namespace fs = std::filesystem;

struct CompressArguments {
  std::vector<std::string> inputs;
  std::string output;
  std::string report;
  std::string residual = "5%";
  std::string residual_allocation = "per-function";
  std::string solver = "irls";
  std::string transform = "identity";
  std::string assign = "opencl";
  std::string method = "l1";
  std::string pca_centering = "none";
  std::string device;
  std::string weights_precision = "quantized";
  std::string residual_precision = "quantized";
  std::string bases_precision = "quantized";
  double quantization_budget = QuantizationBudget{}.relative_increase;
  std::optional<double> term_budget;  // unset: 0, and a rate target tries 0 and 0.1
  double target_error = 0;
  std::uint64_t target_bytes = 0;
  double target_bytes_per_pixel = 0;
  double target_psnr = 0;
  std::string target_region = "frame";
  double psnr_white = 1.0;
  std::string psnr_mask;
  int irls_iterations = IrlsSettings{}.iterations;
  bool resume = false;
  std::string scratch;        // empty: the output's folder
  std::optional<int> refine;  // unset: 2 after --multires, --iterations streamed
  FieldInputOptions field_input;
  CompressionOptions options;
};

// The settings that shape the clustering, with the input: a checkpoint is only resumed when its
// fingerprint is the same.
std::string fingerprint(const std::string& input, const FieldInputOptions& field_input,
                        const CompressionOptions& options) {
  const ClusteringOptions& clustering = options.clustering;
  return nlohmann::json{
      {"input", fs::absolute(input).lexically_normal().string()},
      {"field_input", describe_field_input(field_input)},
      {"clusters", clustering.clusters},
      {"terms", clustering.terms},
      {"transform", options.transform == BasisTransform::haar ? "haar" : "identity"},
      {"light_weighting", options.light_weighting},
      {"multires", options.multires_levels},
      {"candidates", clustering.candidates},
      {"min", clustering.sizes.minimum},
      {"max", clustering.sizes.maximum},
      {"seed", clustering.seed}}
      .dump();
}

// One line for users, leading with the error over what is stored (paper Eq. 16 over the
// functions inside the mask); with a mask, the whole frame's error follows, in which every
// background function, not stored, counts as entirely lost.
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
  const nlohmann::ordered_json& per_light = report["per_light_error_masked"];
  char line[1024];
  std::snprintf(line, sizeof line,
                "compressed %s -> %s: %llu bytes (%.4f of float32), %s, largest per-light error "
                "%.3g of its function's peak, %lld negative values, %d clusters, %.1f s",
                report["input"].get<std::string>().c_str(),
                report["output"].get<std::string>().c_str(),
                static_cast<unsigned long long>(report["bytes"].get<std::uint64_t>()),
                report["ratio"].get<double>(), error, per_light["largest_relative"].get<double>(),
                static_cast<long long>(per_light["negative_values"].get<std::int64_t>()), clusters,
                report["seconds"].get<double>());
  return line;
}

// The stored precisions the options name; throws Error naming a bad name.
StoragePrecision storage_precision(const CompressArguments& arguments,
                                   const CompressionOptions& options) {
  if (arguments.bases_precision != "quantized" && arguments.bases_precision != "float32")
    throw Error("--bases-precision must be 'quantized' or 'float32', got '" +
                arguments.bases_precision + "'");
  StoragePrecision precision;
  precision.weights = parse_value_precision(arguments.weights_precision);
  precision.residual = parse_value_precision(arguments.residual_precision);
  precision.quantize_bases = arguments.bases_precision == "quantized";
  precision.budget = arguments.quantization_budget;
  precision.term_budget = arguments.term_budget.value_or(QuantizationBudget{}.term_increase);
  precision.threads = options.clustering.threads;
  return precision;
}

bool has_rate_target(const CompressArguments& arguments) {
  return arguments.target_bytes > 0 || arguments.target_bytes_per_pixel > 0 ||
         arguments.target_psnr > 0;
}

RateTarget rate_target(const CompressArguments& arguments, const ReflectanceField& field,
                       const std::vector<std::uint8_t>& psnr_mask) {
  RateTarget target;
  target.bytes = arguments.target_bytes;
  if (arguments.target_bytes_per_pixel > 0)
    target.bytes =
        std::uint64_t(std::floor(arguments.target_bytes_per_pixel * double(field.pixels())));
  target.psnr = arguments.target_psnr;
  target.psnr_white = arguments.psnr_white;
  target.term_budgets = arguments.term_budget ? std::vector<double>{*arguments.term_budget}
                                              : std::vector<double>{0.0, 0.1};
  // The whole frame, or the mask: --psnr-mask's, else the field's (an empty region).
  target.region = arguments.target_region == "frame"
                      ? std::vector<std::uint8_t>(std::size_t(field.pixels()), 1)
                      : psnr_mask;
  const std::string solver = arguments.solver;
  target.parameters_json = [solver](const CompressionOptions& options,
                                    const CompressionStats& stats) {
    return compression_parameters(options, stats, solver).dump();
  };
  return target;
}

// At most one target, each finite and positive; throws Error naming the option otherwise.
void check_targets(const CompressArguments& arguments) {
  const std::pair<const char*, double> targets[] = {
      {"--target-error", arguments.target_error},
      {"--target-bytes", double(arguments.target_bytes)},
      {"--target-bytes-per-pixel", arguments.target_bytes_per_pixel},
      {"--target-psnr", arguments.target_psnr}};
  const char* given = nullptr;
  for (const auto& [option, value] : targets) {
    if (value < 0 || !std::isfinite(value))
      throw Error(std::string(option) + " must be a finite number > 0, got " +
                  std::to_string(value));
    if (value == 0) continue;
    if (given) throw Error(std::string(given) + " and " + option + " are two targets: give one");
    given = option;
  }
  if (given && arguments.residual_allocation != "per-function")
    throw Error(std::string("--residual-allocation ") + arguments.residual_allocation +
                " does not apply with " + given +
                ", which chooses every function's residual length itself");
}

// The budget compress plans with: --memory-limit as given (per rank under mpirun), else three
// quarters of what the system says is available, shared by the ranks on this machine.
std::pair<std::uint64_t, std::string> planning_budget() {
  const MemoryBudget budget = memory_budget();
  if (budget.source == "--memory-limit") return {budget.bytes, budget.source};
  const int sharing = process_ranks().local_size();
  std::string source = "three quarters of " + budget.source;
  if (sharing > 1) source += ", over the " + std::to_string(sharing) + " ranks on this machine";
  return {budget.bytes / 4 * 3 / std::uint64_t(sharing), source};
}

// Throws Error naming the options a streamed compression cannot honour.
void check_streamable_arguments(const CompressArguments& arguments) {
  const char* option = arguments.target_error > 0 ? "--target-error"
                       : has_rate_target(arguments)
                           ? "a rate target (--target-bytes, --target-psnr)"
                       : arguments.term_budget.value_or(0) > 0 ? "--term-budget"
                                                               : nullptr;
  if (option)
    throw Error(std::string(option) +
                " measures many compressions against the whole field, which does not fit the "
                "memory budget here (the plan is streamed): leave it out, or raise "
                "--memory-limit");
}

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

nlohmann::ordered_json compress_one(const std::string& input, const fs::path& output,
                                    const CompressArguments& arguments,
                                    const CompressionOptions& base_options,
                                    OpenClAssigner* opencl) {
  const auto start = Clock::now();
  CompressionOptions options = base_options;
  if (opencl) options.clustering.assign = opencl->function();
  const unsigned threads = options.clustering.threads;

  // The plan: in memory when the field fits the budget, else streamed in strips.
  const FieldLoadOptions load = input_load_options(input, arguments.field_input, threads);
  auto reader = std::make_unique<FieldStripReader>(input, load);
  const auto [budget, budget_source] = planning_budget();
  const fs::path scratch_folder =
      arguments.scratch.empty() ? fs::absolute(output).parent_path() : fs::path(arguments.scratch);
  // Several ranks (mpirun) always stream: each reads its own band of pixel rows.
  Ranks& ranks = process_ranks();
  const CompressionPlan plan = plan_compression(reader->header(), options, budget, budget_source,
                                                threads, scratch_folder, ranks.size() > 1);
  note("compress: %s", plan.describe().c_str());
  if (plan.streamed) {
    check_streamable_arguments(arguments);
    check_streamable_options(options);
    // Unless --refine says otherwise, as many passes over all functions as the in-memory path's
    // L1 iterations (each pass is one reassignment and one F-step).
    options.refine_iterations = arguments.refine.value_or(options.clustering.max_iterations);
  } else {
    reader.reset();  // the images are read whole instead
  }
  std::optional<ReflectanceField> field;
  if (!plan.streamed) field = load_input_field(input, load);
  const ReflectanceField& shape = field ? *field : reader->header();
  const double load_seconds = seconds_since(start);
  note("compress: %s: %dx%d, %d channels, %d lights, %s in %.2f s", input.c_str(), shape.width,
       shape.height, shape.channels, shape.lights(), field ? "loaded" : "opened", load_seconds);

  const fs::path checkpoint = output.string() + ".checkpoint";
  std::string print = fingerprint(input, arguments.field_input, options);
  if (plan.streamed)
    print += " streamed sample " + std::to_string(plan.sample_rows) + " ranks " +
             std::to_string(ranks.size());
  std::optional<ClusteringResume> resume;
  if (arguments.resume && fs::exists(checkpoint)) {
    resume = read_checkpoint(checkpoint, print);
    note("compress: resuming from %s (%zu iterations done)", checkpoint.c_str(),
         resume->iterations.size());
  }
  CompressionStats stats;
  const IterationHook hook = [&](const ClusterModel& model, const IterationRecord& record) {
    write_checkpoint(checkpoint, print, model, stats.clustering.iterations);
    note(
        "compress: iteration %d: L1 objective %.6g, %zu of %zu functions changed cluster, %d "
        "clusters, %.2f s",
        record.iteration, record.objective, record.changed, model.assignment.size(),
        record.clusters, record.seconds);
  };

  // What the file stores (store_with_precision); in memory, `compressed` stays for the report's
  // cost of the rounding (a streamed run keeps no float32 copy: its Eq. 16 error was measured as
  // it was built).
  const StoragePrecision precision = storage_precision(arguments, options);
  ContainerOptions container = precision.container_options();
  const QuantizationBudget budget_of_quantization = precision.quantization_budget();

  std::vector<std::uint8_t> psnr_mask;
  if (!arguments.psnr_mask.empty())
    psnr_mask = read_mask(arguments.psnr_mask, shape.width, shape.height);

  CompressedField compressed, stored;
  // A streamed run whose compressed field is on disk (plan.compressed_on_disk): this rank's strip
  // file (the root's has every rank's strips), how they are stored, and at the root the stored
  // field that is written (`stored` stays empty).
  std::unique_ptr<CompressedStripFile> strip_file;
  std::size_t band_strips = 0;
  StripStorage strip_storage;
  std::optional<CompressedFieldStrips> stored_on_disk;
  RelativeError float32_masked;
  std::optional<QuantizationChoice> quantization;
  std::optional<StreamedTrace> streamed;
  std::vector<int> streamed_bands;  // every rank's pixel rows (StreamedCompression::bands)
  nlohmann::ordered_json target_choice;
  const char* target_key = arguments.target_error > 0 ? "target_error" : "rate_target";
  // A streamed run's errors, strip by strip; with several ranks every rank measures its band of
  // what the root stores.
  const auto measure_streamed = [&](const CompressedField& stored_at_root) {
    if (strip_file)
      return measure_errors_on_disk(*reader, streamed_bands, plan.strip_rows, *strip_file,
                                    band_strips, strip_storage, stats.residual_entries,
                                    arguments.psnr_white, psnr_mask, threads,
                                    options.clustering.quiet);
    return measure_streamed_errors(*reader, streamed_bands, plan.strip_rows, stored_at_root,
                                   stats.residual_entries, arguments.psnr_white, psnr_mask,
                                   threads, options.clustering.quiet);
  };
  auto quantize_start = Clock::now();
  if (plan.streamed) {
    StreamedCompression result = compress_streamed(
        *reader, options, plan, stats, streamed.emplace(), output.filename().string() + ".scratch",
        hook, resume ? &*resume : nullptr);
    streamed_bands = result.bands;
    strip_file = std::move(result.strips);
    band_strips = result.band_strips;
    if (!ranks.root()) {  // the root writes and reports
      if (strip_file) broadcast_strip_storage(ranks, strip_storage);
      measure_streamed(CompressedField{});
      return nlohmann::ordered_json();
    }
    quantize_start = Clock::now();
    float32_masked = result.float32_masked;
    if (strip_file) {
      strip_storage = choose_strip_storage(result.original_sample, result.sampled, *strip_file,
                                           precision, quantization);
      broadcast_strip_storage(ranks, strip_storage);
      stored_on_disk = stored_strips(*strip_file, strip_storage);
    } else {
      stored = std::move(result.field);
      quantization = store_with_precision_on_strips(result.original_sample, result.sample_rows,
                                                    stored, precision);
    }
  } else if (arguments.target_error > 0 || has_rate_target(arguments)) {
    const QuantizationBudget* asked_budget =
        precision.quantizes() ? &budget_of_quantization : nullptr;
    TargetSearch search =
        arguments.target_error > 0
            ? compress_to_target_error(*field, options, arguments.target_error, container,
                                       asked_budget, stats)
            : compress_to_rate_target(*field, options, rate_target(arguments, *field, psnr_mask),
                                      container, asked_budget, stats);
    quantize_start = Clock::now();
    compressed = search.field;  // already quantized
    stored = quantize_for_container(search.field, container);
    quantization = search.quantization;
    options = search.options;
    target_choice = search.explanation;
  } else {
    compressed = compress_field(*field, options, stats, hook, resume ? &*resume : nullptr);
    quantize_start = Clock::now();
    stored = compressed;
    quantization = store_with_precision(*field, stored, precision);
  }
  const double quantize_seconds = seconds_since(quantize_start);

  CompressionRun run;
  run.threads = resolve_thread_count(threads);
  // A streamed run measures its error before the root writes: the other ranks measure their bands
  // meanwhile, then wait while the root writes on their cores too.
  auto error_start = Clock::now();
  if (plan.streamed) run.errors = measure_streamed(stored);
  double error_seconds = seconds_since(error_start);

  const auto write_start = Clock::now();
  container.parameters_json = compression_parameters(options, stats, arguments.solver).dump();
  ContainerLayout layout;
  {
    const LocalCoresLease lease(ranks);
    container.coding_threads = lease.threads(threads);
    if (stored_on_disk) {
      layout = write_container_strips(output, *stored_on_disk, container, plan.scratch_folder);
    } else {
      write_container(output, stored, container);
      layout = describe_container(output);
    }
  }
  fs::remove(checkpoint);
  const double write_seconds = seconds_since(write_start);

  if (!plan.streamed) {
    error_start = Clock::now();
    run.errors = measure_field_errors(*field, stored, stats.residual_entries, arguments.psnr_white,
                                      psnr_mask, threads);
    float32_masked = relative_error(*field, compressed, true, all_residual_entries, threads);
    error_seconds = seconds_since(error_start);
  }
  run.input = input;
  run.output = output.string();
  // What the report needs of the stored field: its shape, lights and precisions.
  const CompressedField& stored_shape = stored_on_disk ? stored_on_disk->shell : stored;
  run.compressed = &stored_shape;
  run.options = &options;
  run.stats = &stats;
  run.layout = std::move(layout);
  run.extra_seconds = {{"load", load_seconds},
                       {"quantize", quantize_seconds},
                       {"write", write_seconds},
                       {"error_measure", error_seconds}};
  run.solver = arguments.solver;
  run.assignment_device = opencl ? opencl->device_label() : "cpu";
  run.psnr_white = arguments.psnr_white;
  run.total_seconds = seconds_since(start);
  nlohmann::ordered_json report = compression_report(run);
  report["plan"] = plan_json(plan);
  if (streamed) report["streamed"] = streamed_json(*streamed);
  if (!target_choice.is_null()) report[target_key] = target_choice;
  const bool rounded = quantization || container.weights == ValuePrecision::float16 ||
                       container.residual == ValuePrecision::float16;
  if (rounded) {
    report["precision_cost"] = {
        {"weights", to_string(stored_weight_precision(stored_shape, container))},
        {"residual_values", to_string(stored_residual_precision(stored_shape, container))},
        {"basis_bits", stored_shape.quantization.basis_bits},
        {"error_masked_stored", report["error_masked"]},
        {"error_masked_float32", float32_masked.mean}};
    if (!plan.streamed)
      report["precision_cost"]["quantization_error"] =
          relative_error(compressed, stored, all_residual_entries, run.threads).mean;
    if (quantization)
      report["precision_cost"]["quantization"] = {
          {"budget", precision.budget},
          {"weight_step", quantization->steps.weight_step},
          {"residual_step", quantization->steps.residual_step},
          {"basis_bits", quantization->steps.basis_bits},
          {"sample_error_unquantized", quantization->error_unquantized},
          {"sample_error_quantized", quantization->error_quantized}};
    if (quantization && !quantization->cluster_terms.empty())
      report["precision_cost"]["terms_per_cluster"] = {
          {"budget", precision.term_budget},
          {"error_all_terms", quantization->error_all_terms},
          {"terms", quantization->cluster_terms}};
  }
  say("%s", summary_line(report, stats.clusters).c_str());
  for (const auto& [phase, seconds] : report["phases_seconds"].items())
    detail("compress: %-22s %8.2f s", phase.c_str(), seconds.get<double>());
  return report;
}

// OUT/<input name>.relume for one of several inputs.
fs::path output_for(const fs::path& folder, const std::string& input) {
  fs::path name = fs::path(input).lexically_normal();
  if (name.filename().empty()) name = name.parent_path();
  const std::string stem =
      name.extension() == ".lp" ? name.stem().string() : name.filename().string();
  return folder / (stem + ".relume");
}

// The container of each input, checked before any work: none may exist (without -y), and two
// inputs of one name (scans/a and other/a) would write the same OUT/a.relume: refused.
std::vector<fs::path> output_paths(const CompressArguments& arguments) {
  check_new_output(arguments.report);
  const bool several = arguments.inputs.size() > 1;
  if (several && fs::exists(arguments.output) && !fs::is_directory(arguments.output))
    throw Error("with several inputs -o names a folder, but " + arguments.output + " is a file");
  std::vector<fs::path> outputs;
  for (const std::string& input : arguments.inputs) {
    const fs::path output =
        several ? output_for(arguments.output, input) : fs::path(arguments.output);
    for (std::size_t j = 0; j < outputs.size(); ++j)
      if (outputs[j] == output)
        throw Error("inputs " + arguments.inputs[j] + " and " + input + " would both write " +
                    output.string() + ": compress them into different folders");
    if (!(arguments.resume && fs::exists(output.string() + ".checkpoint")))
      check_new_output(output);
    outputs.push_back(output);
  }
  return outputs;
}

void run_compress(CompressArguments& arguments) {
  CompressionOptions options = arguments.options;
  if (arguments.refine) options.refine_iterations = *arguments.refine;
  options.method = parse_compression_method(arguments.method);
  options.pca.centering = parse_pca_centering(arguments.pca_centering);
  options.residual = parse_residual_budget(arguments.residual);
  options.residual_allocation = parse_residual_allocation(arguments.residual_allocation);
  if (arguments.transform == "haar")
    options.transform = BasisTransform::haar;
  else if (arguments.transform != "identity")
    throw Error("--transform must be 'identity' or 'haar', got '" + arguments.transform + "'");
  if (arguments.solver != "irls")
    options.clustering.exact_refit = parse_l1_method(arguments.solver);
  options.clustering.quiet = verbosity() == Verbosity::quiet;
  if (arguments.irls_iterations < 0)
    throw Error("--irls-iterations must be >= 0, got " + std::to_string(arguments.irls_iterations));
  options.clustering.weight_fit.iterations = arguments.irls_iterations;
  options.clustering.basis_fit.iterations = arguments.irls_iterations;
  check_targets(arguments);

  // Options and outputs are checked before any field is loaded: a typo costs no clustering.
  validate_compression_options(options);
  storage_precision(arguments, options);
  if (arguments.inputs.size() > 1) {
    check_output_folder_location(arguments.output);
  } else {
    check_output_file_location(arguments.output);
    check_output_file_location(arguments.output + ".checkpoint");
  }
  if (!arguments.report.empty()) check_output_file_location(arguments.report);
  const std::vector<fs::path> outputs = output_paths(arguments);

  std::unique_ptr<OpenClAssigner> opencl;
  if (arguments.assign != "opencl" && arguments.assign != "cpu")
    throw Error("--assign must be 'cpu' or 'opencl', got '" + arguments.assign + "'");
  if (options.method == CompressionMethod::cpca) {
    note("compress: clustered PCA (least-squares fits on the CPU)");
  } else {
    if (arguments.assign == "opencl")
      opencl = make_opencl_assigner(arguments.device, options.clustering);
    note("compress: reassignment fits on %s",
         opencl ? opencl->device_label().c_str() : "the CPU (C++ path)");
  }

  const bool several = arguments.inputs.size() > 1;
  if (several) fs::create_directories(arguments.output);
  nlohmann::ordered_json reports = nlohmann::ordered_json::array();
  nlohmann::ordered_json failures = nlohmann::ordered_json::array();
  for (std::size_t i = 0; i < arguments.inputs.size(); ++i) {
    const std::string& input = arguments.inputs[i];
    const fs::path& output = outputs[i];
    // Under mpirun a failure ends every rank (the others would wait for it): no catching.
    if (!several || process_ranks().size() > 1) {
      reports.push_back(compress_one(input, output, arguments, options, opencl.get()));
      continue;
    }
    try {
      reports.push_back(compress_one(input, output, arguments, options, opencl.get()));
    } catch (const Interrupted&) {
      throw;  // an interruption stops the whole batch
    } catch (const std::exception& e) {
      std::fprintf(stderr, "relume: compress: %s failed: %s\n", input.c_str(), e.what());
      failures.push_back({{"input", input}, {"error", e.what()}});
    }
  }
  if (!arguments.report.empty() && process_ranks().root()) {
    const nlohmann::ordered_json document =
        several ? nlohmann::ordered_json{{"runs", reports}, {"failed", failures}} : reports[0];
    write_json_report(arguments.report, document);
  }
  if (!failures.empty())
    throw Error(std::to_string(failures.size()) + " of " + std::to_string(arguments.inputs.size()) +
                " inputs failed (see the messages above)");
}

const CommandRegistration registration{
    20, [](CLI::App& app) {
      auto arguments = std::make_shared<CompressArguments>();
      CompressionOptions& options = arguments->options;
      ClusteringOptions& clustering = options.clustering;
      auto* command = app.add_subcommand(
          "compress",
          "Compress reflectance fields (field folders or .lp files) by clustered sparse residual\n"
          "factorization into .relume containers, with an optional JSON report");
      command->add_option("inputs", arguments->inputs, "Field folders or .lp files")->required();
      command
          ->add_option("-o,--output", arguments->output,
                       "Output .relume file; with several inputs, a folder that receives one "
                       "<input name>.relume per input")
          ->required();
      command->add_option("--method", arguments->method,
                          "l1: the paper's clustered sparse residual factorization (default); "
                          "cpca: clustered PCA (Sloan et al. 2003), the baseline, into the same "
                          "container (--pca-center, --pca-iterations)");
      command->add_option("--pca-center", arguments->pca_centering,
                          "cpca: none (default: --terms components per cluster, the stronger "
                          "at equal bytes) or mean (a mean plus --terms - 1 components, stored "
                          "as their span: Sloan et al.'s mean + t components is --pca-center "
                          "mean --terms t+1)");
      command
          ->add_option("--pca-iterations", options.pca.iterations,
                       "cpca: cap on fit + reassignment rounds (they stop once settled)")
          ->capture_default_str();
      command->add_option(
          "--trimmed-refit", options.trimmed_refit_rounds,
          "Rounds of least trimmed squares refit for the --residual budget after the clustering "
          "(-1: none): lowers the error with that many residual entries (it may raise it at "
          "shorter caps of the dynamic residual), e.g. --residual 0 --trimmed-refit 2");
      command->add_flag(
          "--refit-chooses-clusters", options.refit_chooses_clusters,
          "With --trimmed-refit: also cluster by the other method (cpca for l1, l1 for cpca) and "
          "choose per cluster between the two before the refit (slower; never worse than either "
          "at the budget)");
      command->add_option("--clusters", clustering.clusters, "Clusters K")->capture_default_str();
      command->add_option("--terms", clustering.terms, "Basis functions per cluster t (1 to 16)")
          ->capture_default_str();
      command->add_option("--residual", arguments->residual,
                          "Residual entries kept per function: a count N or a percentage of the "
                          "lights P% (default 5%)");
      command
          ->add_option("--residual-allocation", arguments->residual_allocation,
                       "How the residual entries are spread: per-function (default: the same N "
                       "in every function) or peak (N x functions over the field, the entries "
                       "largest relative to their function's peak: bounds the largest per-light "
                       "error, which a concentrated light such as a sun shows; a function keeps "
                       "at most 4N). Example: --residual 12 --residual-allocation peak")
          ->check(CLI::IsMember({"per-function", "peak"}));
      command->add_option("--noise-floor", options.noise_floor,
                          "Field units: pixels whose every channel has an RMS over the lights at "
                          "or below X share one dark model (no stored rows); default: the input's "
                          "quantization step, 1/255 for 8-bit images (divided by the mean light "
                          "intensity), 0 for float images");
      command->add_option("--threshold", options.residual_threshold,
                          "Drop residual entries with |value| <= X, in field units (default: the "
                          "noise floor)");
      command->add_option("--solver", arguments->solver,
                          "irls: the fast IRLS L1 fits only (default); lp-dual, lp or huber: refit "
                          "every cluster's F and W exactly with that solver after the iterations");
      command->add_option(
          "--transform", arguments->transform,
          "Basis of the factorization: identity (default) or haar (orthonormal Haar "
          "wavelet over the light order; the residual is sparse in that basis)");
      command
          ->add_option(
              "--light-weighting", options.light_weighting,
              "Fit each light's image relative to its own energy, as an exponent in [0, 1]: 1 "
              "fully, 0.5 halfway, 0 not at all (the paper's Eq. 16). Lights that reach the "
              "object only at grazing angles (a sun behind it) then keep their accuracy: better "
              "relit images under concentrated or back light, a higher Eq. 16 error and lower "
              "average PSNR (docs/relit_quality.md); e.g. --light-weighting 0.5")
          ->capture_default_str();
      command->add_option(
          "--multires", options.multires_levels,
          "Cluster a field downsampled 2x per level first, then assign full-resolution "
          "functions among the clusters near them (default 0: off)");
      command->add_option("--refine", arguments->refine,
                          "Full-resolution iterations after --multires clustering (default 2), or "
                          "a streamed compression's passes over all functions after the sample's "
                          "clustering (default: --iterations)");
      command
          ->add_option("--iterations", clustering.max_iterations,
                       "Cap on L1 iterations (F-step + reassignment); they stop earlier once "
                       "fewer than 0.2% of the functions change cluster")
          ->capture_default_str();
      command
          ->add_option("--candidates", clustering.candidates,
                       "Clusters given the exact L1 fit per function, chosen by the smallest "
                       "least-squares projection error")
          ->capture_default_str();
      command
          ->add_option("--irls-iterations", arguments->irls_iterations,
                       "Reweighted solves of every IRLS L1 fit (weights and bases)")
          ->capture_default_str();
      command->add_option("--min-cluster-size", clustering.sizes.minimum,
                          "Clusters with fewer functions merge into their second-best cluster "
                          "(default max(8, 2 x terms))");
      command->add_option(
          "--max-cluster-size", clustering.sizes.maximum,
          "Clusters with more functions split into two halves (default 0: no limit)");
      command->add_option("--seed", clustering.seed, "Random seed of the cluster seeding")
          ->capture_default_str();
      command->add_option(
          "--threads", clustering.threads,
          "Worker threads, also of PoCL for --assign opencl unless POCL_MAX_PTHREAD_COUNT "
          "is set (default 0: all cores)");
      command->add_option(
          "--assign", arguments->assign,
          "Where the reassignment fits run: opencl (default: kernels/assign.cl on --device) or "
          "cpu (the C++ reference path)");
      command->add_option("--device", arguments->device,
                          "OpenCL device for --assign opencl: a substring of 'platform / device' "
                          "(default RELUME_DEVICE, else the first GPU, else PoCL)");
      command->add_option("--weights-precision", arguments->weights_precision,
                          "Stored W: quantized (default: integers times one step, the coarsest "
                          "within --quantization-budget), float32 or float16");
      command->add_option("--residual-precision", arguments->residual_precision,
                          "Stored residual values: quantized (default), float32 or float16");
      command->add_option("--bases-precision", arguments->bases_precision,
                          "Stored bases: quantized (default: 8 to 16 bits per value with a "
                          "scale per basis function) or float32");
      command
          ->add_option("--quantization-budget", arguments->quantization_budget,
                       "How much quantization may add to the error (paper Eq. 16) over the "
                       "stored functions, relative (0.01: 1%)")
          ->capture_default_str();
      command->add_option(
          "--term-budget", arguments->term_budget,
          "With quantized storage, how much dropping the basis terms that clusters of dim or "
          "simple functions do not need may add to the error (Eq. 16), relative: the terms that "
          "cost the most bytes per error go first. Default 0 (every cluster keeps all --terms); "
          "a rate target (--target-bytes, --target-psnr) tries 0 and 0.1 and keeps the better. "
          "Pays on noisy whole frames (docs/compression.md, 'Terms per cluster')");
      command->add_option(
          "--report", arguments->report,
          "Write a JSON report (times, iterations, bytes, errors, sparseness, memory)");
      command->add_option(
          "--target-error", arguments->target_error,
          "Choose terms, clusters and per-function residual lengths that reach this "
          "relative error (paper Eq. 16, masked functions) with the fewest bytes");
      command->add_option("--target-bytes", arguments->target_bytes,
                          "Rate control: choose terms, clusters and the residual entries kept "
                          "for the lowest error (Eq. 16) in a container of at most N bytes; the "
                          "report's rate_target lists every point tried");
      command->add_option("--target-bytes-per-pixel", arguments->target_bytes_per_pixel,
                          "Rate control as --target-bytes, for B bytes per pixel of the frame "
                          "(B x width x height bytes), e.g. 0.5");
      command->add_option("--target-psnr", arguments->target_psnr,
                          "Rate control: the smallest container whose 8-bit PSNR (dB, over "
                          "--target-region; --psnr-white) reaches DB, e.g. 40");
      command
          ->add_option("--target-region", arguments->target_region,
                       "Where --target-psnr is measured: frame (every pixel) or mask (inside "
                       "--psnr-mask, else the field's mask)")
          ->check(CLI::IsMember({"frame", "mask"}))
          ->capture_default_str();
      command
          ->add_option("--psnr-white", arguments->psnr_white,
                       "The field value that is 255 in the report's 8-bit PSNR (1 for fields of "
                       "8-bit or normalised images)")
          ->capture_default_str();
      command->add_option("--psnr-mask", arguments->psnr_mask,
                          "A mask image (non-zero = inside) for the report's masked PSNR and "
                          "--target-region mask, e.g. the object's mask when the whole frame "
                          "is compressed (default: the field's mask)");
      command->add_flag("--resume", arguments->resume,
                        "Continue from OUT.checkpoint, written after every clustering iteration "
                        "(of the sample's clustering when the plan is streamed)");
      command->add_option(
          "--scratch", arguments->scratch,
          "Folder of the scratch file a streamed compression keeps its rows in (float16, up to "
          "functions x lights x 2 bytes; removed at the end, on error and on Ctrl-C). Default: "
          "the output's folder. A field that does not fit --memory-limit (a global option; "
          "default three quarters of the available memory) is compressed streamed: read in "
          "strips, clustered on a sample, refined and built in passes over the strips; the "
          "plan is printed and is in the report");
      add_field_input_options(*command, arguments->field_input);
      command->callback([arguments] { run_compress(*arguments); });
    }};

}  // namespace
}  // namespace relume
