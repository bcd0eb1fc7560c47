// Implementation of the IRLS weight fit of one function against one cluster basis
// (see cluster_function_fit.hpp).
#include "compress/cluster_function_fit.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace relume {

void solve_small_spd(double* gram, double* rhs, int n) {
  double trace = 0;
  for (int j = 0; j < n; ++j) trace += gram[j * n + j];
  const double ridge = 1e-10 * trace + 1e-30;
  for (int j = 0; j < n; ++j) gram[j * n + j] += ridge;
  // In-place Cholesky G = L L^T (lower triangle), then forward and back substitution.
  for (int j = 0; j < n; ++j) {
    double diagonal = gram[j * n + j];
    for (int k = 0; k < j; ++k) diagonal -= gram[j * n + k] * gram[j * n + k];
    if (!(diagonal > ridge * 1e-3)) {  // no support in this direction
      for (int i = j; i < n; ++i) gram[i * n + j] = 0;
      gram[j * n + j] = 1;
      continue;
    }
    const double root = std::sqrt(diagonal);
    gram[j * n + j] = root;
    for (int i = j + 1; i < n; ++i) {
      double value = gram[i * n + j];
      for (int k = 0; k < j; ++k) value -= gram[i * n + k] * gram[j * n + k];
      gram[i * n + j] = value / root;
    }
  }
  for (int j = 0; j < n; ++j) {
    double value = rhs[j];
    for (int k = 0; k < j; ++k) value -= gram[j * n + k] * rhs[k];
    rhs[j] = value / gram[j * n + j];
  }
  for (int j = n - 1; j >= 0; --j) {
    double value = rhs[j];
    for (int k = j + 1; k < n; ++k) value -= gram[k * n + j] * rhs[k];
    rhs[j] = value / gram[j * n + j];
  }
}

namespace {

// The fit for T terms known at compile time (Eigen::Dynamic for any count): Eigen's vectorized
// products and reductions over the lights.
template <int T>
float fit_l1(const float* basis, int terms, int lights, const float* row, float epsilon,
             int iterations, float* weights, FunctionFitScratch& scratch) {
  using Basis = Eigen::Matrix<float, T, Eigen::Dynamic, Eigen::RowMajor>;
  using Vector = Eigen::Matrix<float, T, 1>;
  const Eigen::Map<const Basis> f(basis, terms, lights);
  const Eigen::Map<const Eigen::RowVectorXf> x(row, lights);
  Eigen::Map<Eigen::RowVectorXf> residual(scratch.residual.data(), lights);
  Eigen::Map<Basis> weighted(scratch.weighted_basis.data(), terms, lights);
  Vector current(terms), best_weights(terms);
  const auto solve = [&](const auto& scaled) {
    Eigen::Matrix<double, T, T> gram = (scaled.lazyProduct(f.transpose())).template cast<double>();
    Eigen::Matrix<double, T, 1> rhs = (scaled.lazyProduct(x.transpose())).template cast<double>();
    solve_small_spd(gram.data(), rhs.data(), terms);
    current = rhs.template cast<float>();
  };
  solve(f);
  residual.noalias() = x - current.transpose() * f;
  float best = residual.cwiseAbs().sum();
  best_weights = current;
  for (int iteration = 0; iteration < iterations; ++iteration) {
    weighted = f.array().rowwise() * residual.array().abs().max(epsilon).inverse();
    solve(weighted);
    residual.noalias() = x - current.transpose() * f;
    const float objective = residual.cwiseAbs().sum();
    if (objective < best) {
      best = objective;
      best_weights = current;
    }
  }
  std::copy(best_weights.data(), best_weights.data() + terms, weights);
  return best;
}

}  // namespace

float fit_function_l1(const float* basis, int terms, int lights, const float* row, float norm,
                      const IrlsSettings& settings, float* weights, FunctionFitScratch& scratch) {
  scratch.residual.resize(lights);
  scratch.weighted_basis.resize(std::size_t(terms) * lights);
  const float epsilon = settings.epsilon * norm;
  const int iterations = settings.iterations;
  switch (terms) {
    case 1:
      return fit_l1<1>(basis, terms, lights, row, epsilon, iterations, weights, scratch);
    case 2:
      return fit_l1<2>(basis, terms, lights, row, epsilon, iterations, weights, scratch);
    case 3:
      return fit_l1<3>(basis, terms, lights, row, epsilon, iterations, weights, scratch);
    case 4:
      return fit_l1<4>(basis, terms, lights, row, epsilon, iterations, weights, scratch);
    case 6:
      return fit_l1<6>(basis, terms, lights, row, epsilon, iterations, weights, scratch);
    case 8:
      return fit_l1<8>(basis, terms, lights, row, epsilon, iterations, weights, scratch);
    default:
      return fit_l1<Eigen::Dynamic>(basis, terms, lights, row, epsilon, iterations, weights,
                                    scratch);
  }
}

}  // namespace relume
