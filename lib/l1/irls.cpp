// Fast approximate L1 regression by iteratively reweighted least squares: each step solves the
// weighted least-squares problem with weights 1 / max(|r_i|, epsilon) from the last residual r
// (a majorise-minimise step on a smoothed L1 objective), starting from the plain least-squares
// fit, until the relative change of ||r||_1 falls below the tolerance. The result is then
// polished to a vertex: the L1 optimum interpolates `unknowns` observations, so the fit through
// the observations with the smallest residuals is tried and kept when its L1 objective is lower.
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

#include "l1/methods.hpp"

namespace relume {
namespace {

class IrlsMethod final : public LadMethod {
 public:
  IrlsMethod(const Eigen::MatrixXd& design, const L1Options& options)
      : design_(design), options_(options) {}

  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) override {
    Eigen::VectorXd x = design_.colPivHouseholderQr().solve(rhs);
    Eigen::VectorXd residual = rhs - design_ * x;
    double objective = residual.lpNorm<1>();
    Eigen::VectorXd best = x;
    double best_objective = objective;
    for (int iteration = 0; iteration < options_.irls_max_iterations && objective > 0;
         ++iteration) {
      const Eigen::VectorXd root_weights = residual.unaryExpr([this](double r) {
        return 1.0 / std::sqrt(std::max(std::abs(r), options_.irls_epsilon));
      });
      x = (root_weights.asDiagonal() * design_)
              .colPivHouseholderQr()
              .solve(root_weights.cwiseProduct(rhs));
      residual = rhs - design_ * x;
      const double next_objective = residual.lpNorm<1>();
      if (next_objective < best_objective) {
        best = x;
        best_objective = next_objective;
      }
      const bool converged =
          std::abs(objective - next_objective) <= options_.irls_tolerance * objective;
      objective = next_objective;
      if (converged) break;
    }
    polish_to_vertex(rhs, best, best_objective);
    return best;
  }

 private:
  // Interpolates the linearly independent observations with the smallest |residual| (greedy, in
  // that order) and keeps the result when it lowers the L1 objective.
  void polish_to_vertex(const Eigen::VectorXd& rhs, Eigen::VectorXd& x, double& objective) const {
    const Eigen::Index unknowns = design_.cols();
    const Eigen::VectorXd residual = (rhs - design_ * x).cwiseAbs();
    std::vector<Eigen::Index> order(residual.size());
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(),
              [&](Eigen::Index a, Eigen::Index b) { return residual[a] < residual[b]; });
    // Orthonormal basis of the chosen rows (Gram-Schmidt, twice for stability).
    Eigen::MatrixXd basis(unknowns, unknowns);
    std::vector<Eigen::Index> chosen;
    for (Eigen::Index i : order) {
      if (Eigen::Index(chosen.size()) == unknowns) break;
      Eigen::VectorXd row = design_.row(i).transpose();
      const double norm = row.norm();
      if (norm == 0) continue;
      for (int pass = 0; pass < 2; ++pass)
        for (std::size_t k = 0; k < chosen.size(); ++k)
          row -= basis.col(Eigen::Index(k)).dot(row) * basis.col(Eigen::Index(k));
      if (row.norm() <= 1e-9 * norm) continue;
      basis.col(Eigen::Index(chosen.size())) = row.normalized();
      chosen.push_back(i);
    }
    if (Eigen::Index(chosen.size()) < unknowns) return;  // rank-deficient design: keep IRLS's x
    Eigen::MatrixXd rows(unknowns, unknowns);
    Eigen::VectorXd values(unknowns);
    for (Eigen::Index k = 0; k < unknowns; ++k) {
      rows.row(k) = design_.row(chosen[std::size_t(k)]);
      values[k] = rhs[chosen[std::size_t(k)]];
    }
    const Eigen::VectorXd vertex = rows.colPivHouseholderQr().solve(values);
    const double vertex_objective = (rhs - design_ * vertex).lpNorm<1>();
    if (vertex_objective < objective) {
      x = vertex;
      objective = vertex_objective;
    }
  }

  Eigen::MatrixXd design_;
  L1Options options_;
};

}  // namespace

std::unique_ptr<LadMethod> make_irls_method(const Eigen::MatrixXd& design,
                                            const L1Options& options) {
  return std::make_unique<IrlsMethod>(design, options);
}

}  // namespace relume
