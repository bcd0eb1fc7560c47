// The OpenCL assignment kernel (kernels/assign.cl) against the CPU reference on fresh random
// inputs: the same clusters are chosen wherever the choice is not a near tie, and the objectives
// and weights agree to float precision.
#include <gtest/gtest.h>

#include <random>

#include "cluster_assignment.hpp"
#include "opencl_assignment.hpp"

namespace relume {
namespace {

struct RandomProblem {
  WorkingRows rows;
  ClusterModel model;
  CandidateLists candidates;
};

RandomProblem random_problem(int rows, int clusters, int terms, int lights, int width,
                             std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::normal_distribution<float> normal;
  RandomProblem problem;
  problem.model.terms = terms;
  problem.model.lights = lights;
  problem.model.clusters = clusters;
  for (int i = 0; i < clusters * terms * lights; ++i) problem.model.bases.push_back(normal(random));
  problem.rows.values.resize(rows, lights);
  problem.rows.norms.assign(rows, 1.0f);
  for (int r = 0; r < rows; ++r) {
    // Mostly near one cluster's span, with sparse outliers: realistic L1 problems.
    const int k = static_cast<int>(random() % clusters);
    Eigen::RowVectorXf w(terms);
    for (int j = 0; j < terms; ++j) w[j] = normal(random);
    const Eigen::Map<const RowMatrixF> f(problem.model.basis(k), terms, lights);
    Eigen::RowVectorXf x = w * f;
    for (int i = 0; i < lights; ++i) x[i] += 0.05f * normal(random);
    for (int e = 0; e < 3; ++e) x[random() % lights] += 2.0f * normal(random);
    problem.rows.values.row(r) = x / x.norm();
  }
  problem.candidates.width = width;
  for (int r = 0; r < rows; ++r) {
    const int count = 1 + static_cast<int>(random() % width);  // some lists end early
    for (int slot = 0; slot < width; ++slot)
      problem.candidates.clusters.push_back(slot < count ? static_cast<int>(random() % clusters) : -1);
  }
  return problem;
}

void expect_same_assignment(const RandomProblem& problem, OpenClAssigner& assigner) {
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

TEST(OpenClAssignment, ReuploadsRowsThatChanged) {
  OpenClAssigner assigner("", IrlsSettings{});
  RandomProblem problem = random_problem(800, 6, 4, 48, 3, 4);
  expect_same_assignment(problem, assigner);
  problem.rows.values.row(0) *= -1.0f;
  problem.rows.values.row(500).reverseInPlace();
  expect_same_assignment(problem, assigner);
}

}  // namespace
}  // namespace relume
