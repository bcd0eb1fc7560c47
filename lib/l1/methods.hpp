// Private interface between LadSolver (l1_regression.cpp) and its four solvers (l1_lp_primal.cpp,
// l1_lp_dual.cpp, l1_huber.cpp, l1_irls.cpp). LadSolver hands every solver a normalised problem:
// the design has at least one row and one column, each non-zero design column has max |entry| 1,
// and the right-hand side has max |entry| 1 (an all-zero right-hand side never reaches a solver).
// LadSolver undoes both scalings and computes the reported L1 objective itself.
#pragma once

#include <Eigen/Core>
#include <memory>

#include "l1/regression.hpp"

namespace relume {

class LadMethod {
 public:
  virtual ~LadMethod() = default;
  // Returns x for min ||rhs - design x||_1 (or the method's approximation of it).
  virtual Eigen::VectorXd solve(const Eigen::VectorXd& rhs) = 0;
};

std::unique_ptr<LadMethod> make_lp_primal_method(const Eigen::MatrixXd& design,
                                                 bool nonnegative_residual);
std::unique_ptr<LadMethod> make_lp_dual_method(const Eigen::MatrixXd& design,
                                               bool nonnegative_residual);
// gamma: the Huber threshold for the normalised right-hand side (max |entry| 1).
std::unique_ptr<LadMethod> make_huber_method(const Eigen::MatrixXd& design, double gamma);
std::unique_ptr<LadMethod> make_irls_method(const Eigen::MatrixXd& design,
                                            const L1Options& options);

}  // namespace relume
