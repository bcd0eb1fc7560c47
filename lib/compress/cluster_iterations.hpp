// The alternation of clustered L1 factorization (paper section 3.3): starting from seeded
// clusters, repeat (a) the F-step of every cluster with its rows' weights fixed and (b) the
// reassignment of every row to the candidate cluster whose basis fits it with the smallest L1
// residual (which also refits its weights), then the cluster size rules, until fewer than a
// fraction of the rows change cluster or an iteration cap is reached. An optional final pass
// refits every cluster exactly with an LP solver (lib/l1/regression.hpp).
#pragma once

#include <functional>
#include <optional>
#include <relume/compress.hpp>
#include <vector>

#include "compress/cluster_assignment.hpp"
#include "compress/cluster_function_fit.hpp"
#include "compress/cluster_model.hpp"
#include "compress/cluster_size_rules.hpp"
#include "l1/regression.hpp"

namespace relume {

// Runs the assignment of `rows` to the candidates: the CPU path or the OpenCL kernel.
using AssignFunction = std::function<AssignmentResult(
    const WorkingRows& rows, const ClusterModel& model, const CandidateLists& candidates)>;

struct ClusteringOptions {
  // The defaults of relume/compress.hpp's CompressOptions, the one place that holds them.
  int clusters = compress_defaults().clusters;
  int terms = compress_defaults().terms;
  int max_iterations = compress_defaults().iterations;  // L1 iterations (F-step + reassignment)
  double settle_fraction = 0.002;  // stop once fewer than this fraction of rows change cluster
  int candidates = compress_defaults().candidates;  // clusters given the exact L1 fit per row
  // After each reassignment, a pixel's rows (WorkingRows::pixel) go to one cluster
  // (compress/pixel_clusters.hpp).
  bool shared_pixel_clusters = compress_defaults().channel_clusters == "shared";
  IrlsSettings weight_fit;  // the W fits (assignment)
  IrlsSettings basis_fit;   // the F-step
  ClusterSizeLimits sizes;
  int l2_rounds = 4;
  int seed_sample_rows = 20000;
  std::uint64_t seed = compress_defaults().seed;
  unsigned threads = 0;
  // Refit every cluster's F and its rows' W with this exact solver after the iterations
  // (nullopt: keep the IRLS result).
  std::optional<L1Method> exact_refit;
  AssignFunction assign;  // empty: the CPU path
  bool quiet = false;     // no progress output
};

struct IterationRecord {
  int iteration = 0;             // 0 = the first assignment after seeding
  double objective = 0;          // sum over rows of the L1 residual (unit-norm rows)
  std::size_t changed = 0;       // rows that changed cluster
  std::size_t split_pixels = 0;  // pixels whose channels the reassignment put in several clusters
  int clusters = 0;              // after the size rules
  SizeRuleChanges size_rules;
  double seconds = 0;
};

struct ClusteringTrace {
  double seeding_seconds = 0;
  double basis_seconds = 0;       // F-steps
  double candidate_seconds = 0;   // L2 preselection
  double assignment_seconds = 0;  // L1 fits of the reassignment
  double size_rule_seconds = 0;
  double exact_refit_seconds = 0;
  std::optional<double> exact_refit_objective_before, exact_refit_objective_after;
  std::vector<IterationRecord> iterations;
  bool settled = false;
};

// Called after every iteration with the model (bases, assignment, weights all consistent).
using IterationHook = std::function<void(const ClusterModel& model, const IterationRecord&)>;

// Seeds clusters with the seeding settings of `options` (lib/compress/cluster_seeding.hpp),
// adding the time to trace.seeding_seconds. Without `assign`, the model's assignment is left
// empty for iterate_clusters' first preselection to make.
ClusterModel seed_clusters_for(const WorkingRows& rows, const ClusteringOptions& options,
                               ClusteringTrace& trace, bool assign = true);

// Seeds clusters (seed_clusters_for) and runs the iterations.
ClusterModel cluster_rows(const WorkingRows& rows, const ClusteringOptions& options,
                          ClusteringTrace& trace, const IterationHook& hook = {});

// Runs up to `iterations` iterations from `model` (bases set; weights are fitted first when they
// do not cover every row, and an empty assignment starts as every row's nearest subspace). Then
// the exact refit, if asked for.
void iterate_clusters(const WorkingRows& rows, ClusterModel& model,
                      const ClusteringOptions& options, int iterations, ClusteringTrace& trace,
                      const IterationHook& hook = {});

}  // namespace relume
