// Implementation of the `relume bench` records, their JSON and their tables.
#include "commands/bench/bench_records.hpp"

#include <algorithm>
#include <cstdio>
#include <utility>

#include "opencl/bandwidth_ceiling.hpp"  // median_seconds
#include "options/renderer_options.hpp"  // residual_cap_text

namespace relume {

BenchRecord make_record(const std::string& platform, const std::string& device,
                        const std::string& kernel, std::uint64_t bytes,
                        std::vector<double> run_seconds, std::optional<double> peak_gbps,
                        int frames) {
  BenchRecord record;
  record.platform = platform;
  record.device = device;
  record.kernel = kernel;
  record.bytes = bytes;
  record.seconds = median_seconds(run_seconds);
  record.run_seconds = std::move(run_seconds);
  record.peak_gbps = peak_gbps;
  record.frames = frames;
  return record;
}

std::optional<RooflinePosition> roofline_position(const BenchRecord& record) {
  if (record.flops == 0 || !record.work_ceiling_seconds || !record.peak_gbps ||
      *record.peak_gbps <= 0 || record.seconds <= 0)
    return std::nullopt;
  RooflinePosition position;
  position.memory_seconds = double(record.bytes) / (*record.peak_gbps * 1e9);
  position.work_seconds = *record.work_ceiling_seconds;
  position.memory_binds = position.memory_seconds >= position.work_seconds;
  position.ratio_to_binding_ceiling =
      std::max(position.memory_seconds, position.work_seconds) / record.seconds;
  return position;
}

nlohmann::ordered_json residual_cap_json(int cap) {
  return cap == all_residual_entries ? nlohmann::ordered_json("all") : nlohmann::ordered_json(cap);
}

nlohmann::ordered_json to_json(const BenchRecord& record) {
  const auto optional = [](const std::optional<double>& value) {
    return value ? nlohmann::ordered_json(*value) : nlohmann::ordered_json();
  };
  nlohmann::ordered_json json = {
      {"platform", record.platform},
      {"device", record.device},
      {"kernel", record.kernel},
      {"bytes", record.bytes},
      {"seconds", record.seconds},
      {"gbps", record.gbps()},
      {"ratio_to_peak", record.peak_gbps ? nlohmann::ordered_json(record.gbps() / *record.peak_gbps)
                                         : nlohmann::ordered_json()},
      {"peak_gbps", optional(record.peak_gbps)},
      {"runs", record.run_seconds.size()},
      {"run_seconds", record.run_seconds},
  };
  if (record.flops > 0) {
    json["flops"] = record.flops;
    json["gflops"] = 1e-9 * double(record.flops) / record.seconds;
    json["arithmetic_intensity"] = double(record.flops) / double(record.bytes);
  }
  if (const auto position = roofline_position(record)) {
    json["memory_ceiling_seconds"] = position->memory_seconds;
    json["work_ceiling_seconds"] = position->work_seconds;
    json["work_ceiling_gflops"] = 1e-9 * double(record.flops) / position->work_seconds;
    json["binding_ceiling"] = position->memory_binds ? "memory" : "work";
    json["ratio_to_binding_ceiling"] = position->ratio_to_binding_ceiling;
  }
  if (!record.pattern.empty()) json["access_pattern"] = record.pattern;
  if (!record.layout.is_null()) json["layout"] = record.layout;
  if (record.residual) {
    json["residual_cap"] = residual_cap_json(record.residual->cap);
    if (record.in_sweep()) {
      json["residual_percent"] = record.residual->percent
                                     ? nlohmann::ordered_json(*record.residual->percent)
                                     : nlohmann::ordered_json("all");
      json["error"] = *record.residual->error;
    }
  }
  if (record.frames > 0) {
    json["frames"] = record.frames;
    json["frames_per_second"] = record.frames / record.seconds;
  }
  if (record.fits > 0) {
    json["fits"] = record.fits;
    json["fits_per_second"] = double(record.fits) / record.seconds;
  }
  if (record.wall_seconds) {
    json["wall_seconds"] = *record.wall_seconds;
    if (record.frames > 0) json["wall_frames_per_second"] = record.frames / *record.wall_seconds;
    if (record.fits > 0) json["wall_fits_per_second"] = double(record.fits) / *record.wall_seconds;
  }
  return json;
}

namespace {

std::string percent_of_peak(const BenchRecord& record) {
  if (!record.peak_gbps) return "-";
  char text[16];
  std::snprintf(text, sizeof text, "%.0f%%", 100 * record.gbps() / *record.peak_gbps);
  return text;
}

// "83% mem" or "91% work": the share of the binding roof reached, and which roof binds.
std::string percent_of_binding(const BenchRecord& record) {
  const auto position = roofline_position(record);
  if (!position) return "-";
  char text[24];
  std::snprintf(text, sizeof text, "%.0f%% %s", 100 * position->ratio_to_binding_ceiling,
                position->memory_binds ? "mem" : "work");
  return text;
}

std::string intensity(const BenchRecord& record) {
  if (record.flops == 0) return "-";
  char text[16];
  std::snprintf(text, sizeof text, "%.2f", double(record.flops) / double(record.bytes));
  return text;
}

}  // namespace

void print_record_table(const std::vector<BenchRecord>& records) {
  std::printf("%-44s %-16s %10s %10s %8s %7s %7s %10s %10s %10s\n", "device", "kernel", "MB/run",
              "ms", "GB/s", "%peak", "flop/B", "%bound", "frames/s", "fits/s");
  // Frames and fits per second of a run that took `seconds`.
  const auto rates = [](const BenchRecord& record, double seconds) {
    char frames[16] = "-", fits[16] = "-";
    if (record.frames > 0) std::snprintf(frames, sizeof frames, "%.1f", record.frames / seconds);
    if (record.fits > 0) std::snprintf(fits, sizeof fits, "%.4g", double(record.fits) / seconds);
    return std::pair<std::string, std::string>(frames, fits);
  };
  for (const auto& record : records) {
    if (record.in_sweep()) continue;
    const auto [frames, fits] = rates(record, record.seconds);
    std::printf("%-44.44s %-16s %10.2f %10.3f %8.2f %7s %7s %10s %10s %10s\n",
                record.device.c_str(), record.kernel.c_str(), 1e-6 * double(record.bytes),
                1e3 * record.seconds, record.gbps(), percent_of_peak(record).c_str(),
                intensity(record).c_str(), percent_of_binding(record).c_str(), frames.c_str(),
                fits.c_str());
    if (record.wall_seconds) {
      const auto [wall_frames, wall_fits] = rates(record, *record.wall_seconds);
      std::printf("%-44s %-16s %10s %10.3f %8s %7s %7s %10s %10s %10s\n", "", "  (whole call)", "",
                  1e3 * *record.wall_seconds, "", "", "", "", wall_frames.c_str(),
                  wall_fits.c_str());
    }
  }
}

void print_sweep_table(const std::vector<BenchRecord>& records) {
  std::printf("%-44s %-16s %8s %5s %9s %9s %11s %8s %7s %10s %11s\n", "device", "kernel",
              "residual", "cap", "MB/frame", "frames/s", "whole call", "GB/s", "%peak", "%bound",
              "error");
  for (const auto& record : records) {
    if (!record.in_sweep()) continue;
    const ResidualPoint& point = *record.residual;
    char residual[16] = "all", wall[16] = "-";
    if (point.percent) std::snprintf(residual, sizeof residual, "%g%%", *point.percent);
    if (record.wall_seconds)
      std::snprintf(wall, sizeof wall, "%.1f", record.frames / *record.wall_seconds);
    std::printf("%-44.44s %-16s %8s %5s %9.2f %9.1f %11s %8.2f %7s %10s %11.4g\n",
                record.device.c_str(), record.kernel.c_str(), residual,
                residual_cap_text(point.cap).c_str(), 1e-6 * double(record.bytes) / record.frames,
                record.frames / record.seconds, wall, record.gbps(),
                percent_of_peak(record).c_str(), percent_of_binding(record).c_str(), *point.error);
  }
}

}  // namespace relume
