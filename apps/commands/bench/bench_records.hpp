// The records of `relume bench`: one per (device, kernel, residual setting) with bytes moved per
// run, the median of its timed runs, the device's peak and, for the relighting kernels, their
// place on a roofline of two roofs (memory and work), written as JSON and printed as tables.
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <optional>
#include <relume/compressed_field.hpp>
#include <string>
#include <vector>

namespace relume {

// One residual setting of the relighting records. A point of the --container sweep also carries
// its share of the lights and the error of the field with the residual cut to `cap`.
struct ResidualPoint {
  int cap = all_residual_entries;  // entries per row
  std::optional<double> percent;   // sweep: percentage of the lights; nullopt for the full residual
  std::optional<double> error;     // sweep: paper Eq. 16 of the capped field
};

struct BenchRecord {
  std::string platform;
  std::string device;
  std::string kernel;
  std::uint64_t bytes = 0;  // per run
  double seconds = 0;       // median per run
  std::vector<double> run_seconds;
  std::optional<double> peak_gbps;
  int frames = 0;                         // frames per run; 0 for kernels that make no frame
  std::uint64_t fits = 0;                 // assign: (row, candidate) fits per run
  std::optional<double> wall_seconds;     // median of whole calls (upload + kernels + read-back)
  std::string pattern;                    // access pattern of a ceiling kernel
  std::optional<ResidualPoint> residual;  // for kernels that read the residual
  nlohmann::ordered_json layout;          // relighting kernels: slice, work-group and row vector
  // Relighting kernels: their floating-point operations per run, and the median seconds of the
  // run with the row kernel at the relighter's work ceiling (the second roof).
  std::uint64_t flops = 0;
  std::optional<double> work_ceiling_seconds;

  double gbps() const { return 1e-9 * double(bytes) / seconds; }
  bool in_sweep() const { return residual && residual->error; }
};

// A relighting record against its two roofs: the memory roof (its bytes at the device's peak
// bandwidth) and the work roof (work_ceiling_seconds). The one that takes longer binds; the ratio
// is the binding roof's seconds over the measured ones (1: at the roof).
struct RooflinePosition {
  double memory_seconds = 0;
  double work_seconds = 0;
  bool memory_binds = true;
  double ratio_to_binding_ceiling = 0;
};

// For a record with flops, a work ceiling and a peak; nullopt otherwise.
std::optional<RooflinePosition> roofline_position(const BenchRecord& record);

BenchRecord make_record(const std::string& platform, const std::string& device,
                        const std::string& kernel, std::uint64_t bytes,
                        std::vector<double> run_seconds, std::optional<double> peak_gbps,
                        int frames = 0);

// "all" for the full residual, else the cap.
nlohmann::ordered_json residual_cap_json(int cap);

nlohmann::ordered_json to_json(const BenchRecord& record);

// Every record but the sweep's: MB per run, ms, GB/s, share of peak, frames/s, fits/s.
void print_record_table(const std::vector<BenchRecord>& records);

// The sweep's records (paper Table 1): per device, kernel and residual, frames/s of the kernels
// and of the whole call, GB/s, share of peak and error.
void print_sweep_table(const std::vector<BenchRecord>& records);

}  // namespace relume
