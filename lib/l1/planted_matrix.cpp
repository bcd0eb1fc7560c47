// Implementation of the planted low-rank-plus-sparse matrices and the support comparison.
#include "l1/planted_matrix.hpp"

#include <cmath>
#include <random>

namespace relume {

PlantedMatrix make_planted_matrix(int rows, int cols, int rank, double density,
                                  std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::normal_distribution<double> normal;
  std::uniform_real_distribution<double> uniform;
  PlantedMatrix planted;
  planted.W = Eigen::MatrixXd::NullaryExpr(rows, rank, [&] { return normal(random); });
  planted.F = Eigen::MatrixXd::NullaryExpr(rank, cols, [&] { return normal(random); });
  planted.E = Eigen::MatrixXd::Zero(rows, cols);
  for (Eigen::Index k = 0; k < planted.E.size(); ++k)
    if (uniform(random) < density)
      planted.E.data()[k] = (uniform(random) < 0.5 ? -1 : 1) * (1 + uniform(random));
  planted.R = planted.W * planted.F + planted.E;
  return planted;
}

SupportMatch compare_support(const Eigen::MatrixXd& estimate, const Eigen::MatrixXd& truth,
                             double threshold) {
  double found = 0, planted = 0, both = 0;
  for (Eigen::Index k = 0; k < truth.size(); ++k) {
    const bool is_found = std::abs(estimate.data()[k]) > threshold;
    const bool is_planted = truth.data()[k] != 0;
    found += is_found;
    planted += is_planted;
    both += is_found && is_planted;
  }
  SupportMatch match;
  if (found > 0) match.precision = both / found;
  if (planted > 0) match.recall = both / planted;
  return match;
}

}  // namespace relume
