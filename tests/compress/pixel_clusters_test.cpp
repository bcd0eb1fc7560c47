// Tests of one cluster per pixel (compress/pixel_clusters.hpp): after sharing no pixel is split,
// each split pixel lands in the cluster with the smallest summed L1 residual times the rows'
// norms (checked by fitting every choice again), unsplit pixels are left alone, and the OpenCL
// kernel's fits choose as the CPU path's do.
#include "compress/pixel_clusters.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "compress/opencl_assignment.hpp"
#include "compress/random_assignment_problem.hpp"

namespace relume {
namespace {

// A random problem whose rows are taken three at a time as the channels of a pixel, assigned
// to their best candidates (so some pixels are split), with norms that differ by channel.
AssignmentProblem split_problem(std::uint64_t seed) {
  AssignmentProblem problem = random_assignment_problem({1500, 8, 3, 48, 3, false, seed});
  WorkingRows& rows = problem.rows;
  rows.pixel.resize(rows.rows());
  for (std::size_t r = 0; r < rows.rows(); ++r) {
    rows.pixel[r] = std::uint32_t(r / 3);
    rows.norms[r] = 1.0f + float(r % 3);
  }
  const AssignmentResult best =
      assign_to_best_cluster(rows, problem.model, problem.candidates, IrlsSettings{}, 2);
  problem.model.assignment = best.best;
  problem.model.weights = best.weights;
  return problem;
}

std::size_t split_pixels(const WorkingRows& rows, const ClusterModel& model) {
  std::size_t split = 0;
  for (std::size_t r = 0; r < rows.rows(); r += 3)
    split += std::set<std::int32_t>(model.assignment.begin() + std::ptrdiff_t(r),
                                    model.assignment.begin() + std::ptrdiff_t(r + 3))
                 .size() > 1;
  return split;
}

CandidateFits cpu_fits(const AssignmentProblem& problem) {
  return [&problem](const CandidateLists& lists) {
    return assign_to_best_cluster(problem.rows, problem.model, lists, IrlsSettings{}, 2);
  };
}

// The summed L1 residual x norm of pixel rows [first, first + 3) fitted to cluster k.
double pixel_cost(const AssignmentProblem& problem, std::size_t first, std::int32_t k) {
  const ClusterModel& model = problem.model;
  FunctionFitScratch scratch;
  float weights[max_cluster_terms];
  double cost = 0;
  for (std::size_t r = first; r < first + 3; ++r)
    cost += double(problem.rows.norms[r]) * fit_function_l1(model.basis(k), model.terms,
                                                            model.lights, problem.rows.row(r), 1.0f,
                                                            IrlsSettings{}, weights, scratch);
  return cost;
}

TEST(PixelClusters, EverySplitPixelJoinsItsCheapestCluster) {
  const AssignmentProblem before = split_problem(5);
  const std::size_t split = split_pixels(before.rows, before.model);
  ASSERT_GT(split, 50u) << "the test needs split pixels";
  AssignmentProblem after = before;
  const PixelClusterChange change = share_pixel_clusters(after.rows, after.model, cpu_fits(after));
  EXPECT_EQ(change.split_pixels, split);
  EXPECT_GT(change.rows_moved, 0u);
  EXPECT_EQ(split_pixels(after.rows, after.model), 0u);
  std::size_t checked = 0;
  for (std::size_t r = 0; r < before.rows.rows(); r += 3) {
    const std::set<std::int32_t> clusters(before.model.assignment.begin() + std::ptrdiff_t(r),
                                          before.model.assignment.begin() + std::ptrdiff_t(r + 3));
    const std::int32_t chosen = after.model.assignment[r];
    if (clusters.size() == 1) {
      EXPECT_EQ(chosen, *clusters.begin()) << "pixel " << r / 3 << " was not split";
      for (int j = 0; j < after.model.terms; ++j)
        EXPECT_EQ(after.model.weights(Eigen::Index(r), j),
                  before.model.weights(Eigen::Index(r), j));
      continue;
    }
    ASSERT_TRUE(clusters.count(chosen)) << "pixel " << r / 3;
    const double cost = pixel_cost(after, r, chosen);
    for (const std::int32_t k : clusters) EXPECT_LE(cost, pixel_cost(after, r, k) * (1 + 1e-6));
    // The chosen cluster's weights are the rows' fits to it.
    FunctionFitScratch scratch;
    float weights[max_cluster_terms];
    fit_function_l1(after.model.basis(chosen), after.model.terms, after.model.lights,
                    after.rows.row(r), 1.0f, IrlsSettings{}, weights, scratch);
    for (int j = 0; j < after.model.terms; ++j)
      EXPECT_NEAR(after.model.weights(Eigen::Index(r), j), weights[j], 1e-5f);
    ++checked;
  }
  EXPECT_EQ(checked, split);
}

TEST(PixelClusters, RowsWithoutPixelsAreLeftAlone) {
  AssignmentProblem problem = split_problem(6);
  problem.rows.pixel.clear();
  const auto assignment = problem.model.assignment;
  const PixelClusterChange change =
      share_pixel_clusters(problem.rows, problem.model, cpu_fits(problem));
  EXPECT_EQ(change.split_pixels, 0u);
  EXPECT_EQ(problem.model.assignment, assignment);
}

TEST(PixelClusters, TheOpenClFitsChooseAsTheCpuPathDoes) {
  AssignmentProblem cpu = split_problem(7);
  AssignmentProblem opencl = cpu;
  share_pixel_clusters(cpu.rows, cpu.model, cpu_fits(cpu));
  OpenClAssigner assigner("", IrlsSettings{});
  share_pixel_clusters(opencl.rows, opencl.model, [&](const CandidateLists& lists) {
    return assigner.assign(opencl.rows, opencl.model, lists);
  });
  EXPECT_EQ(split_pixels(opencl.rows, opencl.model), 0u);
  std::size_t same = 0;
  for (std::size_t r = 0; r < cpu.rows.rows(); ++r)
    same += cpu.model.assignment[r] == opencl.model.assignment[r];
  // Different choices only where two clusters fit a pixel almost equally well.
  EXPECT_GE(double(same) / double(cpu.rows.rows()), 0.99);
}

}  // namespace
}  // namespace relume
