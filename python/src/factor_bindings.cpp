// relume.factor: sparse residual factorization R ~ W F + E of any matrix (`relume factor` on an
// array), with the GIL released, a progress callback and Ctrl-C honoured (python_work.hpp).
#include <pybind11/stl.h>

#include <optional>
#include <relume/error.hpp>

#include "arrays.hpp"
#include "bindings.hpp"
#include "core/progress.hpp"
#include "l1/factorization.hpp"
#include "python_work.hpp"

namespace relume::python {

using namespace pybind11::literals;

namespace {

// The residual thresholds `relume factor` uses by default
// (apps/commands/compress/factor_command.cpp): float32 input is already rounded to ~6e-8 of each
// value, so smaller residuals are that rounding.
constexpr double float32_residual_threshold = 1e-6;
constexpr double float64_residual_threshold = 1e-9;

// A float64 matrix handed over without a copy (column-major, as Eigen holds it), or a float32
// copy in C order.
py::array matrix_out(Eigen::MatrixXd&& matrix, bool float32) {
  const py::ssize_t rows = matrix.rows(), columns = matrix.cols();
  if (float32) {
    std::vector<float> values(static_cast<std::size_t>(matrix.size()));
    Eigen::Map<Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
        values.data(), rows, columns) = matrix.cast<float>();
    return adopt_vector(std::move(values), {rows, columns});
  }
  auto* owned = new Eigen::MatrixXd(std::move(matrix));
  py::capsule free_when_done(owned, [](void* p) { delete static_cast<Eigen::MatrixXd*>(p); });
  const py::ssize_t item = sizeof(double);
  return py::array(py::dtype::of<double>(), {rows, columns}, {item, rows * item}, owned->data(),
                   free_when_done);
}

}  // namespace

void bind_factor(py::module_& module) {
  module.def(
      "factor",
      [](py::handle matrix, int terms, const std::string& solver, const std::string& init,
         std::uint64_t seed, int max_iterations, double tolerance,
         std::optional<double> residual_threshold, double gamma, double irls_tolerance,
         bool nonnegative_residual, unsigned threads, py::object progress) {
        const py::array array =
            checked_array(matrix, "matrix", Accepted::float32or64, {-1, -1}, "(rows, columns)");
        const bool float32 = array.dtype().itemsize() == 4;
        if (array.size() == 0)
          throw Error("the matrix is empty (" + std::to_string(array.shape(0)) + " x " +
                      std::to_string(array.shape(1)) + "); nothing to factor");
        if (terms < 1) throw Error("terms must be >= 1, got " + std::to_string(terms));
        if (max_iterations < 1)
          throw Error("max_iterations must be >= 1, got " + std::to_string(max_iterations));
        const DoubleArray values = finite_float64(array, "matrix");
        const Eigen::MatrixXd R = Eigen::Map<
            const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
            values.data(), array.shape(0), array.shape(1));

        FactorizationOptions options;
        options.l1.method = parse_l1_method(solver);
        options.l1.huber_gamma = gamma;
        options.l1.irls_tolerance = irls_tolerance;
        options.l1.nonnegative_residual = nonnegative_residual;
        options.init = parse_factorization_init(init);
        options.seed = seed;
        options.max_iterations = max_iterations;
        options.relative_tolerance = tolerance;
        options.residual_threshold = residual_threshold.value_or(
            float32 ? float32_residual_threshold : float64_residual_threshold);
        options.threads = threads;

        PythonProgress watcher(std::move(progress));
        L1Factorization result = watcher.run([&] {
          const ProgressListenerScope listening(watcher.listener());
          ProgressReporter iterations("factor: iterations", std::uint64_t(max_iterations), true);
          options.on_iteration = [&](int, double) { iterations.advance(); };
          L1Factorization factored = factorize_l1(R, terms, options);
          iterations.finish();
          return factored;
        });
        return py::make_tuple(matrix_out(std::move(result.W), float32),
                              matrix_out(std::move(result.F), float32),
                              matrix_out(std::move(result.E), float32));
      },
      "matrix"_a, "terms"_a, py::kw_only(), "solver"_a = "lp-dual", "init"_a = "random-basis",
      "seed"_a = 1, "max_iterations"_a = 50, "tolerance"_a = 1e-8,
      "residual_threshold"_a = py::none(), "gamma"_a = 1e-3, "irls_tolerance"_a = 1e-6,
      "nonnegative_residual"_a = false, "threads"_a = 0, "progress"_a = py::none(),
      R"(Sparse residual factorization R ~ W F + E of a matrix by alternating L1 regressions,
as `relume factor` does (same options, same result): returns (W, F, E), W (rows, terms),
F (terms, columns), E (rows, columns), in the matrix's dtype (float32 or float64; float64
results are handed over without a copy, in Fortran order).

solver: "lp" (the paper's LP), "lp-dual" (its dual, warm-started), "huber" (the paper's QP,
exact, threshold gamma) or "irls" (fast, approximate; stops at irls_tolerance).
init: "random-basis" (the paper's start), "random-weights" or "svd". The alternation stops
when the L1 objective drops by less than `tolerance` (relative) or after max_iterations.
residual_threshold: |E| <= this times the row's largest |R| is set to 0 (None: 1e-6 for
float32, 1e-9 for float64). nonnegative_residual: E >= 0 (lp and lp-dual only).
progress: called as progress("factor: iterations", fraction). The GIL is released;
Ctrl-C stops it with KeyboardInterrupt.)");
}

}  // namespace relume::python
