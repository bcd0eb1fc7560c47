// The dual of the L1 regression LP: max b^T d subject to A^T d = 0 and -1 <= d <= 1 (d <= 1 alone
// for a non-negative residual). It has one equality row per unknown instead of one per
// observation, and b only enters the objective: the previous optimal basis stays primal feasible
// for the next right-hand side, so each solve after the first is a warm-started primal simplex.
// The regression weights x are the dual values of the equality rows; at the optimum d_i is the
// sign of the residual b_i - A_i x wherever that is non-zero.
#include <relume/error.hpp>
#include <vector>

#include "l1/glpk.hpp"
#include "l1/methods.hpp"

namespace relume {
namespace {

class LpDualMethod final : public LadMethod {
 public:
  LpDualMethod(const Eigen::MatrixXd& design, bool nonnegative_residual)
      : observations_(static_cast<int>(design.rows())),
        unknowns_(static_cast<int>(design.cols())),
        nonnegative_residual_(nonnegative_residual) {
    glp_prob* lp = problem_.get();
    glp_set_obj_dir(lp, GLP_MAX);
    glp_add_rows(lp, unknowns_);
    for (int j = 1; j <= unknowns_; ++j) glp_set_row_bnds(lp, j, GLP_FX, 0.0, 0.0);
    glp_add_cols(lp, observations_);
    for (int i = 1; i <= observations_; ++i) {
      if (nonnegative_residual)
        glp_set_col_bnds(lp, i, GLP_UP, 0.0, 1.0);
      else
        glp_set_col_bnds(lp, i, GLP_DB, -1.0, 1.0);
    }
    std::vector<int> rows{0}, cols{0};
    std::vector<double> values{0.0};
    for (int i = 0; i < observations_; ++i)
      for (int j = 0; j < unknowns_; ++j)
        if (design(i, j) != 0.0) {
          rows.push_back(j + 1);
          cols.push_back(i + 1);
          values.push_back(design(i, j));
        }
    glp_load_matrix(lp, static_cast<int>(rows.size()) - 1, rows.data(), cols.data(), values.data());
    glp_scale_prob(lp, GLP_SF_AUTO);
  }

  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) override {
    glp_prob* lp = problem_.get();
    for (int i = 0; i < observations_; ++i) glp_set_obj_coef(lp, i + 1, rhs[i]);
    // A new problem starts from the standard basis (rows basic, every d at a bound).
    const GlpkProblem::ColdStart cold{[lp] { glp_std_basis(lp); }, GLP_PRIMAL};
    const int status = problem_.simplex(GLP_PRIMAL, cold, "L1 regression (lp-dual)");
    if (status == GLP_UNBND && nonnegative_residual_)
      throw Error(
          "L1 regression (lp-dual) with a non-negative residual has no solution: no x gives "
          "b - A x >= 0 for this right-hand side (it has entries that the design cannot go under)");
    if (status != GLP_OPT)
      throw Error("L1 regression (lp-dual): GLPK ended with status " + std::to_string(status) +
                  " instead of an optimum");
    Eigen::VectorXd x(unknowns_);
    for (int j = 0; j < unknowns_; ++j) x[j] = glp_get_row_dual(lp, j + 1);
    return x;
  }

 private:
  GlpkProblem problem_;
  int observations_;
  int unknowns_;
  bool nonnegative_residual_;
};

}  // namespace

std::unique_ptr<LadMethod> make_lp_dual_method(const Eigen::MatrixXd& design,
                                               bool nonnegative_residual) {
  return std::make_unique<LpDualMethod>(design, nonnegative_residual);
}

}  // namespace relume
