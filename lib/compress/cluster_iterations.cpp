// Implementation of the clustered L1 alternation (see cluster_iterations.hpp). Interruptible
// between its steps (lib/core/interruption.hpp).
#include "compress/cluster_iterations.hpp"

#include <algorithm>
#include <chrono>

#include "compress/cluster_basis.hpp"
#include "compress/cluster_seeding.hpp"
#include "compress/pixel_clusters.hpp"
#include "core/console.hpp"
#include "core/elapsed_time.hpp"
#include "core/interruption.hpp"
#include "core/parallel.hpp"
#include "core/progress.hpp"

namespace relume {
namespace {

AssignmentResult run_assignment(const WorkingRows& rows, const ClusterModel& model,
                                const CandidateLists& candidates, const ClusteringOptions& options,
                                const std::string& title) {
  if (options.assign) return options.assign(rows, model, candidates);
  ProgressReporter progress(title, rows.rows(), options.quiet);
  AssignmentResult result = assign_to_best_cluster(rows, model, candidates, options.weight_fit,
                                                   options.threads, &progress);
  progress.finish();
  return result;
}

// Reassigns every row among its candidates (its current cluster always among them) and records
// the step; returns how many rows changed cluster.
std::size_t reassign(const WorkingRows& rows, ClusterModel& model, const ClusteringOptions& options,
                     ClusteringTrace& trace, IterationRecord& record) {
  auto start = Clock::now();
  CandidateOptions candidate_options;
  candidate_options.count = options.candidates;
  const bool assigned = !model.assignment.empty();
  if (assigned) candidate_options.always_include = &model.assignment;
  const CandidateLists candidates =
      nearest_subspace_candidates(rows, model, candidate_options, options.threads);
  // Seeded without an assignment: it is the nearest subspace, each list's first (the seeding's
  // last least-squares assignment, made here instead of in a pass of its own).
  if (!assigned)
    for (std::size_t r = 0; r < rows.rows(); ++r) model.assignment.push_back(candidates.row(r)[0]);
  trace.candidate_seconds += seconds_since(start);

  start = Clock::now();
  AssignmentResult result =
      run_assignment(rows, model, candidates, options,
                     "compress: iteration " + std::to_string(record.iteration) + ", assigning");
  if (options.shared_pixel_clusters)
    record.split_pixels =
        share_pixel_clusters(rows, result, [&](const CandidateLists& lists) {
          return run_assignment(rows, model, lists, options,
                                "compress: iteration " + std::to_string(record.iteration) +
                                    ", one cluster per pixel");
        }).split_pixels;
  trace.assignment_seconds += seconds_since(start);
  std::size_t changed = 0;
  for (std::size_t r = 0; r < rows.rows(); ++r) changed += result.best[r] != model.assignment[r];
  model.assignment = std::move(result.best);
  model.weights = std::move(result.weights);
  record.objective = result.total_objective();

  start = Clock::now();
  record.size_rules = enforce_cluster_sizes(rows, model, options.sizes, options.candidates,
                                            options.weight_fit, options.threads);
  trace.size_rule_seconds += seconds_since(start);
  record.clusters = model.clusters;
  return changed;
}

void fit_bases(const WorkingRows& rows, ClusterModel& model, const ClusteringOptions& options,
               ClusteringTrace& trace) {
  const auto start = Clock::now();
  const auto members = model.members();
  parallel_for(std::size_t(model.clusters), options.threads, [&](std::size_t k, unsigned) {
    fit_cluster_basis_l1(rows, members[k], model.weights, options.basis_fit, model.terms,
                         model.basis(static_cast<int>(k)));
  });
  trace.basis_seconds += seconds_since(start);
}

// Exact refit: every cluster's F by LP over its rows (W fixed), then every row's W by LP.
void refit_exactly(const WorkingRows& rows, ClusterModel& model, const ClusteringOptions& options,
                   ClusteringTrace& trace) {
  const auto start = Clock::now();
  L1Options l1;
  l1.method = *options.exact_refit;
  const int terms = model.terms, lights = model.lights;
  const auto members = model.members();
  double before = 0, after = 0;
  ProgressReporter progress("compress: exact refit", rows.rows(), options.quiet);
  for (int k = 0; k < model.clusters; ++k) {
    const auto& list = members[static_cast<std::size_t>(k)];
    if (list.empty()) continue;
    Eigen::MatrixXd weights(static_cast<Eigen::Index>(list.size()), terms);
    Eigen::MatrixXd values(static_cast<Eigen::Index>(list.size()), lights);
    for (std::size_t p = 0; p < list.size(); ++p) {
      weights.row(static_cast<Eigen::Index>(p)) = model.weights.row(list[p]).cast<double>();
      values.row(static_cast<Eigen::Index>(p)) = rows.values.row(list[p]).cast<double>();
    }
    const Eigen::Map<RowMatrixF> basis(model.basis(k), terms, lights);
    before += (values - weights * basis.cast<double>()).cwiseAbs().sum();
    const Eigen::MatrixXd fitted = solve_lad_columns(weights, values, l1, options.threads);
    const Eigen::MatrixXd design = fitted.transpose();  // lights x terms
    std::vector<double> objective(list.size());
    RowMatrixF new_weights(static_cast<Eigen::Index>(list.size()), terms);
    // GLPK problems must be created, used and freed on one thread: each worker owns its solver
    // for the whole loop and takes every workers-th row.
    const std::size_t workers =
        std::min<std::size_t>(resolve_thread_count(options.threads), list.size());
    parallel_for(workers, unsigned(workers), [&](std::size_t worker, unsigned) {
      LadSolver solver(design, l1);
      for (std::size_t p = worker; p < list.size(); p += workers) {
        const Eigen::VectorXd x = values.row(static_cast<Eigen::Index>(p)).transpose();
        new_weights.row(static_cast<Eigen::Index>(p)) =
            solver.solve(x, &objective[p]).transpose().cast<float>();
      }
    });
    for (const double value : objective) after += value;
    Eigen::Map<RowMatrixF>(model.basis(k), terms, lights) = fitted.cast<float>();
    for (std::size_t p = 0; p < list.size(); ++p)
      model.weights.row(list[p]) = new_weights.row(static_cast<Eigen::Index>(p));
    progress.advance(list.size());
  }
  progress.finish();
  trace.exact_refit_objective_before = before;
  trace.exact_refit_objective_after = after;
  trace.exact_refit_seconds += seconds_since(start);
}

}  // namespace

void iterate_clusters(const WorkingRows& rows, ClusterModel& model,
                      const ClusteringOptions& options, int iterations, ClusteringTrace& trace,
                      const IterationHook& hook) {
  const bool fit_weights_first = model.weights.rows() != static_cast<Eigen::Index>(rows.rows());
  // Iterations done, for a progress listener only (quiet: a second bar would garble the
  // assignment's on a terminal); its advance() is where an interruption ends the iterations.
  ProgressReporter progress("compress: iterations", std::uint64_t(iterations + fit_weights_first),
                            true);
  const auto finish_iteration = [&](IterationRecord& record, std::size_t changed,
                                    Clock::time_point start) {
    record.changed = changed;
    record.seconds = seconds_since(start);
    trace.iterations.push_back(record);
    if (hook) hook(model, record);
    progress.advance();
  };
  int next = trace.iterations.empty() ? 0 : trace.iterations.back().iteration + 1;
  if (fit_weights_first) {
    const auto start = Clock::now();
    IterationRecord record;
    record.iteration = next++;
    const std::size_t changed = reassign(rows, model, options, trace, record);
    finish_iteration(record, changed, start);
  }
  trace.settled = false;
  for (int done = 0; done < iterations; ++done) {
    const auto start = Clock::now();
    IterationRecord record;
    record.iteration = next++;
    fit_bases(rows, model, options, trace);
    throw_if_interrupted();
    const std::size_t changed = reassign(rows, model, options, trace, record);
    finish_iteration(record, changed, start);
    if (double(changed) <= options.settle_fraction * double(rows.rows())) {
      trace.settled = true;
      break;
    }
  }
  progress.finish();
  if (options.exact_refit) refit_exactly(rows, model, options, trace);
}

ClusterModel seed_clusters_for(const WorkingRows& rows, const ClusteringOptions& options,
                               ClusteringTrace& trace, bool assign) {
  const auto start = Clock::now();
  // More clusters than the rows can fill at the size rules' minimum: the surplus is seeded (one
  // by one, a long wait at 100,000) only for the rules to merge it away.
  const std::size_t minimum = std::size_t(std::max(1, options.sizes.minimum_for(options.terms)));
  if (!options.quiet && std::size_t(options.clusters) > rows.rows() / minimum)
    note(
        "compress: %d clusters are more than %zu functions can fill (clusters with fewer than %zu "
        "functions are merged into others): at most %zu will remain; ask for fewer clusters",
        options.clusters, rows.rows(), minimum, rows.rows() / minimum);
  SeedingOptions seeding;
  seeding.clusters = options.clusters;
  seeding.terms = options.terms;
  seeding.sample_rows = options.seed_sample_rows;
  seeding.l2_rounds = options.l2_rounds;
  seeding.seed = options.seed;
  seeding.threads = options.threads;
  seeding.assign_after_rounds = assign;
  seeding.quiet = options.quiet;
  ClusterModel model = seed_clusters(rows, seeding);
  trace.seeding_seconds += seconds_since(start);
  return model;
}

ClusterModel cluster_rows(const WorkingRows& rows, const ClusteringOptions& options,
                          ClusteringTrace& trace, const IterationHook& hook) {
  ClusterModel model = seed_clusters_for(rows, options, trace, false);
  iterate_clusters(rows, model, options, options.max_iterations, trace, hook);
  return model;
}

}  // namespace relume
