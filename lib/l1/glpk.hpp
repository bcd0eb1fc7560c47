// A GLPK problem owned by one thread, for the LP forms of L1 regression (l1_lp_primal.cpp,
// l1_lp_dual.cpp). GLPK keeps its memory in a per-thread environment (Debian builds it with
// thread-local storage), so a problem must be created, solved and deleted on one thread. When the
// last problem of a thread is deleted, that thread's environment is freed too: worker threads that
// end leave no GLPK memory behind.
#pragma once

#include <glpk.h>

#include <functional>
#include <string>

namespace relume {

class GlpkProblem {
 public:
  GlpkProblem();
  ~GlpkProblem();
  GlpkProblem(const GlpkProblem&) = delete;
  GlpkProblem& operator=(const GlpkProblem&) = delete;

  glp_prob* get() const { return problem_; }

  // How a solve starts from nothing: the basis to set and the simplex method to run from it.
  struct ColdStart {
    std::function<void()> set_basis;
    int method;
  };

  // Runs the simplex method (GLP_PRIMAL, GLP_DUALP, ...) from the current basis with presolving
  // off, so the basis of the previous solve is the warm start, within a bound on the iterations.
  // When that fails, runs out of iterations (GLPK can cycle on these degenerate LPs) or ends
  // without an optimum, it retries once from `cold`, the start a first solve uses, with the
  // textbook ratio test instead of Harris' (glpk.cpp says why). Returns the
  // final glp_get_status; throws Error (naming `what`) when GLPK itself fails twice.
  int simplex(int method, const ColdStart& cold, const std::string& what);

 private:
  glp_prob* problem_;
};

}  // namespace relume
