// The records of `relume bench`: one per (device, kernel, residual setting) with bytes moved per
// run, the median of its timed runs and the device's peak, written as JSON and printed as tables.
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

  double gbps() const { return 1e-9 * double(bytes) / seconds; }
  bool in_sweep() const { return residual && residual->error; }
};

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
