// Implementation of GlpkProblem: per-thread count of live problems, environment release, and the
// simplex call with one cold retry.
#include "l1/glpk.hpp"

#include <relume/error.hpp>

namespace relume {
namespace {
thread_local int live_problems_on_this_thread = 0;
constexpr double kFeasibilityTolerance = 1e-10;

int run_simplex(glp_prob* problem, int method) {
  glp_smcp parameters;
  glp_init_smcp(&parameters);
  parameters.msg_lev = GLP_MSG_OFF;
  parameters.presolve = GLP_OFF;
  parameters.meth = method;
  // Tighter than GLPK's 1e-7: the problems arrive normalised (l1_methods.hpp), and the alternating
  // factorization stalls at the accuracy of its solves (measured in docs/factorization.md).
  parameters.tol_bnd = kFeasibilityTolerance;
  parameters.tol_dj = kFeasibilityTolerance;
  return glp_simplex(problem, &parameters);
}
}  // namespace

GlpkProblem::GlpkProblem() : problem_(glp_create_prob()) {
  ++live_problems_on_this_thread;
  glp_term_out(GLP_OFF);  // scaling reports and the like go nowhere; failures become Errors
}

GlpkProblem::~GlpkProblem() {
  glp_delete_prob(problem_);
  if (--live_problems_on_this_thread == 0) glp_free_env();
}

int GlpkProblem::simplex(int method, const std::string& what) {
  int code = run_simplex(problem_, method);
  if (code == 0 && glp_get_status(problem_) == GLP_OPT) return GLP_OPT;
  glp_std_basis(problem_);
  code = run_simplex(problem_, GLP_PRIMAL);
  if (code != 0)
    throw Error(what + ": GLPK's simplex failed twice (glp_simplex code " + std::to_string(code) +
                "), the last time from the standard basis");
  return glp_get_status(problem_);
}

}  // namespace relume
