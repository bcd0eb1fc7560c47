// The paper's LP for L1 regression: variables (x, k, l), constraints A x + k - l = b with k, l >= 0
// and x free, minimising sum(k) + sum(l); k and l are the positive and negative parts of the
// residual b - A x. With a non-negative residual the l variables are dropped (A x + k = b).
// Only the row bounds (b) change between right-hand sides: the previous optimal basis stays dual
// feasible, so each solve after the first is a warm-started dual simplex.
#include <relume/error.hpp>
#include <vector>

#include "l1/glpk.hpp"
#include "l1/methods.hpp"

namespace relume {
namespace {

class LpPrimalMethod final : public LadMethod {
 public:
  LpPrimalMethod(const Eigen::MatrixXd& design, bool nonnegative_residual)
      : observations_(static_cast<int>(design.rows())),
        unknowns_(static_cast<int>(design.cols())),
        nonnegative_residual_(nonnegative_residual) {
    glp_prob* lp = problem_.get();
    glp_set_obj_dir(lp, GLP_MIN);
    glp_add_rows(lp, observations_);
    for (int i = 1; i <= observations_; ++i) glp_set_row_bnds(lp, i, GLP_FX, 0.0, 0.0);
    const int residual_parts = nonnegative_residual_ ? 1 : 2;
    glp_add_cols(lp, unknowns_ + residual_parts * observations_);
    for (int j = 1; j <= unknowns_; ++j) glp_set_col_bnds(lp, j, GLP_FR, 0.0, 0.0);
    for (int j = unknowns_ + 1; j <= unknowns_ + residual_parts * observations_; ++j) {
      glp_set_col_bnds(lp, j, GLP_LO, 0.0, 0.0);
      glp_set_obj_coef(lp, j, 1.0);
    }
    // Column-major triplets (1-based, GLPK keeps index 0 unused).
    std::vector<int> rows{0}, cols{0};
    std::vector<double> values{0.0};
    for (int j = 0; j < unknowns_; ++j)
      for (int i = 0; i < observations_; ++i)
        if (design(i, j) != 0.0) {
          rows.push_back(i + 1);
          cols.push_back(j + 1);
          values.push_back(design(i, j));
        }
    for (int i = 0; i < observations_; ++i) {
      rows.push_back(i + 1);
      cols.push_back(positive_part(i));
      values.push_back(1.0);
      if (!nonnegative_residual_) {
        rows.push_back(i + 1);
        cols.push_back(negative_part(i));
        values.push_back(-1.0);
      }
    }
    glp_load_matrix(lp, static_cast<int>(rows.size()) - 1, rows.data(), cols.data(), values.data());
    glp_scale_prob(lp, GLP_SF_AUTO);
  }

  Eigen::VectorXd solve(const Eigen::VectorXd& rhs) override {
    glp_prob* lp = problem_.get();
    for (int i = 0; i < observations_; ++i) glp_set_row_bnds(lp, i + 1, GLP_FX, rhs[i], rhs[i]);
    const GlpkProblem::ColdStart cold{[&] { set_residual_basis(rhs); }, GLP_PRIMAL};
    if (!solved_once_) cold.set_basis();
    const int method = solved_once_ ? GLP_DUALP : cold.method;
    const int status = problem_.simplex(method, cold, "L1 regression (lp)");
    if (status == GLP_NOFEAS && nonnegative_residual_)
      throw Error(
          "L1 regression (lp) with a non-negative residual has no solution: no x gives "
          "b - A x >= 0 for this right-hand side (it has entries that the design cannot go under)");
    if (status != GLP_OPT)
      throw Error("L1 regression (lp): GLPK ended with status " + std::to_string(status) +
                  " instead of an optimum");
    solved_once_ = true;
    Eigen::VectorXd x(unknowns_);
    for (int j = 0; j < unknowns_; ++j) x[j] = glp_get_col_prim(lp, j + 1);
    return x;
  }

 private:
  int positive_part(int i) const { return unknowns_ + 1 + i; }
  int negative_part(int i) const { return unknowns_ + 1 + observations_ + i; }

  // The basis of x = 0, primal feasible: every row's residual part that carries b_i is basic, x is
  // non-basic free.
  void set_residual_basis(const Eigen::VectorXd& rhs) {
    glp_prob* lp = problem_.get();
    for (int i = 1; i <= observations_; ++i) glp_set_row_stat(lp, i, GLP_NS);
    for (int j = 1; j <= unknowns_; ++j) glp_set_col_stat(lp, j, GLP_NF);
    for (int i = 0; i < observations_; ++i) {
      const bool positive = rhs[i] >= 0 || nonnegative_residual_;
      glp_set_col_stat(lp, positive_part(i), positive ? GLP_BS : GLP_NL);
      if (!nonnegative_residual_)
        glp_set_col_stat(lp, negative_part(i), positive ? GLP_NL : GLP_BS);
    }
  }

  GlpkProblem problem_;
  int observations_;
  int unknowns_;
  bool nonnegative_residual_;
  bool solved_once_ = false;
};

}  // namespace

std::unique_ptr<LadMethod> make_lp_primal_method(const Eigen::MatrixXd& design,
                                                 bool nonnegative_residual) {
  return std::make_unique<LpPrimalMethod>(design, nonnegative_residual);
}

}  // namespace relume
