// `relume bench-factor`: the paper's solver comparison on planted matrices R = W F + E (random
// rank-t W F plus a sparse E). For square matrices of growing size at a fixed density, and for
// growing density at a fixed size, it runs the whole alternating factorization with every solver
// from the same start and reports the median wall time, iterations, the final L1 objective's gap
// to the best exact-LP objective, and how well E's support is recovered. A second table times
// single L1 regressions (the W-step with the true basis) per solver. Prints Markdown tables; can
// write every record as JSON.
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <limits>
#include <nlohmann/json.hpp>
#include <relume/error.hpp>
#include <sstream>

#include "command_registry.hpp"
#include "core/elapsed_time.hpp"
#include "core/progress.hpp"
#include "core/json_report.hpp"
#include "l1/factorization.hpp"
#include "l1/planted_matrix.hpp"

namespace relume {
namespace {

struct BenchFactorOptions {
  std::vector<int> sizes{50, 100, 200, 400};
  double density = 0.10;
  std::vector<double> densities{0.01, 0.05, 0.10, 0.20, 0.30};
  int size = 200;
  int terms = 4;
  std::vector<std::string> solvers{"lp", "lp-dual", "huber", "irls"};
  std::vector<double> gammas{1e-3, 1e-5};
  int repeats = 3;
  unsigned threads = 0;
  std::uint64_t seed = 1;
  double support_threshold = 1e-6;
  std::string json;
};

struct BenchCase {
  int size;
  double density;
};

struct FactorRecord {
  BenchCase bench_case;
  std::string solver;
  double seconds = 0;  // median over repeats
  int iterations = 0;
  double objective = 0;
  double gap = 0;  // (objective - best exact LP objective) / best exact LP objective
  SupportMatch support{};
};

struct RegressionRecord {
  int observations;
  std::string solver;
  double microseconds_per_solve = 0;  // median over repeats
  double gap = 0;  // (sum of objectives - sum of lp-dual objectives) / sum of lp-dual objectives
};

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

bool is_exact(const std::string& solver) { return solver == "lp" || solver == "lp-dual"; }

struct SolverVariant {
  std::string label;
  L1Options l1;
};

// One variant per solver, and one per gamma for huber.
std::vector<SolverVariant> solver_variants(const BenchFactorOptions& options) {
  std::vector<SolverVariant> variants;
  for (const std::string& solver : options.solvers) {
    L1Options l1;
    l1.method = parse_l1_method(solver);
    if (l1.method != L1Method::huber) {
      variants.push_back({solver, l1});
      continue;
    }
    for (double gamma : options.gammas) {
      l1.huber_gamma = gamma;
      char label[64];
      std::snprintf(label, sizeof label, "huber gamma=%g", gamma);
      variants.push_back({label, l1});
    }
  }
  return variants;
}

std::vector<FactorRecord> bench_factorization(const BenchFactorOptions& options,
                                              const BenchCase& bench_case,
                                              ProgressReporter& progress) {
  const PlantedMatrix planted = make_planted_matrix(bench_case.size, bench_case.size, options.terms,
                                                    bench_case.density, options.seed);
  const double threshold = options.support_threshold * planted.R.cwiseAbs().maxCoeff();
  std::vector<FactorRecord> records;
  for (const SolverVariant& variant : solver_variants(options)) {
    FactorizationOptions factorization;
    factorization.l1 = variant.l1;
    factorization.threads = options.threads;
    factorization.seed = options.seed;
    FactorRecord record{bench_case, variant.label};
    std::vector<double> times;
    for (int repeat = 0; repeat < options.repeats; ++repeat) {
      const auto start = std::chrono::steady_clock::now();
      const L1Factorization result = factorize_l1(planted.R, options.terms, factorization);
      times.push_back(seconds_since(start));
      record.iterations = static_cast<int>(result.objective_per_iteration.size());
      record.objective = result.E.lpNorm<1>();
      record.support = compare_support(result.E, planted.E, threshold);
      progress.advance();
    }
    record.seconds = median(times);
    records.push_back(record);
  }
  double best_exact = std::numeric_limits<double>::infinity();
  for (const auto& record : records)
    if (is_exact(record.solver)) best_exact = std::min(best_exact, record.objective);
  for (auto& record : records)
    record.gap = std::isinf(best_exact) ? NAN : (record.objective - best_exact) / best_exact;
  return records;
}

// Single regressions: the W-step of the planted matrix with its true basis (m = size
// observations, t unknowns, one problem per row), solved on one thread.
std::vector<RegressionRecord> bench_regressions(const BenchFactorOptions& options, int size,
                                                ProgressReporter& progress) {
  const PlantedMatrix planted =
      make_planted_matrix(size, size, options.terms, options.density, options.seed);
  const Eigen::MatrixXd design = planted.F.transpose();
  const Eigen::MatrixXd rhs = planted.R.transpose();
  L1Options exact;
  exact.method = L1Method::lp_dual;
  Eigen::VectorXd optimum(rhs.cols());
  {
    LadSolver solver(design, exact);
    for (Eigen::Index k = 0; k < rhs.cols(); ++k) solver.solve(rhs.col(k), &optimum[k]);
  }
  std::vector<RegressionRecord> records;
  for (const SolverVariant& variant : solver_variants(options)) {
    RegressionRecord record{size, variant.label};
    std::vector<double> times;
    for (int repeat = 0; repeat < options.repeats; ++repeat) {
      double objective_sum = 0;
      const auto start = std::chrono::steady_clock::now();
      LadSolver solver(design, variant.l1);
      for (Eigen::Index k = 0; k < rhs.cols(); ++k) {
        double objective = 0;
        solver.solve(rhs.col(k), &objective);
        objective_sum += objective;
      }
      times.push_back(seconds_since(start) * 1e6 / double(rhs.cols()));
      record.gap = (objective_sum - optimum.sum()) / optimum.sum();
      progress.advance();
    }
    record.microseconds_per_solve = median(times);
    records.push_back(record);
  }
  return records;
}

std::string format(const char* pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

void print_factor_table(const std::vector<FactorRecord>& records) {
  std::printf(
      "| size | density | solver | time (s) | iterations | L1 objective | gap to exact | "
      "precision | recall |\n|---|---|---|---|---|---|---|---|---|\n");
  for (const auto& r : records)
    std::printf("| %d | %.0f%% | %s | %.3f | %d | %.6g | %s | %.4f | %.4f |\n", r.bench_case.size,
                100 * r.bench_case.density, r.solver.c_str(), r.seconds, r.iterations, r.objective,
                format("%.2e", r.gap).c_str(), r.support.precision, r.support.recall);
}

void print_regression_table(const std::vector<RegressionRecord>& records, int terms) {
  std::printf(
      "| observations | unknowns | solver | time per solve (us) | gap to exact |\n"
      "|---|---|---|---|---|\n");
  for (const auto& r : records)
    std::printf("| %d | %d | %s | %.1f | %.2e |\n", r.observations, terms, r.solver.c_str(),
                r.microseconds_per_solve, r.gap);
}

nlohmann::ordered_json to_json(const FactorRecord& r) {
  return {{"size", r.bench_case.size},
          {"density", r.bench_case.density},
          {"solver", r.solver},
          {"seconds_median", r.seconds},
          {"iterations", r.iterations},
          {"l1_objective", r.objective},
          {"gap_to_exact",
           std::isnan(r.gap) ? nlohmann::ordered_json() : nlohmann::ordered_json(r.gap)},
          {"support_precision", r.support.precision},
          {"support_recall", r.support.recall}};
}

void run_bench_factor(const BenchFactorOptions& options) {
  if (options.repeats < 1) throw Error("--repeats must be >= 1");
  const std::size_t variants = solver_variants(options).size();
  std::vector<BenchCase> by_size, by_density;
  for (int size : options.sizes) by_size.push_back({size, options.density});
  for (double density : options.densities) by_density.push_back({options.size, density});
  const std::uint64_t units = (by_size.size() + by_density.size() + options.sizes.size()) *
                              variants * std::uint64_t(options.repeats);
  ProgressReporter progress("bench-factor", units);
  std::vector<FactorRecord> size_records, density_records;
  std::vector<RegressionRecord> regression_records;
  for (const auto& c : by_size)
    for (auto& r : bench_factorization(options, c, progress)) size_records.push_back(r);
  for (const auto& c : by_density)
    for (auto& r : bench_factorization(options, c, progress)) density_records.push_back(r);
  for (int size : options.sizes)
    for (auto& r : bench_regressions(options, size, progress)) regression_records.push_back(r);
  progress.finish();

  std::printf("\nFactorization, square matrices at %.0f%% density, t = %d:\n\n",
              100 * options.density, options.terms);
  print_factor_table(size_records);
  std::printf("\nFactorization, %d x %d, t = %d, growing density:\n\n", options.size, options.size,
              options.terms);
  print_factor_table(density_records);
  std::printf(
      "\nSingle L1 regressions (W-step with the true basis, one thread), %.0f%% density:\n\n",
      100 * options.density);
  print_regression_table(regression_records, options.terms);

  if (!options.json.empty()) {
    nlohmann::ordered_json json;
    json["terms"] = options.terms;
    json["huber_gammas"] = options.gammas;
    json["repeats"] = options.repeats;
    json["seed"] = options.seed;
    json["support_threshold_relative"] = options.support_threshold;
    for (const auto& r : size_records) json["by_size"].push_back(to_json(r));
    for (const auto& r : density_records) json["by_density"].push_back(to_json(r));
    for (const auto& r : regression_records)
      json["regressions"].push_back({{"observations", r.observations},
                                     {"unknowns", options.terms},
                                     {"solver", r.solver},
                                     {"microseconds_per_solve_median", r.microseconds_per_solve},
                                     {"gap_to_exact", r.gap}});
    write_json_report(options.json, json);
  }
}

const CommandRegistration registration{
    95, [](CLI::App& app) {
      auto options = std::make_shared<BenchFactorOptions>();
      auto* command = app.add_subcommand(
          "bench-factor",
          "Compare the L1 solvers (exact LP, its dual, Huber QP, IRLS) on planted low-rank + "
          "sparse "
          "matrices: time, gap to the exact objective, support recovery (Markdown tables)");
      command->add_option("--sizes", options->sizes,
                          "Square sizes for the growing-size table (default 50 100 200 400)");
      command->add_option("--density", options->density,
                          "Fraction of non-zeros in E for the growing-size table (default 0.10)");
      command->add_option(
          "--densities", options->densities,
          "Densities for the growing-density table (default 0.01 0.05 0.10 0.20 0.30)");
      command->add_option("--size", options->size,
                          "Square size for the growing-density table (default 200)");
      command->add_option("-t,--terms", options->terms, "Rank of W F and basis terms (default 4)")
          ->check(CLI::PositiveNumber);
      command->add_option("--solvers", options->solvers,
                          "Solvers to compare (default lp lp-dual huber irls)");
      command->add_option(
          "--gammas", options->gammas,
          "Huber thresholds (relative); huber runs once per value (default 1e-3 1e-5)");
      command->add_option("--repeats", options->repeats,
                          "Runs per measurement; the median time is reported (default 3)");
      command->add_option("--threads", options->threads,
                          "Worker threads for the factorizations (default: all cores)");
      command->add_option("--seed", options->seed,
                          "Seed of the planted matrices and starts (default 1)");
      command->add_option("--support-threshold", options->support_threshold,
                          "An entry of E counts as non-zero when |E| > this times max |R| "
                          "(default 1e-6)");
      command->add_option("--json", options->json, "Also write every record to this JSON file");
      command->callback([options] { run_bench_factor(*options); });
    }};

}  // namespace
}  // namespace relume
