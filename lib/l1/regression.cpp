// LadSolver: input checks, normalisation (design columns to max |entry| 1, right-hand side to
// max |entry| 1), the choice of solver, and the batched solve over worker threads.
#include "l1/regression.hpp"

#include <atomic>
#include <cmath>
#include <cstdint>
#include <optional>
#include <relume/error.hpp>
#include <sstream>
#include <vector>

#include "core/parallel.hpp"
#include "l1/methods.hpp"

namespace relume {
namespace {

std::string describe(double value) {
  std::ostringstream text;
  text << value;
  return text.str();
}

void check_options(const L1Options& options) {
  if (options.method == L1Method::huber &&
      !(options.huber_gamma > 0 && std::isfinite(options.huber_gamma)))
    throw Error("Huber gamma must be a positive finite number, got " +
                describe(options.huber_gamma));
  if (options.method == L1Method::irls) {
    if (!(options.irls_tolerance >= 0))
      throw Error("IRLS tolerance must be >= 0, got " + describe(options.irls_tolerance));
    if (options.irls_max_iterations < 1)
      throw Error("IRLS iteration cap must be >= 1, got " +
                  std::to_string(options.irls_max_iterations));
    if (!(options.irls_epsilon > 0))
      throw Error("IRLS epsilon must be > 0, got " + describe(options.irls_epsilon));
  }
  if (options.nonnegative_residual && options.method != L1Method::lp_primal &&
      options.method != L1Method::lp_dual)
    throw Error("a non-negative residual is only supported by the lp and lp-dual solvers, not " +
                to_string(options.method));
}

void check_finite(const Eigen::MatrixXd& values, const std::string& what) {
  for (Eigen::Index j = 0; j < values.cols(); ++j)
    for (Eigen::Index i = 0; i < values.rows(); ++i)
      if (!std::isfinite(values(i, j)))
        throw Error("L1 regression: " + what + " entry (" + std::to_string(i) + ", " +
                    std::to_string(j) + ") is " + describe(values(i, j)) +
                    "; expected finite values");
}

std::unique_ptr<LadMethod> make_method(const Eigen::MatrixXd& design, const L1Options& options) {
  switch (options.method) {
    case L1Method::lp_primal:
      return make_lp_primal_method(design, options.nonnegative_residual);
    case L1Method::lp_dual:
      return make_lp_dual_method(design, options.nonnegative_residual);
    case L1Method::huber:
      return make_huber_method(design, options.huber_gamma);
    case L1Method::irls:
      return make_irls_method(design, options);
  }
  throw Error("unknown L1 method");
}

}  // namespace

L1Method parse_l1_method(const std::string& name) {
  if (name == "lp") return L1Method::lp_primal;
  if (name == "lp-dual") return L1Method::lp_dual;
  if (name == "huber") return L1Method::huber;
  if (name == "irls") return L1Method::irls;
  throw Error("unknown L1 solver '" + name + "': expected lp, lp-dual, huber or irls");
}

std::string to_string(L1Method method) {
  switch (method) {
    case L1Method::lp_primal:
      return "lp";
    case L1Method::lp_dual:
      return "lp-dual";
    case L1Method::huber:
      return "huber";
    case L1Method::irls:
      return "irls";
  }
  return "unknown";
}

struct LadSolver::Impl {
  Eigen::MatrixXd design;
  Eigen::VectorXd column_scale;       // x = column_scale .* (solution of the normalised design)
  std::unique_ptr<LadMethod> method;  // null when the design has no rows or no columns
};

LadSolver::LadSolver(const Eigen::MatrixXd& design, const L1Options& options)
    : impl_(std::make_unique<Impl>()) {
  check_options(options);
  check_finite(design, "design");
  impl_->design = design;
  impl_->column_scale = Eigen::VectorXd::Ones(design.cols());
  if (design.rows() == 0 || design.cols() == 0) return;
  Eigen::MatrixXd normalised = design;
  for (Eigen::Index j = 0; j < design.cols(); ++j) {
    const double largest = design.col(j).cwiseAbs().maxCoeff();
    if (largest > 0) {
      impl_->column_scale[j] = 1.0 / largest;
      normalised.col(j) /= largest;
    }
  }
  impl_->method = make_method(normalised, options);
}

LadSolver::~LadSolver() = default;
LadSolver::LadSolver(LadSolver&&) noexcept = default;
LadSolver& LadSolver::operator=(LadSolver&&) noexcept = default;

Eigen::VectorXd LadSolver::solve(const Eigen::VectorXd& rhs, double* objective) {
  const Eigen::MatrixXd& design = impl_->design;
  if (rhs.size() != design.rows())
    throw Error("L1 regression: right-hand side has " + std::to_string(rhs.size()) +
                " entries, expected one per design row (" + std::to_string(design.rows()) + ")");
  check_finite(rhs, "right-hand side");
  Eigen::VectorXd x = Eigen::VectorXd::Zero(design.cols());
  const double scale = rhs.size() ? rhs.cwiseAbs().maxCoeff() : 0.0;
  if (impl_->method && scale > 0)
    x = impl_->method->solve(rhs / scale).cwiseProduct(impl_->column_scale) * scale;
  if (objective) *objective = (rhs - design * x).lpNorm<1>();
  return x;
}

namespace {
// The solver a worker thread uses during one solve_lad_columns call. It lives in thread-local
// storage so that it is destroyed on the thread that made it (GLPK requires that): on a worker
// thread when the thread ends, on the calling thread at the end of the call.
struct WorkerSolver {
  std::uint64_t call = 0;
  std::optional<LadSolver> solver;
};
thread_local WorkerSolver worker_solver;
std::atomic<std::uint64_t> next_call{1};

struct ReleaseCallingThreadSolver {
  ~ReleaseCallingThreadSolver() { worker_solver.solver.reset(); }
};
}  // namespace

Eigen::MatrixXd solve_lad_columns(const Eigen::MatrixXd& design, const Eigen::MatrixXd& rhs,
                                  const L1Options& options, unsigned threads, double* objective) {
  if (rhs.rows() != design.rows())
    throw Error("L1 regression: right-hand sides have " + std::to_string(rhs.rows()) +
                " rows, expected one per design row (" + std::to_string(design.rows()) + ")");
  const std::uint64_t call = next_call++;
  Eigen::MatrixXd solutions(design.cols(), rhs.cols());
  std::vector<double> objectives(static_cast<std::size_t>(rhs.cols()), 0.0);
  {
    ReleaseCallingThreadSolver release;
    parallel_for(static_cast<std::size_t>(rhs.cols()), threads, [&](std::size_t index, unsigned) {
      if (worker_solver.call != call || !worker_solver.solver) {
        worker_solver.solver.reset();
        worker_solver.solver.emplace(design, options);
        worker_solver.call = call;
      }
      const auto column = static_cast<Eigen::Index>(index);
      solutions.col(column) = worker_solver.solver->solve(rhs.col(column), &objectives[index]);
    });
  }
  if (objective) {
    *objective = 0;
    for (double value : objectives) *objective += value;
  }
  return solutions;
}

}  // namespace relume
