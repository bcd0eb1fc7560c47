// Tests of the bandwidth ceiling kernels on PoCL: both read kernels sum a random buffer as the CPU
// does, both copy kernels copy it exactly, and the measurement reports consistent bytes and rates.
#include <gtest/gtest.h>

#include <random>
#include <relume/error.hpp>

#include "opencl/bandwidth_ceiling.hpp"

namespace relume {
namespace {

OpenClContext& pocl() {
  static OpenClContext context(select_opencl_device("portable computing language"));
  return context;
}

constexpr std::size_t run_length = 16;  // float4 per work-item of the blocked kernels

std::vector<float> random_values(std::size_t count, std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::uniform_real_distribution<float> unit(-1.0f, 1.0f);
  std::vector<float> values(count);
  for (auto& value : values) value = unit(random);
  return values;
}

TEST(BandwidthCeiling, ReadKernelsSumTheBuffer) {
  const std::size_t runs = 37, float4s = runs * run_length;
  const std::vector<float> values = random_values(float4s * 4, 1);
  double expected = 0;
  for (const float value : values) expected += value;
  auto& context = pocl();
  cl::Buffer input(context.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                   values.size() * sizeof(float), const_cast<float*>(values.data()));
  for (const bool blocked : {true, false}) {
    const std::size_t items = blocked ? runs : 24;
    cl::Buffer partial(context.context(), CL_MEM_WRITE_ONLY, items * sizeof(float));
    cl::Kernel kernel =
        context.kernel("ceiling.cl", blocked ? "read_sum_blocked" : "read_sum_strided");
    kernel.setArg(0, input);
    if (blocked) {
      kernel.setArg(1, partial);
    } else {
      kernel.setArg(1, cl_uint(float4s));
      kernel.setArg(2, partial);
    }
    context.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(items));
    std::vector<float> sums(items);
    context.queue().enqueueReadBuffer(partial, CL_TRUE, 0, items * sizeof(float), sums.data());
    double total = 0;
    for (const float sum : sums) total += sum;
    EXPECT_NEAR(total, expected, 1e-4) << (blocked ? "blocked" : "strided");
  }
}

TEST(BandwidthCeiling, CopyKernelsCopyExactly) {
  const std::size_t runs = 21, float4s = runs * run_length;
  const std::vector<float> values = random_values(float4s * 4, 2);
  auto& context = pocl();
  cl::Buffer input(context.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                   values.size() * sizeof(float), const_cast<float*>(values.data()));
  for (const bool blocked : {true, false}) {
    cl::Buffer output(context.context(), CL_MEM_READ_WRITE, values.size() * sizeof(float));
    context.queue().enqueueFillBuffer(output, 0.0f, 0, values.size() * sizeof(float));
    cl::Kernel kernel = context.kernel("ceiling.cl", blocked ? "copy_blocked" : "copy_strided");
    kernel.setArg(0, input);
    kernel.setArg(1, output);
    if (!blocked) kernel.setArg(2, cl_uint(float4s));
    context.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(blocked ? runs : 50));
    std::vector<float> copied(values.size());
    context.queue().enqueueReadBuffer(output, CL_TRUE, 0, copied.size() * sizeof(float),
                                      copied.data());
    EXPECT_EQ(copied, values) << (blocked ? "blocked" : "strided");
  }
}

TEST(BandwidthCeiling, MeasuresBothKernelsWithConsistentFigures) {
  const BandwidthCeiling ceiling = measure_bandwidth_ceiling(pocl(), 4u << 20, 3);
  EXPECT_EQ(ceiling.read.kernel, "read");
  EXPECT_EQ(ceiling.copy.kernel, "copy");
  EXPECT_EQ(ceiling.copy.bytes, 2u * (4u << 20));
  EXPECT_GE(ceiling.read.bytes, 4u << 20);  // plus the partial sums written
  EXPECT_EQ(ceiling.read.run_seconds.size(), 3u);
  EXPECT_DOUBLE_EQ(ceiling.read.seconds, median_seconds(ceiling.read.run_seconds));
  EXPECT_GT(ceiling.read.gbps(), 0.0);
  EXPECT_DOUBLE_EQ(ceiling.peak_gbps(), std::max(ceiling.read.gbps(), ceiling.copy.gbps()));
  EXPECT_THROW(measure_bandwidth_ceiling(pocl(), 100, 3), Error);
  EXPECT_THROW(measure_bandwidth_ceiling(pocl(), 4u << 20, 0), Error);
}

TEST(BandwidthCeiling, MedianOfTimings) {
  EXPECT_DOUBLE_EQ(median_seconds({3, 1, 2}), 2);
  EXPECT_DOUBLE_EQ(median_seconds({4, 1, 2, 3}), 2.5);
  EXPECT_THROW(median_seconds({}), Error);
}

}  // namespace
}  // namespace relume
