// Assignment of reflectance functions to clusters (paper Eq. 14): every function goes to the
// cluster whose basis fits it with the smallest L1 residual, its weights solved with that
// cluster's F fixed. The exact fits are restricted to a few candidate clusters per function,
// preselected by the cheap least-squares projection error onto each cluster's span. This is the
// CPU path; lib/compress/opencl_assignment.hpp runs the same fits as an OpenCL kernel.
#pragma once

#include <cstdint>
#include <vector>

#include "compress/cluster_function_fit.hpp"
#include "compress/cluster_model.hpp"

namespace relume {

class ProgressReporter;

// Candidate clusters of each row: `width` slots per row, unused slots hold -1.
struct CandidateLists {
  int width = 0;
  std::vector<std::int32_t> clusters;  // rows x width

  std::size_t rows() const { return width == 0 ? 0 : clusters.size() / width; }
  const std::int32_t* row(std::size_t r) const { return clusters.data() + r * width; }
};

struct CandidateOptions {
  int count = 4;  // candidates kept per row
  // Optional per-row cluster that is always kept (the current assignment), or -1.
  const std::vector<std::int32_t>* always_include = nullptr;
  // Optional: only clusters k with allowed[k] != 0 are considered.
  const std::vector<std::uint8_t>* allowed = nullptr;
  // Optional: per row, only these clusters are considered (for example those used near the row's
  // position at a lower resolution); when a row's pool is empty every cluster is considered.
  const CandidateLists* pool = nullptr;
};

// For every row, the `count` clusters with the smallest least-squares projection error
// ||x||^2 - ||Q_k^T x||^2 (Q_k an orthonormal basis of F^k's span), best first.
CandidateLists nearest_subspace_candidates(const WorkingRows& rows, const ClusterModel& model,
                                           const CandidateOptions& options, unsigned threads);

// The most nearest_subspace_candidates holds besides its lists: every basis orthonormalized, and
// per thread a block of rows projected on them (a few MB at most) and a score per cluster.
std::uint64_t candidate_search_bytes(int clusters, int terms, int lights, unsigned threads);

struct AssignmentResult {
  std::vector<std::int32_t> best;    // cluster with the smallest L1 residual
  std::vector<std::int32_t> second;  // the runner-up among the candidates, or -1
  std::vector<float> objective;      // the best cluster's L1 residual
  RowMatrixF weights;                // rows x terms, for the best cluster

  double total_objective() const;
};

// The CPU reference: the IRLS L1 fit of every row against each of its candidates.
AssignmentResult assign_to_best_cluster(const WorkingRows& rows, const ClusterModel& model,
                                        const CandidateLists& candidates,
                                        const IrlsSettings& settings, unsigned threads,
                                        ProgressReporter* progress = nullptr);

}  // namespace relume
