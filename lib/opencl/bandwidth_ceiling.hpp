// The memory bandwidth a device reaches on its own: a streaming read (sum of a large buffer) and a
// copy, run with kernels/ceiling.cl on the same OpenCL device as the relighting kernels. The
// device's peak is the larger of the two; relighting kernels report their GB/s against it.
// Each kernel comes in two access patterns (see ceiling.cl); the faster one counts.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "opencl/runtime.hpp"

namespace relume {

enum class AccessPattern { blocked, strided };

const char* access_pattern_name(AccessPattern pattern);

// Buffers and kernels for timing single runs of the ceiling kernels, so that a benchmark can
// interleave them with the kernels it measures (a shared machine's load then hits both alike).
class BandwidthProbe {
 public:
  // `buffer_bytes` is rounded down to whole work-item runs; the copy needs twice that memory.
  BandwidthProbe(OpenClContext& context, std::uint64_t buffer_bytes = 256ull << 20);

  // Device seconds of one run.
  double time_read(AccessPattern pattern);
  double time_copy(AccessPattern pattern);
  // Bytes one run moves: read plus written (a copy counts both).
  std::uint64_t read_bytes(AccessPattern pattern) const;
  std::uint64_t copy_bytes() const { return 2 * bytes_; }

 private:
  double time(cl::Kernel& kernel, std::uint64_t items);

  OpenClContext& context_;
  std::uint64_t runs_ = 0;           // work-items of the blocked kernels
  std::uint64_t bytes_ = 0;          // buffer size
  std::uint64_t strided_items_ = 0;  // work-items of the strided kernels
  cl::Buffer input_, output_, partial_;
  cl::Kernel read_blocked_, read_strided_, copy_blocked_, copy_strided_;
};

struct BandwidthMeasurement {
  std::string kernel;                              // "read" or "copy"
  AccessPattern pattern = AccessPattern::blocked;  // the faster one
  std::uint64_t bytes = 0;                         // per run
  double seconds = 0;                              // median over the runs
  std::vector<double> run_seconds;                 // every timed run of the faster pattern

  double gbps() const { return seconds > 0 ? 1e-9 * double(bytes) / seconds : 0; }
};

struct BandwidthCeiling {
  BandwidthMeasurement read;
  BandwidthMeasurement copy;

  double peak_gbps() const { return read.gbps() > copy.gbps() ? read.gbps() : copy.gbps(); }
};

// Times both kernels in both patterns `repeats` times each (after a warm-up run) and keeps the
// faster pattern of each.
BandwidthCeiling measure_bandwidth_ceiling(OpenClContext& context,
                                           std::uint64_t buffer_bytes = 256ull << 20,
                                           int repeats = 7);

// Median of a non-empty list of timings.
double median_seconds(std::vector<double> seconds);

}  // namespace relume
