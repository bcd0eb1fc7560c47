// Implementation of the seeded random reassignment problem.
#include "compress/random_assignment_problem.hpp"

#include <random>
#include <relume/error.hpp>
#include <string>

namespace relume {

std::size_t AssignmentProblem::candidate_count() const {
  std::size_t count = 0;
  for (const std::int32_t k : candidates.clusters) count += k >= 0;
  return count;
}

AssignmentProblem random_assignment_problem(const AssignmentProblemShape& shape) {
  if (shape.rows <= 0 || shape.clusters <= 0 || shape.terms <= 0 || shape.lights <= 0 ||
      shape.candidates <= 0)
    throw Error(
        "random assignment problem: rows, clusters, terms, lights and candidates must be "
        "positive (got " +
        std::to_string(shape.rows) + " rows, " + std::to_string(shape.clusters) + " clusters, " +
        std::to_string(shape.terms) + " terms, " + std::to_string(shape.lights) + " lights, " +
        std::to_string(shape.candidates) + " candidates)");
  std::mt19937_64 random(shape.seed);
  std::normal_distribution<float> normal;
  AssignmentProblem problem;
  ClusterModel& model = problem.model;
  model.terms = shape.terms;
  model.lights = shape.lights;
  model.clusters = shape.clusters;
  model.bases.resize(std::size_t(shape.clusters) * shape.terms * shape.lights);
  for (float& value : model.bases) value = normal(random);
  problem.rows.values.resize(shape.rows, shape.lights);
  problem.rows.norms.assign(std::size_t(shape.rows), 1.0f);
  Eigen::RowVectorXf weights(shape.terms);
  for (int r = 0; r < shape.rows; ++r) {
    const int k = static_cast<int>(random() % shape.clusters);
    for (int j = 0; j < shape.terms; ++j) weights[j] = normal(random);
    const Eigen::Map<const RowMatrixF> basis(model.basis(k), shape.terms, shape.lights);
    Eigen::RowVectorXf row = weights * basis;
    for (int i = 0; i < shape.lights; ++i) row[i] += 0.05f * normal(random);
    for (int e = 0; e < 3; ++e) row[random() % shape.lights] += 2.0f * normal(random);
    problem.rows.values.row(r) = row / row.norm();
  }
  problem.candidates.width = shape.candidates;
  problem.candidates.clusters.reserve(std::size_t(shape.rows) * shape.candidates);
  for (int r = 0; r < shape.rows; ++r) {
    const int count = shape.lists_end_early ? 1 + static_cast<int>(random() % shape.candidates)
                                            : shape.candidates;
    for (int slot = 0; slot < shape.candidates; ++slot)
      problem.candidates.clusters.push_back(
          slot < count ? static_cast<int>(random() % shape.clusters) : -1);
  }
  return problem;
}

}  // namespace relume
