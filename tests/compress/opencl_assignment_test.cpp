// The OpenCL assignment kernel (kernels/assign.cl) against the CPU reference on fresh random
// inputs: the same clusters are chosen wherever the choice is not a near tie, and the objectives
// and weights agree to float precision.
#include "compress/opencl_assignment.hpp"

#include <gtest/gtest.h>

#include <relume/error.hpp>

#include "compress/cluster_assignment.hpp"
#include "compress/random_assignment_problem.hpp"

namespace relume {
namespace {

AssignmentProblem random_problem(int rows, int clusters, int terms, int lights, int width,
                                 std::uint64_t seed) {
  return random_assignment_problem({rows, clusters, terms, lights, width, true, seed});
}

void expect_same_assignment(const AssignmentProblem& problem, OpenClAssigner& assigner) {
  const IrlsSettings settings;
  const AssignmentResult cpu =
      assign_to_best_cluster(problem.rows, problem.model, problem.candidates, settings, 2);
  const AssignmentResult gpu = assigner.assign(problem.rows, problem.model, problem.candidates);
  ASSERT_EQ(gpu.best.size(), cpu.best.size());
  std::size_t same = 0;
  for (std::size_t r = 0; r < cpu.best.size(); ++r) {
    EXPECT_NEAR(gpu.objective[r], cpu.objective[r], 2e-3f * std::max(1.0f, cpu.objective[r]))
        << "row " << r;
    if (gpu.best[r] == cpu.best[r]) {
      ++same;
      for (int j = 0; j < problem.model.terms; ++j)
        EXPECT_NEAR(gpu.weights(r, j), cpu.weights(r, j), 2e-2f) << "row " << r << " term " << j;
    }
  }
  // Different choices only where two candidates fit almost equally well.
  EXPECT_GE(double(same) / cpu.best.size(), 0.99);
}

TEST(OpenClAssignment, MatchesTheCpuReferenceOnRandomInputs) {
  OpenClAssigner assigner("", IrlsSettings{});
  std::printf("device: %s\n", assigner.device_label().c_str());
  expect_same_assignment(random_problem(3000, 12, 4, 96, 4, 1), assigner);
  expect_same_assignment(random_problem(1000, 5, 3, 37, 6, 2), assigner);
  expect_same_assignment(random_problem(500, 3, 1, 16, 2, 3), assigner);
}

// Every vector width of the kernel's passes, with lights that fill whole vectors and lights that
// leave a partial one.
TEST(OpenClAssignment, EveryLightVectorWidthMatchesTheCpuReference) {
  for (const int light_vector : {4, 8, 16}) {
    SCOPED_TRACE("light vector " + std::to_string(light_vector));
    OpenClAssigner assigner("", IrlsSettings{}, light_vector);
    EXPECT_EQ(assigner.light_vector(), light_vector);
    expect_same_assignment(random_problem(600, 6, 4, 64, 3, 6), assigner);
    expect_same_assignment(random_problem(600, 6, 2, 45, 3, 7), assigner);
    expect_same_assignment(random_problem(300, 4, 3, 5, 2, 8), assigner);
  }
  EXPECT_THROW(OpenClAssigner("", IrlsSettings{}, 2), Error);
}

TEST(OpenClAssignment, ReuploadsRowsThatChanged) {
  OpenClAssigner assigner("", IrlsSettings{});
  AssignmentProblem problem = random_problem(800, 6, 4, 48, 3, 4);
  expect_same_assignment(problem, assigner);
  problem.rows.values.row(0) *= -1.0f;
  problem.rows.values.row(500).reverseInPlace();
  expect_same_assignment(problem, assigner);
}

TEST(OpenClAssignment, RunsOnAListedDevice) {
  const std::vector<OpenClDevice> devices = list_opencl_devices();
  ASSERT_FALSE(devices.empty());
  const OpenClDevice& device = devices[default_opencl_device_index(devices)];
  OpenClAssigner assigner(device, IrlsSettings{});
  EXPECT_EQ(assigner.device_label(), device.label());
  expect_same_assignment(random_problem(300, 4, 2, 20, 3, 5), assigner);
  EXPECT_GT(assigner.kernel_seconds(), 0.0);
}

}  // namespace
}  // namespace relume
