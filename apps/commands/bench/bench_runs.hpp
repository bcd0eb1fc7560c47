// The timed runs of `relume bench`. On an OpenCL device: the bandwidth ceilings, the relighting
// kernels at one or more residual caps and the assignment kernel, each run once per round by the
// caller so that a shared machine's changing load hits them alike. On the CPU: the C++ reference
// paths of relighting and assignment.
#pragma once

#include <cstdint>
#include <optional>
#include <vector>

#include "commands/bench/bench_records.hpp"
#include "compress/opencl_assignment.hpp"
#include "compress/random_assignment_problem.hpp"
#include "opencl/bandwidth_ceiling.hpp"
#include "relight/opencl_relighter.hpp"

namespace relume {

class ProgressReporter;

// The read and copy ceiling kernels of one device.
class CeilingRuns {
 public:
  // Picks the faster access pattern of each kernel by the median of a few runs.
  CeilingRuns(OpenClContext& context, std::uint64_t buffer_bytes);
  void run_round();
  double peak_gbps() const;                  // the larger of the read and copy medians, in GB/s
  std::vector<BenchRecord> records() const;  // read, copy

 private:
  const OpenClDevice& device_;
  BandwidthProbe probe_;
  AccessPattern read_pattern_, copy_pattern_;
  std::vector<double> read_, copy_;
};

// The relighting kernels on one uploaded field, at each residual point, each with its work
// ceiling (OpenClRelighter::work_ceiling_seconds) timed in the same round.
class RelightRuns {
 public:
  // `batches`: the light vectors of each batched pass, one batch per batch size. with_parts: also
  // time the GEMV and the residual SpMV on their own (gemv and spmv records). Builds the programs
  // and touches every buffer once.
  RelightRuns(OpenClRelighter& relighter, std::vector<ResidualPoint> points,
              std::vector<std::vector<LightRgb>> batches, bool with_parts);
  void run_round(const LightRgb& light);
  // Per point: [gemv, spmv,] relight, then relight_batched per batch.
  std::vector<BenchRecord> records(const OpenClDevice& device, double peak_gbps) const;

 private:
  // `work`: the call's kernels with the row kernel at its work ceiling (RelightRuns::run_round).
  struct BatchRuns {
    std::vector<double> kernel, wall, work;
    std::uint64_t bytes = 0, flops = 0;
  };
  struct PointRuns {
    std::vector<double> gemv, spmv, relight, relight_wall, relight_work;
    std::uint64_t gemv_bytes = 0, spmv_bytes = 0, relight_bytes = 0, relight_flops = 0;
    std::vector<BatchRuns> batched;  // per batch
  };
  OpenClRelighter& relighter_;
  std::vector<ResidualPoint> points_;
  std::vector<std::vector<LightRgb>> batches_;
  bool with_parts_;
  std::vector<PointRuns> runs_;  // per point
  std::vector<Image> frame_;
  std::vector<std::vector<Image>> frames_;  // per batch, so that no round reallocates them
};

// Global memory one assignment call moves: the rows, the candidate lists and the bases read
// (the bases once: they stay in cache), and the outputs written (best, second, objective, weights).
std::uint64_t assignment_bytes(const AssignmentProblem& problem);

// The assignment kernel (kernels/assign.cl) on one device, one whole assign() call per round.
class AssignmentRuns {
 public:
  // Makes the assigner on `device` and runs one call (build, row upload).
  AssignmentRuns(const OpenClDevice& device, const AssignmentProblem& problem);
  void run_round();
  // Kernel seconds; whole calls (uploads of bases and lists, kernel, read-back) as wall seconds.
  BenchRecord record(const OpenClDevice& device, double peak_gbps) const;

 private:
  const AssignmentProblem& problem_;
  OpenClAssigner assigner_;
  std::vector<double> kernel_, wall_;
};

// `repeats` rounds of the C++ reference: relighting `field` at each point (gemv, spmv and relight
// records with_parts, else relight only), with bytes counted from its CSR arrays; and, given a
// problem, the CPU assignment path. Compared with `cpu_peak`, the CPU OpenCL device's peak.
std::vector<BenchRecord> bench_reference(const CompressedField& field,
                                         const std::vector<LightRgb>& lights,
                                         const std::vector<ResidualPoint>& points, bool with_parts,
                                         const AssignmentProblem* problem, unsigned threads,
                                         int repeats, std::optional<double> cpu_peak,
                                         ProgressReporter& progress);

}  // namespace relume
