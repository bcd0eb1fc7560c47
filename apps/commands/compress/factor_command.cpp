// `relume factor`: sparse residual factorization R ~ W F + E of any matrix stored as a NumPy .npy
// file (float32 or float64), written back as PREFIX_W.npy, PREFIX_F.npy and PREFIX_E.npy in the
// input's dtype. Prints the L1 objective after every iteration.
#include <chrono>
#include <cstdio>
#include <optional>
#include <relume/error.hpp>

#include "command_registry.hpp"
#include "core/atomic_file.hpp"
#include "core/console.hpp"
#include "core/progress.hpp"
#include "field/npy.hpp"
#include "l1/factorization.hpp"
#include "options/output_paths.hpp"

namespace relume {
namespace {

constexpr double kFloat32ResidualThreshold = 1e-6;
constexpr double kFloat64ResidualThreshold = 1e-9;

struct FactorCommandOptions {
  std::string input;
  std::string output_prefix;
  int terms = 0;
  std::string solver = "lp-dual";
  std::string init = "random-basis";
  std::optional<double> residual_threshold;
  FactorizationOptions factorization;
};

void run_factor(FactorCommandOptions options) {
  options.factorization.l1.method = parse_l1_method(options.solver);
  options.factorization.init = parse_factorization_init(options.init);
  for (const char* suffix : {"_W.npy", "_F.npy", "_E.npy"}) {
    check_new_output(options.output_prefix + suffix);
    check_output_file_location(options.output_prefix + suffix);
  }
  const NpyMatrix input = read_npy_matrix(options.input);
  const Eigen::MatrixXd& R = input.values;
  // float32 input is already rounded to ~6e-8 of each value: smaller residuals are that rounding.
  options.factorization.residual_threshold = options.residual_threshold.value_or(
      input.dtype == NpyDtype::float32 ? kFloat32ResidualThreshold : kFloat64ResidualThreshold);
  if (R.size() == 0)
    throw Error(options.input + ": the matrix is empty (" + std::to_string(R.rows()) + " x " +
                std::to_string(R.cols()) + "); nothing to factor");
  note("factoring %s: %lld x %lld, %d terms, solver %s, init %s", options.input.c_str(),
       static_cast<long long>(R.rows()), static_cast<long long>(R.cols()), options.terms,
       options.solver.c_str(), options.init.c_str());
  ProgressReporter progress("factor (iterations, up to the cap)",
                            static_cast<std::uint64_t>(options.factorization.max_iterations));
  const auto start = std::chrono::steady_clock::now();
  options.factorization.on_iteration = [&](int iteration, double objective) {
    progress.advance();
    say("iteration %d: L1 objective %.10g", iteration, objective);
  };
  const L1Factorization result = factorize_l1(R, options.terms, options.factorization);
  progress.finish();
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  const auto nonzeros = (result.E.array() != 0).count();
  say("L1 objective %.10g after %zu iterations in %.2f s; residual non-zeros %lld of %lld "
      "(%.2f%%)",
      result.E.lpNorm<1>(), result.objective_per_iteration.size(), seconds,
      static_cast<long long>(nonzeros), static_cast<long long>(R.size()),
      100.0 * double(nonzeros) / double(R.size()));
  for (const auto& [suffix, matrix] :
       {std::pair{"_W.npy", &result.W}, std::pair{"_F.npy", &result.F},
        std::pair{"_E.npy", &result.E}}) {
    const std::string path = options.output_prefix + suffix;
    write_npy_matrix(path, *matrix, input.dtype);
    say("wrote %s (%lld x %lld)", path.c_str(), static_cast<long long>(matrix->rows()),
        static_cast<long long>(matrix->cols()));
  }
}

const CommandRegistration registration{
    60, [](CLI::App& app) {
      auto options = std::make_shared<FactorCommandOptions>();
      FactorizationOptions& f = options->factorization;
      auto* command =
          app.add_subcommand("factor",
                             "Sparse residual factorization R ~ W F + E of a matrix in a NumPy "
                             ".npy file (L1 objective, "
                             "no clustering); writes PREFIX_W.npy, PREFIX_F.npy, PREFIX_E.npy");
      command
          ->add_option("input", options->input, "Input matrix: a 2-D float32 or float64 .npy file")
          ->required();
      command->add_option("-t,--terms", options->terms, "Number of basis terms t (W is rows x t)")
          ->required()
          ->check(CLI::PositiveNumber);
      command
          ->add_option("-o,--output", options->output_prefix,
                       "Output prefix: writes PREFIX_W.npy, PREFIX_F.npy and PREFIX_E.npy in the "
                       "input's dtype")
          ->required();
      command->add_option("--solver", options->solver,
                          "L1 solver: lp (the paper's LP), lp-dual (its dual, warm-started), huber "
                          "(the paper's QP, exact), irls (fast approximate); default lp-dual");
      command->add_option(
          "--gamma", f.l1.huber_gamma,
          "Huber threshold for --solver huber, relative to each fit's largest |value| "
          "(default 1e-3)");
      command->add_option("--irls-tolerance", f.l1.irls_tolerance,
                          "IRLS stops when the L1 objective changes by less than this fraction "
                          "(default 1e-6)");
      command->add_flag("--nonnegative-residual", f.l1.nonnegative_residual,
                        "Constrain the residual E >= 0 (lp and lp-dual only; default off)");
      command->add_option(
          "--init", options->init,
          "Start: random-basis (random F, the paper's start), random-weights (random "
          "W) or svd (leading right singular vectors); default random-basis");
      command->add_option("--seed", f.seed, "Seed of the random start (default 1)");
      command
          ->add_option("--max-iterations", f.max_iterations,
                       "Iteration cap of the alternation (default 50)")
          ->check(CLI::PositiveNumber);
      command->add_option("--tolerance", f.relative_tolerance,
                          "Stop when the L1 objective drops by less than this fraction in an "
                          "iteration (default 1e-8)");
      command->add_option("--residual-threshold", options->residual_threshold,
                          "Residual entries with |E| <= this times the row's largest |R| are "
                          "set to 0 (default 1e-6 for float32 input, 1e-9 for float64)");
      command->add_option("--threads", f.threads, "Worker threads (default: all cores)");
      command->callback([options] { run_factor(*options); });
    }};

}  // namespace
}  // namespace relume
