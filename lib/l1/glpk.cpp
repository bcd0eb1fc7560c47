// Implementation of GlpkProblem: per-thread count of live problems, environment release, and the
// simplex call with an iteration bound and one cold retry.
#include "l1/glpk.hpp"

#include <relume/error.hpp>

namespace relume {
namespace {
thread_local int live_problems_on_this_thread = 0;
constexpr double kFeasibilityTolerance = 1e-10;
// Simplex iterations allowed per row and column of the problem. A warm-started solve takes a few
// pivots and a cold one about two per row, but GLPK's own bound is INT_MAX and its ratio test can
// cycle on the degenerate L1 LPs: seen on a loaded machine, where the thread schedule decides
// which warm basis a solve starts from, as a solve that never ended.
constexpr int kIterationsPerDimension = 50;
constexpr int kIterationsAtLeast = 1000;

// GLPK's default ratio test is Harris' two-pass one. At the tight tolerance it can creep through
// ever smaller improvements without end (seen on captured cold starts that the textbook test
// solves in some 30 pivots, tests/l1/l1_regression_test.cpp), so the retry uses the textbook test.
int run_simplex(glp_prob* problem, int method, int ratio_test) {
  glp_smcp parameters;
  glp_init_smcp(&parameters);
  parameters.msg_lev = GLP_MSG_OFF;
  parameters.presolve = GLP_OFF;
  parameters.meth = method;
  parameters.r_test = ratio_test;
  // Tighter than GLPK's 1e-7: the problems arrive normalised (l1_methods.hpp), and the alternating
  // factorization stalls at the accuracy of its solves (measured in docs/factorization.md).
  parameters.tol_bnd = kFeasibilityTolerance;
  parameters.tol_dj = kFeasibilityTolerance;
  parameters.it_lim =
      kIterationsPerDimension * (glp_get_num_rows(problem) + glp_get_num_cols(problem)) +
      kIterationsAtLeast;
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

int GlpkProblem::simplex(int method, const ColdStart& cold, const std::string& what) {
  int code = run_simplex(problem_, method, GLP_RT_HAR);
  if (code == 0 && glp_get_status(problem_) == GLP_OPT) return GLP_OPT;
  cold.set_basis();
  code = run_simplex(problem_, cold.method, GLP_RT_STD);
  if (code == GLP_EITLIM)
    throw Error(what + ": GLPK's simplex ran past " + std::to_string(kIterationsPerDimension) +
                " iterations per row and column twice, the last time from a cold start");
  if (code != 0)
    throw Error(what + ": GLPK's simplex failed twice (glp_simplex code " + std::to_string(code) +
                "), the last time from a cold start");
  return glp_get_status(problem_);
}

}  // namespace relume
