// Sparse residual factorization of one matrix (the paper's Section 3.2, without clusters):
//     R ~ W F + E,  W: rows x terms, F: terms x columns, E as sparse as possible,
// by alternating exact (or approximate) L1 regressions: the W-step fits every row of R on the
// rows of F, the F-step fits every column of R on the columns of W. Each step can only lower
// ||R - W F||_1 with an exact solver, so the alternation stops when the relative decrease falls
// below a tolerance (or at an iteration cap). With the approximate solvers (huber, irls) the L1
// objective can rise: the alternation then stops and returns the best iterate.
//
// Documented behaviour at the extremes (see docs/factorization.md and the tests):
//  - terms >= columns: W-step fits are exact, E = 0 after one iteration;
//  - all-zero rows of R get zero weights and a zero residual;
//  - rows scaled by 1e-8 or 1e8: no NaN; the objective is the plain L1 norm, so the F-step is
//    dominated by large rows; each row's residual threshold is relative to that row's magnitude;
//  - a basis row that becomes zero (rank-deficient F) stays zero and its weights are zero;
//  - NaN or Inf in R is refused with its position.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "l1/regression.hpp"

namespace relume {

enum class FactorizationInit {
  random_basis,    // F ~ N(0, 1), the first step is a W-step (the paper's random start)
  random_weights,  // W ~ N(0, 1), the first step is an F-step
  svd,             // F = the leading right singular vectors of R (an L2 start), then a W-step
};

// "random-basis", "random-weights", "svd" <-> FactorizationInit; throws Error on a bad name.
FactorizationInit parse_factorization_init(const std::string& name);
std::string to_string(FactorizationInit init);

struct FactorizationOptions {
  L1Options l1;
  unsigned threads = 0;  // 0 = all cores
  std::uint64_t seed = 1;
  FactorizationInit init = FactorizationInit::random_basis;
  int max_iterations = 50;
  double relative_tolerance = 1e-8;  // stop when the L1 objective drops by less than this fraction
  // |E[p, i]| <= residual_threshold * max_i |R[p, i]| is set to 0 (solver round-off).
  double residual_threshold = 1e-9;
  // Called after each iteration (1-based) with ||R - W F||_1; may be empty.
  std::function<void(int iteration, double objective)> on_iteration;
};

struct L1Factorization {
  Eigen::MatrixXd W, F, E;                      // R = W F + E up to the zeroed round-off
  std::vector<double> objective_per_iteration;  // ||R - W F||_1 after each iteration
};

L1Factorization factorize_l1(const Eigen::MatrixXd& R, int terms, const FactorizationOptions&);

}  // namespace relume
