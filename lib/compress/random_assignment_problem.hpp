// A seeded random reassignment problem (rows, cluster bases and candidate lists) of a chosen shape,
// for the assignment tests and for `relume bench`'s assign records. Same seed, same problem.
#pragma once

#include <cstdint>

#include "compress/cluster_assignment.hpp"
#include "compress/cluster_model.hpp"

namespace relume {

struct AssignmentProblemShape {
  int rows = 65536;
  int clusters = 128;
  int terms = 4;
  int lights = 253;
  int candidates = 3;  // slots per candidate list
  // Each list holds a random count in [1, candidates] of clusters (the rest -1) instead of all.
  bool lists_end_early = false;
  std::uint64_t seed = 1;
};

struct AssignmentProblem {
  WorkingRows rows;
  ClusterModel model;  // terms, lights, clusters and bases set
  CandidateLists candidates;

  std::size_t candidate_count() const;  // slots that name a cluster
};

// Bases normal(0, 1); every row lies near a random cluster's span (normal weights, noise sigma
// 0.05, three sparse outliers of sigma 2), scaled to unit norm: realistic L1 problems. Candidate
// clusters are uniformly random (repeats possible). Throws Error for non-positive sizes.
AssignmentProblem random_assignment_problem(const AssignmentProblemShape& shape);

}  // namespace relume
