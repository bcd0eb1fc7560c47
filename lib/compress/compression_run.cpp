// Implementation of the compression run and of the public compress_file, compress_with_report and
// compress (relume/compress.hpp).
#include "compress/compression_run.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <relume/error.hpp>

#include "compress/checkpoint.hpp"
#include "compress/compress_settings.hpp"
#include "compress/compression_report.hpp"
#include "compress/compression_target.hpp"
#include "compress/rank_exchange.hpp"
#include "compress/rate_control.hpp"
#include "compress/run_report_sections.hpp"
#include "container/container.hpp"
#include "container/container_strips.hpp"
#include "core/console.hpp"
#include "core/elapsed_time.hpp"
#include "core/memory_budget.hpp"
#include "core/parallel.hpp"
#include "core/progress.hpp"
#include "core/ranks.hpp"
#include "field/field_strips.hpp"
#include "field/input_encoding.hpp"
#include "field/load_with_progress.hpp"
#include "field/mask_file.hpp"

namespace relume {
namespace {

namespace fs = std::filesystem;

// The run's own memory limit (CompressOptions::memory_limit) for its duration, the process's
// before and after.
class MemoryLimitScope {
 public:
  explicit MemoryLimitScope(std::uint64_t bytes) : set_(bytes > 0) {
    if (!set_) return;
    const MemoryBudget before = memory_budget();
    before_ = before.source == "--memory-limit" ? before.bytes : 0;
    set_memory_limit(bytes);
  }
  ~MemoryLimitScope() {
    if (set_) set_memory_limit(before_);
  }
  MemoryLimitScope(const MemoryLimitScope&) = delete;
  MemoryLimitScope& operator=(const MemoryLimitScope&) = delete;

 private:
  bool set_;
  std::uint64_t before_ = 0;
};

// The budget the run plans with: the limit as given (per rank under mpirun), else three quarters
// of what the system says is available, shared by the ranks on this machine.
std::pair<std::uint64_t, std::string> planning_budget() {
  const MemoryBudget budget = memory_budget();
  if (budget.source == "--memory-limit") return {budget.bytes, budget.source};
  const int sharing = process_ranks().local_size();
  std::string source = "three quarters of " + budget.source;
  if (sharing > 1) source += ", over the " + std::to_string(sharing) + " ranks on this machine";
  return {budget.bytes / 4 * 3 / std::uint64_t(sharing), source};
}

FieldLoadOptions load_options(const std::string& input, const CompressOptions& options,
                              bool quiet) {
  const InputEncodingDecision decision =
      decide_input_encoding(fs::path(input), parse_input_encoding(options.input_encoding));
  if (!quiet) note("%s: input %s", input.c_str(), decision.reason.c_str());
  FieldLoadOptions load;
  load.image.eight_bit = decision.encoding;
  load.threads = options.threads;
  load.mask_file = options.mask_file;
  load.use_mask = options.use_mask;
  return load;
}

RateTarget rate_target(const CompressOptions& asked, const std::string& solver,
                       const ReflectanceField& field, const std::vector<std::uint8_t>& psnr_mask) {
  RateTarget target;
  target.bytes = asked.target_bytes;
  if (asked.target_bytes_per_pixel > 0)
    target.bytes = std::uint64_t(std::floor(asked.target_bytes_per_pixel * double(field.pixels())));
  target.psnr = asked.target_psnr;
  target.psnr_white = asked.psnr_white;
  // Unless given, the term budgets 0 and 0.1 and the quantization budgets 1%, 10% and 100%.
  const std::vector<double> term_budgets = asked.term_budget >= 0
                                               ? std::vector<double>{asked.term_budget}
                                               : std::vector<double>{0.0, 0.1};
  const std::vector<double> quantization_budgets =
      asked.quantization_budget > 0 ? std::vector<double>{asked.quantization_budget}
                                    : std::vector<double>{default_quantization_budget, 0.1, 1.0};
  target.stored_as.clear();
  for (const double term_budget : term_budgets)
    for (const double quantization_budget : quantization_budgets)
      target.stored_as.push_back({term_budget, quantization_budget});
  // The whole frame, or the mask: psnr_mask's, else the field's (an empty region).
  target.region = asked.target_region == "frame"
                      ? std::vector<std::uint8_t>(std::size_t(field.pixels()), 1)
                      : psnr_mask;
  target.clustered = asked.target_models != "one-basis";
  target.one_basis = asked.target_models != "clustered";
  target.parameters_json = [solver](const CompressionOptions& options,
                                    const CompressionStats& stats) {
    return compression_parameters(options, stats, solver).dump();
  };
  return target;
}

// One run: the settings, what it read and made, and the seconds of each phase.
class CompressionRunner {
 public:
  CompressionRunner(const CompressOptions& asked, OpenClAssigner* assigner)
      : asked_(asked), settings_(compress_settings(asked)), assigner_(assigner) {
    if (assigner_) settings_.compression.clustering.assign = assigner_->function();
    container_ = settings_.precision.container_options();
  }

  // `input` into the container `output`; the report is empty on the ranks other than the root.
  CompressionReport run_file(const std::string& input, const fs::path& output) {
    input_ = input;
    output_ = output;
    plan_and_read();
    if (!cluster_and_store()) return {};
    measure_streamed();
    write();
    measure_in_memory();
    return finish();
  }

  CompressionResult run_in_memory(const ReflectanceField& field) {
    input_ = "memory";
    field_ = &field;
    read_psnr_mask(field);
    cluster_and_store();
    container_.parameters_json = parameters().dump();
    layout_ = plan_container(stored_, container_);
    measure_in_memory();
    CompressionResult result;
    result.report = finish();
    result.field = std::move(stored_);
    result.container = container_;
    return result;
  }

 private:
  void inform(const char* text) const {
    if (!asked_.quiet) note("compress: %s", text);
  }
  void time_phase(const char* phase, Clock::time_point since) {
    seconds_[phase] = seconds_since(since);
  }
  unsigned threads() const { return settings_.compression.clustering.threads; }
  nlohmann::ordered_json parameters() const {
    return compression_parameters(settings_.compression, stats_, settings_.solver);
  }

  void read_psnr_mask(const ReflectanceField& shape) {
    if (!asked_.psnr_mask.empty())
      psnr_mask_ = read_mask(asked_.psnr_mask, shape.width, shape.height);
  }

  // The plan: in memory when the field fits the budget, else streamed in strips; then the field
  // is loaded, or opened for strips.
  void plan_and_read() {
    const FieldLoadOptions load = load_options(input_, asked_, asked_.quiet);
    reader_ = std::make_unique<FieldStripReader>(input_, load);
    const auto [budget, budget_source] = planning_budget();
    const fs::path scratch_folder =
        asked_.scratch.empty() ? fs::absolute(output_).parent_path() : asked_.scratch;
    // Several ranks (mpirun) always stream: each reads its own band of pixel rows.
    plan_ = plan_compression(reader_->header(), settings_.compression, budget, budget_source,
                             threads(), scratch_folder, process_ranks().size() > 1);
    inform(plan_->describe().c_str());
    if (plan_->streamed) {
      check_streamable(asked_, settings_.compression);
      // Unless refine_iterations says otherwise, as many passes over all functions as the
      // in-memory path's L1 iterations (each pass is one reassignment and one F-step).
      settings_.compression.refine_iterations =
          asked_.refine >= 0 ? asked_.refine : settings_.compression.clustering.max_iterations;
    } else {
      reader_.reset();  // the images are read whole instead
      loaded_ = load_field_with_progress(input_, load);
      field_ = &*loaded_;
    }
    const ReflectanceField& shape = field_ ? *field_ : reader_->header();
    seconds_["load"] = seconds_since(start_);
    if (!asked_.quiet)
      note("compress: %s: %dx%d, %d channels, %d lights, %s in %.2f s", input_.c_str(), shape.width,
           shape.height, shape.channels, shape.lights(), field_ ? "loaded" : "opened",
           seconds_["load"]);
    read_psnr_mask(shape);
  }

  // A checkpoint to continue from, when asked and one exists; the hook that writes them.
  IterationHook checkpoints() {
    checkpoint_ = output_.string() + ".checkpoint";
    fingerprint_ = checkpoint_fingerprint(input_, asked_, settings_.compression);
    if (plan_ && plan_->streamed)
      fingerprint_ += " streamed sample " + std::to_string(plan_->sample_rows) + " ranks " +
                      std::to_string(process_ranks().size());
    if (asked_.resume && fs::exists(checkpoint_)) {
      resume_ = read_checkpoint(checkpoint_, fingerprint_);
      if (!asked_.quiet)
        note("compress: resuming from %s (%zu iterations done)", checkpoint_.c_str(),
             resume_->iterations.size());
    }
    return [this](const ClusterModel& model, const IterationRecord& record) {
      write_checkpoint(checkpoint_, fingerprint_, model, stats_.clustering.iterations);
      if (!asked_.quiet)
        note(
            "compress: iteration %d: L1 objective %.6g, %zu of %zu functions changed cluster, "
            "%zu pixels' channels moved into one cluster, %d clusters, %.2f s",
            record.iteration, record.objective, record.changed, model.assignment.size(),
            record.split_pixels, record.clusters, record.seconds);
    };
  }

  // Clusters and stores the field as the plan and the targets say; false on the ranks that
  // neither write nor report.
  bool cluster_and_store() {
    const IterationHook hook = output_.empty() ? IterationHook{} : checkpoints();
    const ClusteringResume* resume = resume_ ? &*resume_ : nullptr;
    auto quantize_start = Clock::now();
    if (plan_ && plan_->streamed) {
      if (!cluster_streamed(hook, resume)) return false;
      quantize_start = quantize_start_;
    } else if (asked_.target_error > 0 || has_rate_target(asked_)) {
      const auto search_start = Clock::now();
      search_target();
      time_phase("target_search", search_start);
      quantize_start = quantize_start_;
    } else {
      compressed_ = compress_field(*field_, settings_.compression, stats_, hook, resume);
      quantize_start = Clock::now();
      stored_ = compressed_;
      quantization_ = store_with_precision(*field_, stored_, settings_.precision);
    }
    time_phase("quantize", quantize_start);
    return true;
  }

  void search_target() {
    const QuantizationBudget budget = settings_.precision.quantization_budget();
    const QuantizationBudget* asked_budget = settings_.precision.quantizes() ? &budget : nullptr;
    TargetSearch search =
        asked_.target_error > 0
            ? compress_to_target_error(*field_, settings_.compression, asked_.target_error,
                                       container_, asked_budget, stats_)
            : compress_to_rate_target(*field_, settings_.compression,
                                      rate_target(asked_, settings_.solver, *field_, psnr_mask_),
                                      container_, asked_budget, stats_);
    quantize_start_ = Clock::now();
    compressed_ = std::move(search.field);  // already quantized
    stored_ = quantize_for_container(compressed_, container_);
    quantization_ = search.quantization;
    settings_.compression = search.options;
    target_key_ = asked_.target_error > 0 ? "target_error" : "rate_target";
    target_choice_ = search.explanation;
  }

  bool cluster_streamed(const IterationHook& hook, const ClusteringResume* resume) {
    Ranks& ranks = process_ranks();
    StreamedCompression result =
        compress_streamed(*reader_, settings_.compression, *plan_, stats_, streamed_.emplace(),
                          output_.filename().string() + ".scratch", hook, resume);
    streamed_bands_ = result.bands;
    strip_file_ = std::move(result.strips);
    band_strips_ = result.band_strips;
    if (!ranks.root()) {  // the root writes and reports; the others measure their bands
      if (strip_file_) broadcast_strip_storage(ranks, strip_storage_);
      measure_streamed();
      return false;
    }
    quantize_start_ = Clock::now();
    float32_masked_ = result.float32_masked;
    if (strip_file_) {
      strip_storage_ = choose_strip_storage(result.original_sample, result.sampled, *strip_file_,
                                            settings_.precision, quantization_);
      broadcast_strip_storage(ranks, strip_storage_);
      stored_on_disk_ = stored_strips(*strip_file_, strip_storage_);
    } else {
      stored_ = std::move(result.field);
      quantization_ = store_with_precision_on_strips(result.original_sample, result.sample_rows,
                                                     stored_, settings_.precision);
    }
    return true;
  }

  // A streamed run measures its error before the root writes, strip by strip: the other ranks
  // measure their bands meanwhile, then wait while the root writes on their cores too.
  void measure_streamed() {
    if (!plan_ || !plan_->streamed) return;
    const auto start = Clock::now();
    const bool quiet = settings_.compression.clustering.quiet;
    errors_ =
        strip_file_
            ? measure_errors_on_disk(*reader_, streamed_bands_, plan_->strip_rows, *strip_file_,
                                     band_strips_, strip_storage_, stats_.residual_entries,
                                     asked_.psnr_white, psnr_mask_, threads(), quiet)
            : measure_streamed_errors(*reader_, streamed_bands_, plan_->strip_rows, stored_,
                                      stats_.residual_entries, asked_.psnr_white, psnr_mask_,
                                      threads(), quiet);
    time_phase("error_measure", start);
  }

  void write() {
    const auto start = Clock::now();
    container_.parameters_json = parameters().dump();
    {
      const LocalCoresLease lease(process_ranks());
      container_.coding_threads = lease.threads(threads());
      if (stored_on_disk_) {
        layout_ =
            write_container_strips(output_, *stored_on_disk_, container_, plan_->scratch_folder);
      } else {
        write_container(output_, stored_, container_);
        layout_ = describe_container(output_);
      }
    }
    fs::remove(checkpoint_);
    time_phase("write", start);
  }

  // Whether the stored field holds the values compressed_ computed (no quantization, no float16).
  bool stored_as_computed() const {
    return !quantization_ && container_.weights != ValuePrecision::float16 &&
           container_.residual != ValuePrecision::float16;
  }

  void measure_in_memory() {
    if (!field_) return;
    const auto start = Clock::now();
    errors_ = measure_field_errors(*field_, stored_, stats_.residual_entries, asked_.psnr_white,
                                   psnr_mask_, threads());
    float32_masked_ = stored_as_computed()
                          ? errors_.masked
                          : relative_error(*field_, compressed_, true, all_residual_entries,
                                           threads());
    time_phase("error_measure", start);
  }

  CompressionReport finish() {
    CompressionReportInputs inputs;
    inputs.threads = resolve_thread_count(threads());
    inputs.errors = errors_;
    inputs.input = input_;
    inputs.output = output_.string();
    // What the report needs of the stored field: its shape, lights and precisions.
    const CompressedField& stored_shape = stored_on_disk_ ? stored_on_disk_->shell : stored_;
    inputs.compressed = &stored_shape;
    inputs.options = &settings_.compression;
    inputs.stats = &stats_;
    inputs.layout = layout_;
    inputs.extra_seconds = seconds_;
    inputs.solver = settings_.solver;
    inputs.assignment_device = assigner_ ? assigner_->device_label() : "cpu";
    inputs.psnr_white = asked_.psnr_white;
    inputs.total_seconds = seconds_since(start_);
    nlohmann::ordered_json report = compression_report(inputs);
    if (plan_) report["plan"] = plan_json(*plan_);
    if (streamed_) report["streamed"] = streamed_json(*streamed_);
    if (!target_choice_.is_null()) report[target_key_] = target_choice_;
    if (!stored_as_computed()) {
      const double quantization_error =
          field_ ? relative_error(compressed_, stored_, all_residual_entries, inputs.threads).mean
                 : std::numeric_limits<double>::quiet_NaN();
      report["precision_cost"] =
          precision_cost_json(report, stored_shape, container_, settings_.precision, quantization_,
                              float32_masked_.mean, quantization_error);
    }
    return public_report(report);
  }

  CompressionReport public_report(const nlohmann::ordered_json& json) const {
    CompressionReport report;
    report.input = input_;
    report.output = output_.string();
    report.bytes = json["bytes"].get<std::uint64_t>();
    report.bytes_per_pixel = json["bytes_per_pixel"].get<double>();
    report.ratio = json["ratio"].get<double>();
    report.error_masked = json["error_masked"].get<double>();
    report.error_all = json["error_all"].get<double>();
    const auto psnr = [&](const char* key) {
      const auto& value = json["psnr_8bit"][key];
      return value.is_null() ? std::numeric_limits<double>::infinity() : value.get<double>();
    };
    report.psnr_frame = psnr("whole_frame");
    report.psnr_mask = psnr("mask");
    report.clusters = stats_.clusters;
    report.seconds = json["seconds"].get<double>();
    report.summary = summary_line(json, stats_.clusters);
    report.json = json.dump(2);
    return report;
  }

  const CompressOptions& asked_;
  CompressSettings settings_;
  OpenClAssigner* assigner_;
  ContainerOptions container_;
  Clock::time_point start_ = Clock::now();
  std::string input_;
  fs::path output_;  // empty: a run in memory

  std::optional<CompressionPlan> plan_;  // none for a field given in memory
  std::unique_ptr<FieldStripReader> reader_;
  std::optional<ReflectanceField> loaded_;
  const ReflectanceField* field_ = nullptr;  // held in memory (loaded or given)
  std::vector<std::uint8_t> psnr_mask_;

  fs::path checkpoint_;
  std::string fingerprint_;
  std::optional<ClusteringResume> resume_;

  CompressionStats stats_;
  // In memory, `compressed_` stays for the report's cost of the rounding (a streamed run keeps no
  // float32 copy: its Eq. 16 error was measured as it was built).
  CompressedField compressed_, stored_;
  std::optional<QuantizationChoice> quantization_;
  Clock::time_point quantize_start_;
  RelativeError float32_masked_;
  nlohmann::ordered_json target_choice_;
  const char* target_key_ = "rate_target";

  // A streamed run: its trace, every rank's pixel rows, and with the compressed field on disk
  // this rank's strip file (the root's has every rank's strips), how they are stored and at the
  // root the stored field that is written (`stored_` stays empty).
  std::optional<StreamedTrace> streamed_;
  std::vector<int> streamed_bands_;
  std::unique_ptr<CompressedStripFile> strip_file_;
  std::size_t band_strips_ = 0;
  StripStorage strip_storage_;
  std::optional<CompressedFieldStrips> stored_on_disk_;

  FieldErrors errors_;
  ContainerLayout layout_;
  std::map<std::string, double> seconds_;
};

}  // namespace

std::unique_ptr<OpenClAssigner> assigner_for(const CompressOptions& options) {
  const CompressSettings settings = compress_settings(options);
  if (settings.compression.method == CompressionMethod::cpca) {
    if (!options.quiet) note("compress: clustered PCA (least-squares fits on the CPU)");
    return nullptr;
  }
  std::unique_ptr<OpenClAssigner> assigner =
      make_assigner(options.assign, options.device, settings.compression.clustering);
  if (!options.quiet)
    note("compress: reassignment fits on %s",
         assigner ? assigner->device_label().c_str() : "the CPU (C++ path)");
  return assigner;
}

CompressionReport compress_file_with(const std::string& input, const fs::path& output,
                                     const CompressOptions& options, OpenClAssigner* assigner) {
  const MemoryLimitScope limit(options.memory_limit);
  const ProgressListenerScope listening(options.progress);
  return CompressionRunner(options, assigner).run_file(input, output);
}

CompressionReport compress_file(const std::string& input, const fs::path& output,
                                const CompressOptions& options) {
  compress_settings(options);  // bad options cost no device set-up
  const std::unique_ptr<OpenClAssigner> assigner = assigner_for(options);
  return compress_file_with(input, output, options, assigner.get());
}

CompressionResult compress_with_report(const ReflectanceField& field,
                                       const CompressOptions& options) {
  const std::unique_ptr<OpenClAssigner> assigner = assigner_for(options);
  const MemoryLimitScope limit(options.memory_limit);
  const ProgressListenerScope listening(options.progress);
  return CompressionRunner(options, assigner.get()).run_in_memory(field);
}

CompressedField compress(const ReflectanceField& field, const CompressOptions& options) {
  return compress_with_report(field, options).field;
}

}  // namespace relume
