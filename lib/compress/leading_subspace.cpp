// Implementation of the leading right singular vectors (see leading_subspace.hpp).
#include "compress/leading_subspace.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <random>

namespace relume {
namespace {

// Extra directions carried by the subspace iteration: the gap between the wanted and the carried
// singular values, not the wanted ones' gap, sets its convergence rate.
constexpr int oversampling = 8;
constexpr int max_iterations = 60;
// The iteration stops when the wanted Ritz values (the captured energy) change by less than this,
// relative: the energy a subspace misses is quadratic in its angle, so this is already far below
// the float noise of the rows.
constexpr double energy_tolerance = 1e-7;
// Eigenvalues below this fraction of the largest are X's null space.
constexpr double rank_tolerance = 1e-12;

// Eigenvectors of a symmetric matrix for its `count` largest eigenvalues, largest first; columns
// whose eigenvalue is in the null space are zero.
Eigen::MatrixXd leading_eigenvectors(const Eigen::MatrixXd& symmetric, int count) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(symmetric);
  const Eigen::Index size = symmetric.rows();
  const double largest = size ? eigen.eigenvalues()[size - 1] : 0.0;
  Eigen::MatrixXd vectors = Eigen::MatrixXd::Zero(size, count);
  for (int j = 0; j < std::min<Eigen::Index>(count, size); ++j) {
    const Eigen::Index index = size - 1 - j;  // eigenvalues ascend
    if (eigen.eigenvalues()[index] > rank_tolerance * largest)
      vectors.col(j) = eigen.eigenvectors().col(index);
  }
  return vectors;
}

// From the Gram matrix of the short side of X: m x m when X has few columns, else n x n (whose
// eigenvectors U give the right singular vectors as X^T U).
Eigen::MatrixXd from_gram(const RowMatrixF& X, int terms) {
  if (X.cols() <= X.rows()) return leading_eigenvectors((X.transpose() * X).cast<double>(), terms);
  const Eigen::MatrixXd U = leading_eigenvectors((X * X.transpose()).cast<double>(), terms);
  return (X.transpose() * U.cast<float>()).cast<double>();
}

// Block subspace iteration on X^T X, then a Rayleigh-Ritz step: about 4 n m b flops per iteration
// for b = terms + oversampling. The block starts from `warm_start` (terms x m rows, e.g. the
// subspace of the previous round) where given, completed by the range of X^T applied to a random
// block.
Eigen::MatrixXd by_subspace_iteration(const RowMatrixF& X, int terms, const float* warm_start) {
  const Eigen::Index block =
      std::min<Eigen::Index>(terms + oversampling, std::min(X.rows(), X.cols()));
  const Eigen::Index given = warm_start ? std::min<Eigen::Index>(terms, block) : 0;
  std::mt19937_64 random(0x5eedu);
  std::normal_distribution<float> normal;
  Eigen::MatrixXf probe(X.rows(), block - given);
  for (Eigen::Index i = 0; i < probe.size(); ++i) probe.data()[i] = normal(random);
  Eigen::MatrixXf Z(X.cols(), block);  // m x b, in X's row space
  if (given)
    Z.leftCols(given) = Eigen::Map<const RowMatrixF>(warm_start, given, X.cols()).transpose();
  Z.rightCols(block - given) = X.transpose() * probe;
  Eigen::MatrixXd Q;
  double previous = -1;
  for (int iteration = 0;; ++iteration) {
    Q = Eigen::HouseholderQR<Eigen::MatrixXd>(Z.cast<double>()).householderQ() *
        Eigen::MatrixXd::Identity(X.cols(), block);
    const Eigen::MatrixXf XQ = X * Q.cast<float>();
    Z = X.transpose() * XQ;
    // Rayleigh quotient Q^T X^T X Q: its leading eigenvalues are the captured energy.
    const Eigen::MatrixXd rayleigh = (XQ.transpose() * XQ).cast<double>();
    const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> ritz(rayleigh);
    const double energy = ritz.eigenvalues().tail(std::min<Eigen::Index>(terms, block)).sum();
    const bool converged = previous >= 0 && energy - previous <= energy_tolerance * energy;
    if (converged || iteration + 1 == max_iterations) {
      const Eigen::MatrixXd U = leading_eigenvectors(rayleigh, terms);
      return Q * U;
    }
    previous = energy;
  }
}

}  // namespace

void orthonormalise_columns(Eigen::MatrixXd& V, DependentColumn dependent) {
  const Eigen::Index m = V.rows();
  Eigen::Index next_unit = 0;
  for (Eigen::Index j = 0; j < V.cols(); ++j) {
    for (;;) {
      const double original = V.col(j).norm();
      for (int pass = 0; pass < 2; ++pass)  // modified Gram-Schmidt, twice for stability
        for (Eigen::Index l = 0; l < j; ++l) V.col(j) -= V.col(l).dot(V.col(j)) * V.col(l);
      const double remaining = V.col(j).norm();
      if (remaining > 1e-6 * original && remaining > 0) {
        V.col(j) /= remaining;
        break;
      }
      if (dependent == DependentColumn::zero) {
        V.col(j).setZero();
        break;
      }
      V.col(j) = Eigen::VectorXd::Unit(m, next_unit++ % m);
    }
  }
}

Eigen::MatrixXd leading_right_singular_vectors(const RowMatrixF& X, int terms,
                                               SubspaceMethod method, const float* warm_start) {
  if (method == SubspaceMethod::automatic) {
    // Flop estimates: the short side's Gram and its eigenvectors, against the iterations (about
    // 15 from a random start, 4 from a warm one).
    const double n = double(X.rows()), m = double(X.cols()), b = terms + oversampling;
    const double short_side = std::min(n, m);
    const double gram_cost = short_side * short_side * (std::max(n, m) + 10 * short_side);
    const double iteration_cost = (warm_start ? 4 : 15) * 4 * n * m * b;
    method =
        gram_cost <= iteration_cost ? SubspaceMethod::gram : SubspaceMethod::subspace_iteration;
  }
  Eigen::MatrixXd V = X.size() == 0 ? Eigen::MatrixXd::Zero(X.cols(), terms)
                      : method == SubspaceMethod::gram
                          ? from_gram(X, terms)
                          : by_subspace_iteration(X, terms, warm_start);
  orthonormalise_columns(V, DependentColumn::unit_vector);
  return V.transpose();
}

}  // namespace relume
