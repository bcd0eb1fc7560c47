// Alternating L1 factorization R ~ W F + E: initialisation, the W- and F-steps as batched L1
// regressions, the stopping rule, and the thresholded residual.
#include "l1/factorization.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <relume/error.hpp>

namespace relume {
namespace {

Eigen::MatrixXd gaussian(Eigen::Index rows, Eigen::Index cols, std::mt19937_64& random) {
  std::normal_distribution<double> normal;
  Eigen::MatrixXd values(rows, cols);
  for (Eigen::Index i = 0; i < values.size(); ++i) values.data()[i] = normal(random);
  return values;
}

void check_input(const Eigen::MatrixXd& R, int terms, const FactorizationOptions& options) {
  if (terms < 1) throw Error("factorization: terms must be >= 1, got " + std::to_string(terms));
  // More terms than the smaller side of R explain nothing more (rank) and would only size W and F.
  if (terms > std::min(R.rows(), R.cols()))
    throw Error("factorization: " + std::to_string(terms) + " terms for a " +
                std::to_string(R.rows()) + " x " + std::to_string(R.cols()) +
                " matrix, expected at most min(rows, columns) = " +
                std::to_string(std::min(R.rows(), R.cols())));
  if (options.max_iterations < 1)
    throw Error("factorization: the iteration cap must be >= 1, got " +
                std::to_string(options.max_iterations));
  if (!(options.relative_tolerance >= 0))
    throw Error("factorization: the relative tolerance must be >= 0");
  if (!(options.residual_threshold >= 0))
    throw Error("factorization: the residual threshold must be >= 0");
  for (Eigen::Index j = 0; j < R.cols(); ++j)
    for (Eigen::Index i = 0; i < R.rows(); ++i)
      if (!std::isfinite(R(i, j)))
        throw Error("factorization: matrix entry (row " + std::to_string(i) + ", column " +
                    std::to_string(j) + ") is not finite; expected finite values");
}

// The leading right singular vectors of R (eigenvectors of R^T R, columns x columns) as basis
// rows; rows past R's rank stay random.
Eigen::MatrixXd svd_basis(const Eigen::MatrixXd& R, int terms, std::mt19937_64& random) {
  Eigen::MatrixXd F = gaussian(terms, R.cols(), random);
  if (R.size() == 0) return F;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(R.transpose() * R);
  const Eigen::VectorXd& values = eigen.eigenvalues();  // ascending
  const double largest = values[values.size() - 1];
  for (Eigen::Index k = 0; k < std::min<Eigen::Index>(terms, values.size()); ++k) {
    const Eigen::Index index = values.size() - 1 - k;
    if (!(values[index] > 1e-12 * largest)) break;
    F.row(k) = eigen.eigenvectors().col(index).transpose();
  }
  return F;
}

// Scales every basis row to max |entry| 1 and the weights inversely: W F is unchanged.
void normalise_basis(Eigen::MatrixXd& W, Eigen::MatrixXd& F) {
  for (Eigen::Index k = 0; k < F.rows(); ++k) {
    const double largest = F.cols() ? F.row(k).cwiseAbs().maxCoeff() : 0.0;
    if (largest > 0) {
      F.row(k) /= largest;
      W.col(k) *= largest;
    }
  }
}

}  // namespace

FactorizationInit parse_factorization_init(const std::string& name) {
  if (name == "random-basis") return FactorizationInit::random_basis;
  if (name == "random-weights") return FactorizationInit::random_weights;
  if (name == "svd") return FactorizationInit::svd;
  throw Error("unknown initialisation '" + name +
              "': expected random-basis, random-weights or svd");
}

std::string to_string(FactorizationInit init) {
  switch (init) {
    case FactorizationInit::random_basis:
      return "random-basis";
    case FactorizationInit::random_weights:
      return "random-weights";
    case FactorizationInit::svd:
      return "svd";
  }
  return "unknown";
}

L1Factorization factorize_l1(const Eigen::MatrixXd& R, int terms,
                             const FactorizationOptions& options) {
  check_input(R, terms, options);
  std::mt19937_64 random(options.seed);
  Eigen::MatrixXd W = Eigen::MatrixXd::Zero(R.rows(), terms);
  Eigen::MatrixXd F = Eigen::MatrixXd::Zero(terms, R.cols());
  switch (options.init) {
    case FactorizationInit::random_basis:
      F = gaussian(terms, R.cols(), random);
      break;
    case FactorizationInit::random_weights:
      W = gaussian(R.rows(), terms, random);
      break;
    case FactorizationInit::svd:
      F = svd_basis(R, terms, random);
      break;
  }
  const bool weights_first = options.init == FactorizationInit::random_weights;
  const Eigen::MatrixXd R_transposed = R.transpose();
  double objective = 0;
  auto weight_step = [&] {
    W = solve_lad_columns(F.transpose(), R_transposed, options.l1, options.threads, &objective)
            .transpose();
  };
  auto basis_step = [&] { F = solve_lad_columns(W, R, options.l1, options.threads, &objective); };

  L1Factorization result;
  double best = std::numeric_limits<double>::infinity();
  for (int iteration = 1; iteration <= options.max_iterations; ++iteration) {
    if (weights_first) {
      basis_step();
      weight_step();
    } else {
      weight_step();
      basis_step();
    }
    normalise_basis(W, F);
    result.objective_per_iteration.push_back(objective);
    if (options.on_iteration) options.on_iteration(iteration, objective);
    const double previous = best;
    if (objective < best) {
      best = objective;
      result.W = W;
      result.F = F;
    }
    const bool decreased_enough =
        std::isinf(previous) || previous - objective > options.relative_tolerance * previous;
    if (objective == 0 || !decreased_enough) break;
  }
  result.E = R - result.W * result.F;
  for (Eigen::Index p = 0; p < R.rows(); ++p) {
    const double threshold =
        options.residual_threshold * (R.cols() ? R.row(p).cwiseAbs().maxCoeff() : 0.0);
    for (Eigen::Index i = 0; i < R.cols(); ++i)
      if (std::abs(result.E(p, i)) <= threshold) result.E(p, i) = 0;
  }
  return result;
}

}  // namespace relume
