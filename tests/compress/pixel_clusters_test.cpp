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

// A random problem whose rows are taken three at a time as the channels of a pixel, with norms
// that differ by channel, and its rows assigned to their best candidates (some pixels split).
struct SplitProblem {
  AssignmentProblem problem;
  AssignmentResult assigned;
};

SplitProblem split_problem(std::uint64_t seed) {
  SplitProblem split{random_assignment_problem({1500, 8, 3, 48, 3, false, seed}), {}};
  WorkingRows& rows = split.problem.rows;
  rows.pixel.resize(rows.rows());
  for (std::size_t r = 0; r < rows.rows(); ++r) {
    rows.pixel[r] = std::uint32_t(r / 3);
    rows.norms[r] = 1.0f + float(r % 3);
  }
  split.assigned = assign_to_best_cluster(rows, split.problem.model, split.problem.candidates,
                                          IrlsSettings{}, 2);
  return split;
}

std::size_t split_pixels(const std::vector<std::int32_t>& cluster) {
  std::size_t split = 0;
  for (std::size_t r = 0; r < cluster.size(); r += 3)
    split += std::set<std::int32_t>(cluster.begin() + std::ptrdiff_t(r),
                                    cluster.begin() + std::ptrdiff_t(r + 3))
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
  const SplitProblem before = split_problem(5);
  const AssignmentProblem& problem = before.problem;
  const std::size_t split = split_pixels(before.assigned.best);
  ASSERT_GT(split, 50u) << "the test needs split pixels";
  AssignmentResult after = before.assigned;
  const PixelClusterChange change = share_pixel_clusters(problem.rows, after, cpu_fits(problem));
  EXPECT_EQ(change.split_pixels, split);
  EXPECT_GT(change.rows_moved, 0u);
  EXPECT_EQ(split_pixels(after.best), 0u);
  const ClusterModel& model = problem.model;
  std::size_t checked = 0;
  for (std::size_t r = 0; r < problem.rows.rows(); r += 3) {
    const std::set<std::int32_t> clusters(before.assigned.best.begin() + std::ptrdiff_t(r),
                                          before.assigned.best.begin() + std::ptrdiff_t(r + 3));
    const std::int32_t chosen = after.best[r];
    if (clusters.size() == 1) {
      EXPECT_EQ(chosen, *clusters.begin()) << "pixel " << r / 3 << " was not split";
      EXPECT_EQ(after.objective[r], before.assigned.objective[r]);
      for (int j = 0; j < model.terms; ++j)
        EXPECT_EQ(after.weights(Eigen::Index(r), j), before.assigned.weights(Eigen::Index(r), j));
      continue;
    }
    ASSERT_TRUE(clusters.count(chosen)) << "pixel " << r / 3;
    const double cost = pixel_cost(problem, r, chosen);
    for (const std::int32_t k : clusters) EXPECT_LE(cost, pixel_cost(problem, r, k) * (1 + 1e-6));
    // The chosen cluster's weights and objective are the rows' fits to it.
    FunctionFitScratch scratch;
    float weights[max_cluster_terms];
    const float objective =
        fit_function_l1(model.basis(chosen), model.terms, model.lights, problem.rows.row(r), 1.0f,
                        IrlsSettings{}, weights, scratch);
    EXPECT_NEAR(after.objective[r], objective, 1e-6f);
    for (int j = 0; j < model.terms; ++j)
      EXPECT_NEAR(after.weights(Eigen::Index(r), j), weights[j], 1e-5f);
    ++checked;
  }
  EXPECT_EQ(checked, split);
}

TEST(PixelClusters, RowsWithoutPixelsAreLeftAlone) {
  SplitProblem split = split_problem(6);
  split.problem.rows.pixel.clear();
  const std::vector<std::int32_t> best = split.assigned.best;
  const PixelClusterChange change =
      share_pixel_clusters(split.problem.rows, split.assigned, cpu_fits(split.problem));
  EXPECT_EQ(change.split_pixels, 0u);
  EXPECT_EQ(split.assigned.best, best);
}

TEST(PixelClusters, TheOpenClFitsChooseAsTheCpuPathDoes) {
  SplitProblem split = split_problem(7);
  const AssignmentProblem& problem = split.problem;
  AssignmentResult cpu = split.assigned, opencl = split.assigned;
  share_pixel_clusters(problem.rows, cpu, cpu_fits(problem));
  OpenClAssigner assigner("", IrlsSettings{});
  share_pixel_clusters(problem.rows, opencl, [&](const CandidateLists& lists) {
    return assigner.assign(problem.rows, problem.model, lists);
  });
  EXPECT_EQ(split_pixels(opencl.best), 0u);
  std::size_t same = 0;
  for (std::size_t r = 0; r < problem.rows.rows(); ++r) same += cpu.best[r] == opencl.best[r];
  // Different choices only where two clusters fit a pixel almost equally well.
  EXPECT_GE(double(same) / double(problem.rows.rows()), 0.99);
}

}  // namespace
}  // namespace relume
