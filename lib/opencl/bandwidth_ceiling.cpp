// Implementation of the bandwidth ceiling measurement.
#include "opencl/bandwidth_ceiling.hpp"

#include <algorithm>
#include <relume/error.hpp>

namespace relume {
namespace {

constexpr std::uint64_t run_length = 16;  // float4 per work-item; RUN_LENGTH in ceiling.cl
constexpr std::uint64_t float4_bytes = 16;

[[noreturn]] void rethrow_opencl(const cl::Error& error, const OpenClContext& context) {
  throw Error("bandwidth ceiling on " + context.device().label() + ": " + error.what() +
              " failed with " + opencl_error_name(error.err()));
}

}  // namespace

const char* access_pattern_name(AccessPattern pattern) {
  return pattern == AccessPattern::blocked ? "blocked" : "strided";
}

double median_seconds(std::vector<double> seconds) {
  if (seconds.empty()) throw Error("median of an empty list of timings");
  std::sort(seconds.begin(), seconds.end());
  const std::size_t middle = seconds.size() / 2;
  return seconds.size() % 2 ? seconds[middle] : 0.5 * (seconds[middle - 1] + seconds[middle]);
}

BandwidthProbe::BandwidthProbe(OpenClContext& context, std::uint64_t buffer_bytes)
    : context_(context) {
  runs_ = buffer_bytes / (run_length * float4_bytes);
  if (runs_ == 0)
    throw Error("bandwidth ceiling: a buffer of " + std::to_string(buffer_bytes) +
                " bytes is too small (at least " + std::to_string(run_length * float4_bytes) +
                " expected)");
  const std::uint64_t count = runs_ * run_length;  // float4 elements
  if (count > 0xffffffffull)
    throw Error("bandwidth ceiling: a buffer of " + std::to_string(buffer_bytes) +
                " bytes is larger than the kernels' 32-bit element index allows");
  bytes_ = count * float4_bytes;
  strided_items_ = std::min<std::uint64_t>(
      count, std::uint64_t(std::max(1u, context.device().compute_units)) * 2048);
  try {
    const cl::Context& cl_context = context.context();
    cl::CommandQueue& queue = context.queue();
    input_ = cl::Buffer(cl_context, CL_MEM_READ_WRITE, bytes_);
    output_ = cl::Buffer(cl_context, CL_MEM_READ_WRITE, bytes_);
    partial_ =
        cl::Buffer(cl_context, CL_MEM_READ_WRITE, std::max(runs_, strided_items_) * sizeof(float));
    queue.enqueueFillBuffer(input_, 1.0f, 0, bytes_);  // also touches every page once
    queue.enqueueFillBuffer(output_, 0.0f, 0, bytes_);
    queue.finish();
    read_blocked_ = context.kernel("ceiling.cl", "read_sum_blocked");
    read_blocked_.setArg(0, input_);
    read_blocked_.setArg(1, partial_);
    read_strided_ = context.kernel("ceiling.cl", "read_sum_strided");
    read_strided_.setArg(0, input_);
    read_strided_.setArg(1, cl_uint(count));
    read_strided_.setArg(2, partial_);
    copy_blocked_ = context.kernel("ceiling.cl", "copy_blocked");
    copy_blocked_.setArg(0, input_);
    copy_blocked_.setArg(1, output_);
    copy_strided_ = context.kernel("ceiling.cl", "copy_strided");
    copy_strided_.setArg(0, input_);
    copy_strided_.setArg(1, output_);
    copy_strided_.setArg(2, cl_uint(count));
  } catch (const cl::Error& error) {
    rethrow_opencl(error, context);
  }
}

std::uint64_t BandwidthProbe::read_bytes(AccessPattern pattern) const {
  const std::uint64_t partial_writes =
      (pattern == AccessPattern::blocked ? runs_ : strided_items_) * sizeof(float);
  return bytes_ + partial_writes;
}

double BandwidthProbe::time(cl::Kernel& kernel, std::uint64_t items) {
  try {
    cl::Event event;
    context_.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(items), cl::NullRange,
                                          nullptr, &event);
    event.wait();
    return event_seconds(event);
  } catch (const cl::Error& error) {
    rethrow_opencl(error, context_);
  }
}

double BandwidthProbe::time_read(AccessPattern pattern) {
  return pattern == AccessPattern::blocked ? time(read_blocked_, runs_)
                                           : time(read_strided_, strided_items_);
}

double BandwidthProbe::time_copy(AccessPattern pattern) {
  return pattern == AccessPattern::blocked ? time(copy_blocked_, runs_)
                                           : time(copy_strided_, strided_items_);
}

BandwidthCeiling measure_bandwidth_ceiling(OpenClContext& context, std::uint64_t buffer_bytes,
                                           int repeats) {
  if (repeats < 1)
    throw Error("bandwidth ceiling: repeats must be at least 1, got " + std::to_string(repeats));
  BandwidthProbe probe(context, buffer_bytes);
  const auto measure = [&](const char* kernel, bool read) {
    BandwidthMeasurement best;
    for (const AccessPattern pattern : {AccessPattern::blocked, AccessPattern::strided}) {
      BandwidthMeasurement measurement;
      measurement.kernel = kernel;
      measurement.pattern = pattern;
      measurement.bytes = read ? probe.read_bytes(pattern) : probe.copy_bytes();
      read ? probe.time_read(pattern) : probe.time_copy(pattern);  // warm-up
      for (int i = 0; i < repeats; ++i)
        measurement.run_seconds.push_back(read ? probe.time_read(pattern)
                                               : probe.time_copy(pattern));
      measurement.seconds = median_seconds(measurement.run_seconds);
      if (best.run_seconds.empty() || measurement.gbps() > best.gbps()) best = measurement;
    }
    return best;
  };
  BandwidthCeiling ceiling;
  ceiling.read = measure("read", true);
  ceiling.copy = measure("copy", false);
  return ceiling;
}

}  // namespace relume
