// `relume bench`: times the relighting kernels on every OpenCL device (or the ones asked for) and
// the CPU reference: GEMV, residual SpMV, full relight and batched relight on a seeded random
// compressed field of a stated shape, or relight at the residual caps of the paper's Table 1 on a
// container (--container), with each cap's error; and the cluster assignment kernel on seeded
// random rows. The batched relight runs at each batch size of --frames. Every record has bytes
// moved, GB/s and the ratio to the device's own peak (the faster of a streaming read and a copy on
// the same device). Medians of several runs.
#include <algorithm>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>
#include <relume/error.hpp>

#include "command_registry.hpp"
#include "commands/bench/bench_container_sweep.hpp"
#include "commands/bench/bench_report.hpp"
#include "commands/bench/bench_runs.hpp"
#include "core/json_report.hpp"
#include "core/progress.hpp"
#include "model/basis_alignment.hpp"
#include "model/quantization.hpp"
#include "model/random_compressed_field.hpp"
#include "options/renderer_options.hpp"

namespace relume {
namespace {

// `options.repeats` rounds on one device, each running the ceiling kernels, every relighting kernel
// at every point and the assignment kernel once.
std::vector<BenchRecord> bench_device(const OpenClDevice& device, const RelightSubject& subject,
                                      const std::vector<LightRgb>& lights,
                                      const AssignmentProblem* problem, const BenchOptions& options,
                                      ProgressReporter& progress) {
  OpenClContext context(device);
  CeilingRuns ceilings(context, options.ceiling_mib << 20);
  OpenClRelighter relighter(context, subject.field, options.relighter);
  std::vector<std::vector<LightRgb>> batches;
  for (const int frames : options.frames)
    batches.emplace_back(lights.begin(), lights.begin() + frames);
  RelightRuns relights(relighter, subject.points, std::move(batches), subject.with_parts);
  std::optional<AssignmentRuns> assignment;
  if (problem) assignment.emplace(device, *problem);
  for (int r = 0; r < options.repeats; ++r) {
    ceilings.run_round();
    relights.run_round(lights[std::size_t(r) % lights.size()]);
    if (assignment) assignment->run_round();
    progress.advance();
  }
  const double peak = ceilings.peak_gbps();
  std::vector<BenchRecord> records = ceilings.records();
  for (auto& record : relights.records(device, peak)) records.push_back(std::move(record));
  if (assignment) records.push_back(assignment->record(device, peak));
  return records;
}

void check_options(const BenchOptions& options) {
  if (options.frames.empty()) throw Error("--frames needs at least one batch size");
  for (const int frames : options.frames)
    if (frames < 1 || frames > options.relighter.max_batch)
      throw Error("--frames " + std::to_string(frames) + " (expected 1 to --max-batch " +
                  std::to_string(options.relighter.max_batch) + ")");
  if (options.repeats < 1)
    throw Error("--repeats " + std::to_string(options.repeats) + " (expected at least 1)");
  if (options.residual_cap < 0)
    throw Error("--cap " + std::to_string(options.residual_cap) + " (expected 0 or more)");
  if (options.assign_rows < 0)
    throw Error("--assign-rows " + std::to_string(options.assign_rows) + " (expected 0 or more)");
  if (options.assign_candidates < 1)
    throw Error("--assign-candidates " + std::to_string(options.assign_candidates) +
                " (expected at least 1)");
  if (!options.original_field.empty() && options.container.empty())
    throw Error("--field " + options.original_field + " needs --container");
  if (options.precision != "float32" && options.precision != "int16" && options.precision != "int8")
    throw Error("--precision must be float32, int16 or int8, got '" + options.precision + "'");
}

// The random field stored as a quantized field would be: W and the residual values as integers of
// the asked width (their largest |value| at 100 for int8, 30000 for int16) on aligned bases.
CompressedField random_field(const BenchOptions& options) {
  CompressedField field = random_compressed_field(options.shape);
  if (options.precision == "float32") return field;
  align_cluster_bases(field);
  const float top = options.precision == "int8" ? 100.0f : 30000.0f;
  float largest_residual = 0;
  for (float v : field.residual.values) largest_residual = std::max(largest_residual, std::abs(v));
  const float largest_weight = field.weights.size() ? field.weights.cwiseAbs().maxCoeff() : 0.0f;
  return quantize_values(field, {largest_weight > 0 ? largest_weight / top : 0.0f,
                                 largest_residual > 0 ? largest_residual / top : 0.0f, 0});
}

RelightSubject relight_subject(const BenchOptions& options) {
  RelightSubject subject;
  if (options.container.empty()) {
    subject.field = random_field(options);
    subject.points = {{options.residual_cap, {}, {}}};
    return subject;
  }
  ContainerSweep sweep =
      container_sweep(options.container, options.original_field, options.threads);
  subject.field = std::move(sweep.field);
  subject.points = std::move(sweep.points);
  subject.with_parts = false;
  return subject;
}

void run_bench(const BenchOptions& options) {
  check_options(options);
  std::vector<OpenClDevice> devices;
  if (options.devices.empty()) {
    devices = list_opencl_devices();
  } else {
    for (const auto& selector : options.devices) devices.push_back(select_opencl_device(selector));
  }

  const RelightSubject subject = relight_subject(options);
  const CompressedField& field = subject.field;
  const auto& shape = options.shape;
  if (options.container.empty())
    std::fprintf(stderr,
                 "bench: random field %dx%dx%d, %d lights, %d clusters, %d terms, %d residual "
                 "entries per function, %.0f%% stored, cap %s\n",
                 shape.width, shape.height, shape.channels, shape.lights, shape.clusters,
                 shape.terms, shape.residual_per_function, 100 * shape.stored_fraction,
                 residual_cap_text(options.residual_cap).c_str());
  else
    std::fprintf(stderr,
                 "bench: container %s: %dx%dx%d, %d lights, %d clusters, %d terms, %zu stored "
                 "rows, %zu residual entries; residual sweep, errors against %s\n",
                 options.container.c_str(), field.width, field.height, field.channels, field.lights,
                 field.clusters, field.terms, field.stored_rows(), field.residual.nonzeros(),
                 options.original_field.empty() ? "the container's full residual"
                                                : options.original_field.c_str());
  const AssignmentProblemShape assignment_shape{
      options.assign_rows,       shape.clusters, shape.terms, shape.lights,
      options.assign_candidates, false,          shape.seed};
  std::optional<AssignmentProblem> problem;
  if (options.assign_rows > 0) {
    problem = random_assignment_problem(assignment_shape);
    std::fprintf(stderr,
                 "bench: assignment of %d random rows x %d lights, %d clusters of %d terms, %d "
                 "candidates per row\n",
                 options.assign_rows, shape.lights, shape.clusters, shape.terms,
                 options.assign_candidates);
  }
  std::fprintf(stderr, "bench: %d runs each (medians)\n", options.repeats);
  std::vector<LightRgb> lights;
  const int most_frames = *std::max_element(options.frames.begin(), options.frames.end());
  for (int i = 0; i < std::max(most_frames, options.repeats); ++i)
    lights.push_back(random_light_vector(field.lights, shape.seed + 1000 + std::uint64_t(i)));

  ProgressReporter progress(
      "bench", std::uint64_t(options.repeats) * (devices.size() + (options.reference ? 1 : 0)));
  std::vector<BenchRecord> records;
  std::optional<double> cpu_peak;
  const AssignmentProblem* assignment = problem ? &*problem : nullptr;
  for (const auto& device : devices) {
    auto device_records = bench_device(device, subject, lights, assignment, options, progress);
    if (device.type == "cpu" && !cpu_peak) cpu_peak = device_records.front().peak_gbps;
    records.insert(records.end(), device_records.begin(), device_records.end());
  }
  if (options.reference) {
    auto reference_records =
        bench_reference(field, lights, subject.points, subject.with_parts, assignment,
                        options.threads, options.repeats, cpu_peak, progress);
    records.insert(records.end(), reference_records.begin(), reference_records.end());
  }
  progress.finish();
  print_record_table(records);
  if (!options.container.empty()) {
    std::printf("\nresidual sweep of %s, error against %s:\n", options.container.c_str(),
                options.original_field.empty() ? "the container's full residual"
                                               : options.original_field.c_str());
    print_sweep_table(records);
  }

  if (!options.json.empty()) {
    nlohmann::ordered_json json;
    json["field"] = field_json(options, field);
    if (options.container.empty())
      json["residual_cap"] = residual_cap_json(options.residual_cap);
    else
      json["sweep"] = sweep_json(options, subject);
    json["devices"] = nlohmann::ordered_json::array();
    for (const auto& device : devices) json["devices"].push_back(device_json(device));
    json["batch_frames"] = options.frames;
    json["repeats"] = options.repeats;
    json["assignment"] =
        problem ? nlohmann::ordered_json{{"rows", assignment_shape.rows},
                                         {"lights", assignment_shape.lights},
                                         {"clusters", assignment_shape.clusters},
                                         {"terms", assignment_shape.terms},
                                         {"candidates", assignment_shape.candidates},
                                         {"irls_iterations", IrlsSettings{}.iterations},
                                         {"seed", assignment_shape.seed}}
                : nlohmann::ordered_json();
    json["records"] = nlohmann::ordered_json::array();
    for (const auto& record : records) json["records"].push_back(to_json(record));
    write_json_report(options.json, json);
  }
}

const CommandRegistration registration{
    90, [](CLI::App& app) {
      auto options = std::make_shared<BenchOptions>();
      auto* command = app.add_subcommand(
          "bench",
          "Time the relighting kernels (GEMV, residual SpMV, relight, batched relight), the "
          "cluster assignment kernel and the device's read/copy bandwidth ceiling, on a seeded "
          "random compressed field or at the residual caps of the paper's Table 1 on a container");
      command->add_option(
          "--device", options->devices,
          "OpenCL device to bench: part of \"platform / device\" as `relume devices` "
          "lists it; repeat for several (default: every device)");
      command->add_option("--json", options->json, "Also write every record to this JSON file");
      command
          ->add_option("--frames", options->frames,
                       "Light vectors relit per pass by the batched kernel; several batch sizes, "
                       "comma-separated, give one relight_batched record each, e.g. --frames "
                       "1,4,16,64 --max-batch 64 (default 16)")
          ->delimiter(',');
      command->add_option(
          "--repeats", options->repeats,
          "Timed rounds, each running every kernel once; medians are reported (default 9)");
      command->add_option("--cap", options->residual_cap,
                          "Residual entries used per function (default: all stored; ignored with "
                          "--container)");
      command->add_option(
          "--container", options->container,
          "Relight this .relume container instead of the random field, at residual caps of 0, 3, "
          "5, 10, 20 and 30% of the lights and the full residual (relight and relight_batched "
          "records with each cap's error; no gemv/spmv records and no random field)");
      command->add_option("--field", options->original_field,
                          "With --container: measure each cap's error against this original "
                          "field (folder or .lp) over the mask (default: against the container's "
                          "full residual)");
      command->add_option("--assign-rows", options->assign_rows,
                          "Random rows of the assignment benchmark, each --lights long, with "
                          "--clusters clusters of --terms terms (default 16384; 0 skips it)");
      command->add_option("--assign-candidates", options->assign_candidates,
                          "Candidate clusters fitted per row by the assignment (default 3)");
      command->add_option("--precision", options->precision,
                          "W and residual values of the random field: float32 (default), or the "
                          "integers a quantized container holds, int16 or int8");
      command->add_option("--width", options->shape.width, "Image width (default 640)");
      command->add_option("--height", options->shape.height, "Image height (default 640)");
      command->add_option("--channels", options->shape.channels,
                          "Colour channels, 1 or 3 (default 3)");
      command->add_option("--lights", options->shape.lights, "Lights (default 253)");
      command->add_option("--clusters", options->shape.clusters, "Clusters (default 128)");
      command->add_option("--terms", options->shape.terms, "Basis terms per cluster (default 4)");
      command->add_option("--residual", options->shape.residual_per_function,
                          "Residual entries stored per function (default 12)");
      command->add_option("--stored-fraction", options->shape.stored_fraction,
                          "Share of functions stored; the rest are outside the mask (default 1)");
      command->add_option(
          "--seed", options->shape.seed,
          "Seed of the random field, assignment rows and light vectors (default 1)");
      command->add_option("--ceiling-mib", options->ceiling_mib,
                          "Buffer size of the read/copy ceiling kernels in MiB (default 256)");
      command->add_option(
          "--work-group", options->relighter.work_group_rows,
          "Rows per work-group of the row kernels (default: 1024 on CPUs, 64 otherwise)");
      command->add_option(
          "--slice", options->relighter.slice_rows,
          "Rows per slice of the W and residual layout (default on CPUs: the tallest "
          "of 4096, 2048, ... whose padding adds at most 1/8 to the residual; 32 "
          "otherwise)");
      command->add_option("--head-entries", options->relighter.head_entries,
                          "CPUs: residual entries per row kept in the slices; the rest lie in "
                          "groups of one row vector (default 24)");
      command->add_option(
          "--row-vector", options->relighter.row_vector,
          "Rows per work-item of single-frame passes: 1, 4, 8 or 16 (default: 16 on "
          "CPUs, 1 otherwise)");
      command->add_option("--max-batch", options->relighter.max_batch,
                          "Most frames one pass may relight (default 32)");
      command->add_flag("!--no-reference", options->reference,
                        "Skip the CPU reference paths: double-precision relight and the C++ "
                        "assignment (default: bench them too)");
      command->add_option("--threads", options->threads,
                          "Threads of the CPU reference and of the error measurement (default: "
                          "all cores)");
      command->callback([options] { run_bench(*options); });
    }};

}  // namespace
}  // namespace relume
