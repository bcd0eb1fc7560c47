// `relume bench`: times the relighting kernels on every OpenCL device (or the one asked for) and
// the CPU reference, on a seeded random compressed field of a stated shape: GEMV, residual SpMV,
// full relight and batched relight, each with bytes moved, GB/s and the ratio to the device's own
// peak (the faster of a streaming read and a copy on the same device). Medians of several runs.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <optional>

#include "atomic_file.hpp"
#include "bandwidth_ceiling.hpp"
#include "command_registry.hpp"
#include "compressed_relight_reference.hpp"
#include "error.hpp"
#include "opencl_relighter.hpp"
#include "parallel.hpp"
#include "progress.hpp"
#include "random_compressed_field.hpp"

namespace relume {
namespace {

struct BenchOptions {
  std::vector<std::string> devices;
  std::string json;
  int frames = 16;
  int repeats = 9;
  int residual_cap = full_residual;
  RandomFieldShape shape;
  std::uint64_t ceiling_mib = 256;
  bool reference = true;
  unsigned threads = 0;
  OpenClRelighterOptions relighter;
};

struct BenchRecord {
  std::string platform;
  std::string device;
  std::string kernel;
  std::uint64_t bytes = 0;  // per run
  double seconds = 0;       // median per run
  std::vector<double> run_seconds;
  std::optional<double> peak_gbps;
  int frames = 0;                      // frames per run; 0 for kernels that make no frame
  std::optional<double> wall_seconds;  // median of whole calls (upload + kernels + read-back)
  std::string pattern;                 // access pattern of a ceiling kernel
  std::optional<int> residual_cap;     // for kernels that read the residual

  double gbps() const { return 1e-9 * double(bytes) / seconds; }
};

BenchRecord make_record(const std::string& platform, const std::string& device,
                        const std::string& kernel, std::uint64_t bytes,
                        std::vector<double> run_seconds, std::optional<double> peak_gbps,
                        int frames = 0) {
  BenchRecord record{platform,    device,    kernel, bytes,        median_seconds(run_seconds),
                     run_seconds, peak_gbps, frames, std::nullopt, "",
                     std::nullopt};
  return record;
}

template <typename Call>
double timed(Call call) {
  const auto start = std::chrono::steady_clock::now();
  call();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// The faster access pattern of a ceiling kernel, by the median of a few runs.
template <typename Time>
AccessPattern faster_pattern(Time time) {
  std::vector<double> blocked, strided;
  for (int i = 0; i < 4; ++i) {
    blocked.push_back(time(AccessPattern::blocked));
    strided.push_back(time(AccessPattern::strided));
  }
  return median_seconds(blocked) <= median_seconds(strided) ? AccessPattern::blocked
                                                            : AccessPattern::strided;
}

// Timed runs of the OpenCL kernels on one device. Each round runs the ceiling kernels and then
// every relighting kernel once, so that a shared machine's changing load hits them alike.
std::vector<BenchRecord> bench_device(const OpenClDevice& device, const CompressedField& field,
                                      const std::vector<LightRgb>& lights,
                                      const BenchOptions& options, ProgressReporter& progress) {
  OpenClContext context(device);
  BandwidthProbe probe(context, options.ceiling_mib << 20);
  const AccessPattern read_pattern =
      faster_pattern([&](AccessPattern pattern) { return probe.time_read(pattern); });
  const AccessPattern copy_pattern =
      faster_pattern([&](AccessPattern pattern) { return probe.time_copy(pattern); });

  OpenClRelighter relighter(context, field, options.relighter);
  const int cap = options.residual_cap;
  const std::vector<LightRgb> batch(lights.begin(), lights.begin() + options.frames);
  // Builds the programs and touches every buffer once; later calls reuse the images.
  std::vector<Image> frame(1), frames;
  relighter.relight_batch_into({lights[0]}, cap, frame);
  relighter.relight_residual_into(lights[0], cap, frame[0]);
  relighter.relight_batch_into(batch, cap, frames);

  std::vector<double> read, copy, gemv, relight, relight_wall, spmv, batched, batched_wall;
  std::uint64_t gemv_bytes = 0, relight_bytes = 0, spmv_bytes = 0, batched_bytes = 0;
  for (int r = 0; r < options.repeats; ++r) {
    read.push_back(probe.time_read(read_pattern));
    copy.push_back(probe.time_copy(copy_pattern));
    const LightRgb& light = lights[std::size_t(r) % lights.size()];
    relighter.relight_batch_into({light}, cap, frame);
    const RelightTiming& timing = relighter.last_timing();
    gemv.push_back(timing.kernel("gemv").seconds);
    gemv_bytes = timing.kernel("gemv").bytes;
    relight.push_back(timing.kernel_seconds());
    relight_bytes = timing.kernel_bytes();
    relight_wall.push_back(timing.wall_seconds);
    relighter.relight_residual_into(light, cap, frame[0]);
    spmv.push_back(relighter.last_timing().kernel("spmv").seconds);
    spmv_bytes = relighter.last_timing().kernel("spmv").bytes;
    relighter.relight_batch_into(batch, cap, frames);
    batched.push_back(relighter.last_timing().kernel_seconds());
    batched_wall.push_back(relighter.last_timing().wall_seconds);
    batched_bytes = relighter.last_timing().kernel_bytes();
    progress.advance();
  }
  const std::string platform = device.platform_name, name = device.device_name;
  const double read_gbps = 1e-9 * double(probe.read_bytes(read_pattern)) / median_seconds(read);
  const double copy_gbps = 1e-9 * double(probe.copy_bytes()) / median_seconds(copy);
  const double peak = std::max(read_gbps, copy_gbps);
  std::vector<BenchRecord> records;
  records.push_back(
      make_record(platform, name, "read", probe.read_bytes(read_pattern), read, peak));
  records.back().pattern = access_pattern_name(read_pattern);
  records.push_back(make_record(platform, name, "copy", probe.copy_bytes(), copy, peak));
  records.back().pattern = access_pattern_name(copy_pattern);
  records.push_back(make_record(platform, name, "gemv", gemv_bytes, gemv, peak));
  records.push_back(make_record(platform, name, "spmv", spmv_bytes, spmv, peak));
  records.push_back(make_record(platform, name, "relight", relight_bytes, relight, peak, 1));
  records.back().wall_seconds = median_seconds(relight_wall);
  records.push_back(
      make_record(platform, name, "relight_batched", batched_bytes, batched, peak, options.frames));
  records.back().wall_seconds = median_seconds(batched_wall);
  for (auto& record : records)
    if (record.kernel != "read" && record.kernel != "copy" && record.kernel != "gemv")
      record.residual_cap = cap;
  return records;
}

// Timed runs of the double-precision CPU reference. Its bytes count what it reads from the
// CompressedField arrays (CSR residual with 32-bit light indices, 32-bit cluster ids).
std::vector<BenchRecord> bench_reference(const CompressedField& field,
                                         const std::vector<LightRgb>& lights,
                                         const BenchOptions& options,
                                         std::optional<double> cpu_peak,
                                         ProgressReporter& progress) {
  const CompressedRelightReference reference(field);
  const std::string platform = "reference";
  const std::string device =
      "C++ double, " + std::to_string(resolve_thread_count(options.threads)) + " threads";
  const std::uint64_t rows = field.stored_rows();
  std::uint64_t used_entries = 0;
  for (std::size_t s = 0; s < rows; ++s)
    used_entries +=
        std::min<std::uint64_t>(field.residual.row_offsets[s + 1] - field.residual.row_offsets[s],
                                std::uint64_t(options.residual_cap));
  const std::uint64_t light_bytes = std::uint64_t(field.lights) * 3 * sizeof(float);
  const std::uint64_t gemv_bytes = field.bases.size() * sizeof(float) + light_bytes;
  const std::uint64_t residual_bytes = used_entries * 8 + rows * (4 + 4 + 4) + light_bytes;
  const std::uint64_t relight_bytes =
      gemv_bytes + residual_bytes + rows * (4 + 4 * std::uint64_t(field.terms));

  std::vector<double> gemv, spmv, relight;
  for (int r = 0; r < options.repeats; ++r) {
    const LightRgb& light = lights[std::size_t(r) % lights.size()];
    gemv.push_back(
        timed([&] { cluster_light_products(field, light_in_field_basis(field, light)); }));
    spmv.push_back(timed([&] {
      reference.relight(light, options.residual_cap, RelightTerms::residual_only, options.threads);
    }));
    relight.push_back(timed([&] {
      reference.relight(light, options.residual_cap, RelightTerms::all, options.threads);
    }));
    progress.advance();
  }
  std::vector<BenchRecord> records = {
      make_record(platform, device, "gemv", gemv_bytes, gemv, cpu_peak),
      make_record(platform, device, "spmv", residual_bytes, spmv, cpu_peak),
      make_record(platform, device, "relight", relight_bytes, relight, cpu_peak, 1)};
  records[1].residual_cap = records[2].residual_cap = options.residual_cap;
  return records;
}

nlohmann::ordered_json to_json(const BenchRecord& record) {
  nlohmann::ordered_json json = {
      {"platform", record.platform},
      {"device", record.device},
      {"kernel", record.kernel},
      {"bytes", record.bytes},
      {"seconds", record.seconds},
      {"gbps", record.gbps()},
      {"ratio_to_peak", record.peak_gbps ? nlohmann::ordered_json(record.gbps() / *record.peak_gbps)
                                         : nlohmann::ordered_json()},
      {"peak_gbps",
       record.peak_gbps ? nlohmann::ordered_json(*record.peak_gbps) : nlohmann::ordered_json()},
      {"runs", record.run_seconds.size()},
      {"run_seconds", record.run_seconds},
  };
  if (!record.pattern.empty()) json["access_pattern"] = record.pattern;
  if (record.residual_cap)
    json["residual_cap"] = *record.residual_cap == full_residual
                               ? nlohmann::ordered_json("all")
                               : nlohmann::ordered_json(*record.residual_cap);
  if (record.frames > 0) {
    json["frames"] = record.frames;
    json["frames_per_second"] = record.frames / record.seconds;
  }
  if (record.wall_seconds) {
    json["wall_seconds"] = *record.wall_seconds;
    json["wall_frames_per_second"] = record.frames / *record.wall_seconds;
  }
  return json;
}

void print_table(const std::vector<BenchRecord>& records) {
  std::printf("%-44s %-16s %10s %10s %8s %7s %9s\n", "device", "kernel", "MB/run", "ms", "GB/s",
              "%peak", "frames/s");
  for (const auto& record : records) {
    char peak[16] = "-", fps[16] = "-";
    if (record.peak_gbps)
      std::snprintf(peak, sizeof peak, "%.0f%%", 100 * record.gbps() / *record.peak_gbps);
    if (record.frames > 0) std::snprintf(fps, sizeof fps, "%.1f", record.frames / record.seconds);
    std::printf("%-44.44s %-16s %10.2f %10.3f %8.2f %7s %9s\n", record.device.c_str(),
                record.kernel.c_str(), 1e-6 * double(record.bytes), 1e3 * record.seconds,
                record.gbps(), peak, fps);
    if (record.wall_seconds)
      std::printf("%-44s %-16s %10s %10.3f %8s %7s %9.1f\n", "", "  (whole call)", "",
                  1e3 * *record.wall_seconds, "", "", record.frames / *record.wall_seconds);
  }
}

void run_bench(const BenchOptions& options) {
  if (options.frames < 1 || options.frames > options.relighter.max_batch)
    throw Error("--frames " + std::to_string(options.frames) + " (expected 1 to --max-batch " +
                std::to_string(options.relighter.max_batch) + ")");
  if (options.repeats < 1)
    throw Error("--repeats " + std::to_string(options.repeats) + " (expected at least 1)");
  if (options.residual_cap < 0)
    throw Error("--cap " + std::to_string(options.residual_cap) + " (expected 0 or more)");

  std::vector<OpenClDevice> devices;
  if (options.devices.empty()) {
    devices = list_opencl_devices();
  } else {
    for (const auto& selector : options.devices) devices.push_back(select_opencl_device(selector));
  }

  const auto& shape = options.shape;
  std::fprintf(
      stderr,
      "bench: random field %dx%dx%d, %d lights, %d clusters, %d terms, %d residual "
      "entries per function, %.0f%% stored, cap %s, %d runs each (medians)\n",
      shape.width, shape.height, shape.channels, shape.lights, shape.clusters, shape.terms,
      shape.residual_per_function, 100 * shape.stored_fraction,
      options.residual_cap == full_residual ? "all" : std::to_string(options.residual_cap).c_str(),
      options.repeats);
  const CompressedField field = random_compressed_field(shape);
  std::vector<LightRgb> lights;
  for (int i = 0; i < std::max(options.frames, options.repeats); ++i)
    lights.push_back(random_light_vector(shape.lights, shape.seed + 1000 + std::uint64_t(i)));

  const std::uint64_t per_device = std::uint64_t(options.repeats);
  ProgressReporter progress(
      "bench", per_device * devices.size() + (options.reference ? options.repeats : 0));
  std::vector<BenchRecord> records;
  std::optional<double> cpu_peak;
  for (const auto& device : devices) {
    auto device_records = bench_device(device, field, lights, options, progress);
    if (device.type == "cpu" && !cpu_peak) cpu_peak = device_records.front().peak_gbps;
    records.insert(records.end(), device_records.begin(), device_records.end());
  }
  if (options.reference) {
    auto reference_records = bench_reference(field, lights, options, cpu_peak, progress);
    records.insert(records.end(), reference_records.begin(), reference_records.end());
  }
  progress.finish();
  print_table(records);

  if (!options.json.empty()) {
    nlohmann::ordered_json json;
    json["field"] = {{"source", "random"},
                     {"width", shape.width},
                     {"height", shape.height},
                     {"channels", shape.channels},
                     {"lights", shape.lights},
                     {"clusters", shape.clusters},
                     {"terms", shape.terms},
                     {"residual_per_function", shape.residual_per_function},
                     {"stored_fraction", shape.stored_fraction},
                     {"stored_rows", field.stored_rows()},
                     {"seed", shape.seed}};
    json["residual_cap"] = options.residual_cap == full_residual
                               ? nlohmann::ordered_json("all")
                               : nlohmann::ordered_json(options.residual_cap);
    json["batch_frames"] = options.frames;
    json["repeats"] = options.repeats;
    json["records"] = nlohmann::ordered_json::array();
    for (const auto& record : records) json["records"].push_back(to_json(record));
    write_file_atomically(options.json, json.dump(2) + "\n");
  }
}

const CommandRegistration registration{
    90, [](CLI::App& app) {
      auto options = std::make_shared<BenchOptions>();
      auto* command = app.add_subcommand(
          "bench",
          "Time the relighting kernels (GEMV, residual SpMV, relight, batched relight) and the "
          "device's read/copy bandwidth ceiling on a seeded random compressed field");
      command->add_option(
          "--device", options->devices,
          "OpenCL device to bench: part of \"platform / device\" as `relume devices` "
          "lists it; repeat for several (default: every device)");
      command->add_option("--json", options->json, "Also write every record to this JSON file");
      command->add_option("--frames", options->frames,
                          "Light vectors relit per pass by the batched kernel (default 16)");
      command->add_option(
          "--repeats", options->repeats,
          "Timed rounds, each running every kernel once; medians are reported (default 9)");
      command->add_option("--cap", options->residual_cap,
                          "Residual entries used per function (default: all stored)");
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
      command->add_option("--seed", options->shape.seed, "Seed of the random field (default 1)");
      command->add_option("--ceiling-mib", options->ceiling_mib,
                          "Buffer size of the read/copy ceiling kernels in MiB (default 256)");
      command->add_option(
          "--work-group", options->relighter.work_group_rows,
          "Rows per work-group of the row kernels (default: 256 on CPUs, 64 otherwise)");
      command->add_option("--slice", options->relighter.slice_rows,
                          "Rows per slice of the W and residual layout (default: the row vector on "
                          "CPUs, 32 otherwise)");
      command->add_option(
          "--row-vector", options->relighter.row_vector,
          "Rows per work-item of single-frame passes: 1, 4, 8 or 16 (default: 16 on "
          "CPUs, 1 otherwise)");
      command->add_option("--max-batch", options->relighter.max_batch,
                          "Most frames one pass may relight (default 32)");
      command->add_flag("!--no-reference", options->reference,
                        "Skip the double-precision CPU reference (default: bench it too)");
      command->add_option("--threads", options->threads,
                          "Threads of the CPU reference (default: all cores)");
      command->callback([options] { run_bench(*options); });
    }};

}  // namespace
}  // namespace relume
