// Implementation of the eval's compressions and per-row measures (see grid_runs.hpp).
#include "eval/grid_runs.hpp"

#include <algorithm>
#include <cmath>
#include <functional>

#include "core/elapsed_time.hpp"
#include "core/interruption.hpp"
#include "core/parallel.hpp"
#include "core/progress.hpp"

namespace relume {
namespace {

// |x - w F| of stored row r (unit norm), into `out` (lights values).
void absolute_residual(const WorkingRows& rows, const ClusterModel& model, std::size_t r,
                       std::vector<double>& out) {
  const int lights = model.lights, terms = model.terms;
  const float* x = rows.row(r);
  const float* basis = model.basis(model.assignment[r]);
  out.resize(lights);
  for (int i = 0; i < lights; ++i) {
    double value = x[i];
    for (int j = 0; j < terms; ++j)
      value -= double(model.weights(static_cast<Eigen::Index>(r), j)) *
               basis[std::size_t(j) * lights + i];
    out[i] = std::fabs(value);
  }
}

}  // namespace

bool has_method(const std::vector<std::string>& methods, const std::string& method) {
  return std::find(methods.begin(), methods.end(), method) != methods.end();
}

std::vector<EvalRun> run_grid(const WorkingRows& rows, const EvalGrid& grid,
                              const std::function<void(const EvalRun&)>& report) {
  std::vector<EvalRun> runs;
  ProgressReporter progress("eval: compressing", grid.clusters.size() * grid.terms.size(),
                            grid.clustering.quiet);
  const auto finish = [&](EvalRun run) {
    runs.push_back(std::move(run));
    if (report) report(runs.back());
    throw_if_interrupted();
  };
  for (const int clusters : grid.clusters) {
    for (const int terms : grid.terms) {
      ClusteringOptions clustering = grid.clustering;
      clustering.clusters = clusters;
      clustering.terms = terms;
      EvalRun base;
      base.clusters_asked = clusters;
      base.terms = terms;
      std::size_t l1 = runs.size();
      if (has_method(grid.methods, "l1") || has_method(grid.methods, "l1-refit")) {
        const auto start = Clock::now();
        ClusteringTrace trace;
        EvalRun run = base;
        run.method = "l1";
        run.model = cluster_rows(rows, clustering, trace);
        run.seconds = seconds_since(start);
        run.iterations = static_cast<int>(trace.iterations.size());
        l1 = runs.size();
        finish(std::move(run));
      }
      for (const PcaCentering centering : {PcaCentering::none, PcaCentering::mean}) {
        const std::string name = centering == PcaCentering::none ? "cpca" : "cpca-mean";
        if (!has_method(grid.methods, name)) continue;
        const auto start = Clock::now();
        ClusteringTrace trace;
        ClusteredPcaOptions pca = grid.pca;
        pca.centering = centering;
        EvalRun run = base;
        run.method = name;
        run.model = cluster_rows_pca(rows, clustering, pca, trace);
        run.seconds = seconds_since(start);
        run.iterations = static_cast<int>(trace.iterations.size());
        finish(std::move(run));
      }
      const std::vector<int> budgets =
          has_method(grid.methods, "l1-refit") ? grid.refit_entries : std::vector<int>{};
      for (const int entries : budgets) {
        if (entries + terms >= rows.lights()) continue;
        const auto start = Clock::now();
        EvalRun run = base;
        run.method = "l1-refit";
        run.budget = entries;
        run.model = runs[l1].model;
        refit_trimmed_least_squares(rows, run.model,
                                    trimmed_refit_options(clustering, entries, grid.refit_rounds),
                                    run.refit);
        run.refit_seconds = seconds_since(start);
        run.seconds = runs[l1].seconds + run.refit_seconds;
        run.iterations = runs[l1].iterations;
        finish(std::move(run));
      }
      progress.advance();
    }
  }
  progress.finish();
  return runs;
}

Eigen::MatrixXd row_errors(const WorkingRows& rows, const ClusterModel& model,
                           const std::vector<int>& caps, unsigned threads) {
  Eigen::MatrixXd errors(static_cast<Eigen::Index>(rows.rows()),
                         static_cast<Eigen::Index>(caps.size()));
  const int lights = model.lights;
  const int largest =
      caps.empty() ? 0 : std::min(lights, *std::max_element(caps.begin(), caps.end()));
  std::vector<std::vector<double>> scratch(resolve_thread_count(threads));
  parallel_for(rows.rows(), threads, [&](std::size_t r, unsigned worker) {
    std::vector<double>& residual = scratch[worker];
    absolute_residual(rows, model, r, residual);
    std::partial_sort(residual.begin(), residual.begin() + largest, residual.end(),
                      std::greater<double>());
    // total - (squares of the largest c) for every cap c.
    double total = 0;
    for (const double value : residual) total += value * value;
    for (std::size_t c = 0; c < caps.size(); ++c) {
      double kept = 0;
      for (int e = 0; e < std::min(caps[c], lights); ++e) kept += residual[e] * residual[e];
      errors(static_cast<Eigen::Index>(r), static_cast<Eigen::Index>(c)) =
          std::max(0.0, total - kept);
    }
  });
  return errors;
}

std::vector<double> residual_sparseness(const WorkingRows& rows, const ClusterModel& model,
                                        const std::vector<double>& thresholds, unsigned threads) {
  const unsigned workers = resolve_thread_count(threads);
  std::vector<std::vector<double>> scratch(workers);
  std::vector<std::vector<std::size_t>> counts(workers,
                                               std::vector<std::size_t>(thresholds.size(), 0));
  parallel_for(rows.rows(), threads, [&](std::size_t r, unsigned worker) {
    absolute_residual(rows, model, r, scratch[worker]);
    for (const double value : scratch[worker])
      for (std::size_t t = 0; t < thresholds.size(); ++t)
        counts[worker][t] += value <= thresholds[t];
  });
  std::vector<double> fractions(thresholds.size(), 0.0);
  const double entries = double(rows.rows()) * model.lights;
  for (std::size_t t = 0; t < thresholds.size(); ++t) {
    std::size_t total = 0;
    for (const auto& worker : counts) total += worker[t];
    fractions[t] = entries > 0 ? double(total) / entries : 0.0;
  }
  return fractions;
}

}  // namespace relume
