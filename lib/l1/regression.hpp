// Least-absolute-deviations (L1) regression: min_x ||b - A x||_1 for many right-hand sides b that
// share one design matrix A (observations x unknowns). This is every solve of the alternating
// factorization: W-step (A = F^T, b = a row of R) and F-step (A = W, b = a column of R).
//
// Solvers (see ../shared/GUIDE.md section 2):
//  - lp_primal: the paper's LP, variables (x, k, l), constraints A x + k - l = b, k, l >= 0
//    (with nonnegative_residual the l variables are dropped: b - A x >= 0);
//  - lp_dual:   the LAD dual, max b^T d s.t. A^T d = 0, -1 <= d <= 1 (t equality rows),
//    warm-started from the previous right-hand side's optimal basis; x = the row duals;
//  - huber:     the paper's Huber/QP form with threshold gamma, solved exactly (Newton/active set);
//  - irls:      iteratively reweighted least squares, approximate, stops at `tolerance`.
// One LadSolver holds one GLPK problem and is used by one thread only.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <string>

namespace relume {

enum class L1Method { lp_primal, lp_dual, huber, irls };

// "lp", "lp-dual", "huber", "irls" <-> L1Method; throws Error naming the bad value.
L1Method parse_l1_method(const std::string& name);
std::string to_string(L1Method method);

struct L1Options {
  L1Method method = L1Method::lp_dual;
  double huber_gamma = 1e-3;     // relative to the scale of b (see implementation notes)
  double irls_tolerance = 1e-6;  // relative change of the objective that stops IRLS
  int irls_max_iterations = 100;
  double irls_epsilon = 1e-8;    // smallest |residual| in the IRLS weights, relative to max |b|
  bool nonnegative_residual = false;  // lp_primal and lp_dual only: residual b - A x >= 0
};

class LadSolver {
 public:
  LadSolver(const Eigen::MatrixXd& design, const L1Options& options);
  ~LadSolver();
  LadSolver(LadSolver&&) noexcept;
  LadSolver& operator=(LadSolver&&) noexcept;

  // Returns x; `objective` (if not null) receives ||b - A x||_1.
  Eigen::VectorXd solve(const Eigen::VectorXd& rhs, double* objective = nullptr);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Solves for every column of `rhs` (observations x problems) with `threads` workers (0 = all
// cores), one LadSolver per worker. Returns unknowns x problems; `objective` receives the sum.
Eigen::MatrixXd solve_lad_columns(const Eigen::MatrixXd& design, const Eigen::MatrixXd& rhs,
                                  const L1Options& options, unsigned threads,
                                  double* objective = nullptr);

}  // namespace relume
