// Implementation of the timed runs of `relume bench`.
#include "commands/bench/bench_runs.hpp"

#include <algorithm>
#include <chrono>

#include "compress/cluster_assignment.hpp"
#include "core/parallel.hpp"
#include "core/progress.hpp"

namespace relume {
namespace {

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

}  // namespace

CeilingRuns::CeilingRuns(OpenClContext& context, std::uint64_t buffer_bytes)
    : device_(context.device()),
      probe_(context, buffer_bytes),
      read_pattern_(
          faster_pattern([&](AccessPattern pattern) { return probe_.time_read(pattern); })),
      copy_pattern_(
          faster_pattern([&](AccessPattern pattern) { return probe_.time_copy(pattern); })) {}

void CeilingRuns::run_round() {
  read_.push_back(probe_.time_read(read_pattern_));
  copy_.push_back(probe_.time_copy(copy_pattern_));
}

double CeilingRuns::peak_gbps() const {
  const double read_gbps = 1e-9 * double(probe_.read_bytes(read_pattern_)) / median_seconds(read_);
  const double copy_gbps = 1e-9 * double(probe_.copy_bytes()) / median_seconds(copy_);
  return std::max(read_gbps, copy_gbps);
}

std::vector<BenchRecord> CeilingRuns::records() const {
  const double peak = peak_gbps();
  std::vector<BenchRecord> records = {
      make_record(device_.platform_name, device_.device_name, "read",
                  probe_.read_bytes(read_pattern_), read_, peak),
      make_record(device_.platform_name, device_.device_name, "copy", probe_.copy_bytes(), copy_,
                  peak)};
  records[0].pattern = access_pattern_name(read_pattern_);
  records[1].pattern = access_pattern_name(copy_pattern_);
  return records;
}

RelightRuns::RelightRuns(OpenClRelighter& relighter, std::vector<ResidualPoint> points,
                         std::vector<std::vector<LightRgb>> batches, bool with_parts)
    : relighter_(relighter),
      points_(std::move(points)),
      batches_(std::move(batches)),
      with_parts_(with_parts),
      runs_(points_.size()),
      frame_(1),
      frames_(batches_.size()) {
  for (PointRuns& runs : runs_) runs.batched.resize(batches_.size());
  const LightRgb& first = batches_.at(0).at(0);
  for (const ResidualPoint& point : points_) {
    relighter_.relight_batch_into({first}, point.cap, frame_);
    if (with_parts_) relighter_.relight_residual_into(first, point.cap, frame_[0]);
    for (std::size_t b = 0; b < batches_.size(); ++b)
      relighter_.relight_batch_into(batches_[b], point.cap, frames_[b]);
  }
}

namespace {

// Seconds of the call's kernels with its row kernel replaced by `ceiling` seconds: the call at
// the relighter's work ceiling.
double at_work_ceiling(const RelightTiming& timing, double ceiling) {
  double seconds = ceiling;
  for (const KernelTiming& kernel : timing.kernels)
    if (kernel.kernel != "rows") seconds += kernel.seconds;
  return seconds;
}

}  // namespace

void RelightRuns::run_round(const LightRgb& light) {
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const int cap = points_[i].cap;
    PointRuns& runs = runs_[i];
    relighter_.relight_batch_into({light}, cap, frame_);
    const RelightTiming& single = relighter_.last_timing();
    runs.gemv.push_back(single.kernel("gemv").seconds);
    runs.gemv_bytes = single.kernel("gemv").bytes;
    runs.relight.push_back(single.kernel_seconds());
    runs.relight_bytes = single.kernel_bytes();
    runs.relight_flops = single.kernel_flops();
    runs.relight_wall.push_back(single.wall_seconds);
    runs.relight_work.push_back(at_work_ceiling(single, relighter_.work_ceiling_seconds(1, cap)));
    if (with_parts_) {
      relighter_.relight_residual_into(light, cap, frame_[0]);
      runs.spmv.push_back(relighter_.last_timing().kernel("spmv").seconds);
      runs.spmv_bytes = relighter_.last_timing().kernel("spmv").bytes;
    }
    for (std::size_t b = 0; b < batches_.size(); ++b) {
      relighter_.relight_batch_into(batches_[b], cap, frames_[b]);
      const RelightTiming& timing = relighter_.last_timing();
      BatchRuns& batched = runs.batched[b];
      batched.kernel.push_back(timing.kernel_seconds());
      batched.wall.push_back(timing.wall_seconds);
      batched.bytes = timing.kernel_bytes();
      batched.flops = timing.kernel_flops();
      batched.work.push_back(
          at_work_ceiling(timing, relighter_.work_ceiling_seconds(int(batches_[b].size()), cap)));
    }
  }
}

std::vector<BenchRecord> RelightRuns::records(const OpenClDevice& device, double peak_gbps) const {
  const std::string& platform = device.platform_name;
  const std::string& name = device.device_name;
  nlohmann::ordered_json layout = {{"slice_rows", relighter_.slice_rows()},
                                   {"weight_rows", relighter_.weight_rows()},
                                   {"work_group_rows", relighter_.work_group_rows()},
                                   {"row_vector", relighter_.row_vector()},
                                   {"head_entries", nlohmann::ordered_json()}};
  if (relighter_.head_entries() != 0xffffffffu) layout["head_entries"] = relighter_.head_entries();
  std::vector<BenchRecord> records;
  for (std::size_t i = 0; i < points_.size(); ++i) {
    const PointRuns& runs = runs_[i];
    if (with_parts_) {
      records.push_back(make_record(platform, name, "gemv", runs.gemv_bytes, runs.gemv, peak_gbps));
      records.push_back(make_record(platform, name, "spmv", runs.spmv_bytes, runs.spmv, peak_gbps));
      records.back().residual = points_[i];
    }
    records.push_back(
        make_record(platform, name, "relight", runs.relight_bytes, runs.relight, peak_gbps, 1));
    records.back().wall_seconds = median_seconds(runs.relight_wall);
    records.back().residual = points_[i];
    records.back().flops = runs.relight_flops;
    records.back().work_ceiling_seconds = median_seconds(runs.relight_work);
    for (std::size_t b = 0; b < batches_.size(); ++b) {
      const BatchRuns& batched = runs.batched[b];
      records.push_back(make_record(platform, name, "relight_batched", batched.bytes,
                                    batched.kernel, peak_gbps, int(batches_[b].size())));
      records.back().wall_seconds = median_seconds(batched.wall);
      records.back().residual = points_[i];
      records.back().flops = batched.flops;
      records.back().work_ceiling_seconds = median_seconds(batched.work);
    }
  }
  for (BenchRecord& record : records) record.layout = layout;
  return records;
}

std::uint64_t assignment_bytes(const AssignmentProblem& problem) {
  const ClusterModel& model = problem.model;
  const std::uint64_t rows = problem.rows.rows();
  const std::uint64_t input = rows * std::uint64_t(model.lights) * sizeof(float) +
                              problem.candidates.clusters.size() * sizeof(std::int32_t) +
                              model.bases.size() * sizeof(float);
  const std::uint64_t output = rows * (2 * sizeof(std::int32_t) + sizeof(float) +
                                       std::uint64_t(model.terms) * sizeof(float));
  return input + output;
}

AssignmentRuns::AssignmentRuns(const OpenClDevice& device, const AssignmentProblem& problem)
    : problem_(problem), assigner_(device, IrlsSettings{}) {
  assigner_.assign(problem_.rows, problem_.model, problem_.candidates);
}

void AssignmentRuns::run_round() {
  const double before = assigner_.kernel_seconds();
  wall_.push_back(
      timed([&] { assigner_.assign(problem_.rows, problem_.model, problem_.candidates); }));
  kernel_.push_back(assigner_.kernel_seconds() - before);
}

BenchRecord AssignmentRuns::record(const OpenClDevice& device, double peak_gbps) const {
  BenchRecord record = make_record(device.platform_name, device.device_name, "assign",
                                   assignment_bytes(problem_), kernel_, peak_gbps);
  record.fits = problem_.candidate_count();
  record.wall_seconds = median_seconds(wall_);
  return record;
}

std::vector<BenchRecord> bench_reference(const CompressedField& field,
                                         const std::vector<LightRgb>& lights,
                                         const std::vector<ResidualPoint>& points, bool with_parts,
                                         const AssignmentProblem* problem, unsigned threads,
                                         int repeats, std::optional<double> cpu_peak,
                                         ProgressReporter& progress) {
  const CompressedRelightReference reference(field);
  const std::string platform = "reference";
  const std::string thread_text = std::to_string(resolve_thread_count(threads)) + " threads";
  const std::string relight_device = "C++ double, " + thread_text;
  const std::uint64_t rows = field.stored_rows();
  const std::uint64_t light_bytes = std::uint64_t(field.lights) * 3 * sizeof(float);
  const std::uint64_t gemv_bytes = field.bases.size() * sizeof(float) + light_bytes;
  // The CSR residual with 32-bit light indices, 32-bit cluster ids and function indices.
  const auto residual_bytes = [&](int cap) {
    std::uint64_t used_entries = 0;
    for (std::size_t s = 0; s < rows; ++s)
      used_entries += std::min<std::uint64_t>(field.residual.length(s), std::uint64_t(cap));
    return used_entries * 8 + rows * (4 + 4 + 4) + light_bytes;
  };

  std::vector<std::vector<double>> gemv(points.size()), spmv(points.size()), relight(points.size());
  std::vector<double> assign;
  for (int r = 0; r < repeats; ++r) {
    const LightRgb& light = lights[std::size_t(r) % lights.size()];
    for (std::size_t i = 0; i < points.size(); ++i) {
      const int cap = points[i].cap;
      if (with_parts) {
        gemv[i].push_back(
            timed([&] { cluster_light_products(field, light_in_field_basis(field, light)); }));
        spmv[i].push_back(
            timed([&] { reference.relight(light, cap, RelightTerms::residual_only, threads); }));
      }
      relight[i].push_back(
          timed([&] { reference.relight(light, cap, RelightTerms::all, threads); }));
    }
    if (problem)
      assign.push_back(timed([&] {
        assign_to_best_cluster(problem->rows, problem->model, problem->candidates, IrlsSettings{},
                               threads);
      }));
    progress.advance();
  }

  std::vector<BenchRecord> records;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const std::uint64_t spmv_bytes = residual_bytes(points[i].cap);
    if (with_parts) {
      records.push_back(
          make_record(platform, relight_device, "gemv", gemv_bytes, gemv[i], cpu_peak));
      records.push_back(
          make_record(platform, relight_device, "spmv", spmv_bytes, spmv[i], cpu_peak));
      records.back().residual = points[i];
    }
    const std::uint64_t relight_bytes =
        gemv_bytes + spmv_bytes + rows * (4 + 4 * std::uint64_t(field.terms));
    records.push_back(
        make_record(platform, relight_device, "relight", relight_bytes, relight[i], cpu_peak, 1));
    records.back().residual = points[i];
  }
  if (problem) {
    records.push_back(make_record(platform, "C++ float IRLS, " + thread_text, "assign",
                                  assignment_bytes(*problem), assign, cpu_peak));
    records.back().fits = problem->candidate_count();
  }
  return records;
}

}  // namespace relume
