// The start of clustered factorization. A random assignment (the paper's start) stalls in impure
// clusters, so clusters are seeded like k-means++ for subspaces (GUIDE section 2): on a random
// sample of rows, each new seed is drawn with probability proportional to its squared distance
// from the subspaces chosen so far, and its subspace is grown from the rows most similar to it
// (the 2t largest |cosines|, then the rows closest to their least-squares subspace). A few cheap
// least-squares rounds over all rows (assign to the nearest subspace, refit each subspace) follow.
#pragma once

#include <cstdint>

#include "compress/cluster_model.hpp"

namespace relume {

struct SeedingOptions {
  int clusters = 64;
  int terms = 4;
  int sample_rows = 20000;  // rows the seeds are chosen from
  int l2_rounds = 4;        // least-squares k-subspace rounds over all rows
  // After the last round, assign every row to its nearest subspace. Off for the L1 iterations:
  // their first candidate preselection projects every row on the same bases anyway and takes the
  // nearest as the assignment (cluster_iterations.cpp), so the pass would be done twice.
  bool assign_after_rounds = true;
  std::uint64_t seed = 1;
  unsigned threads = 0;
  bool quiet = false;  // no progress line while the seeds are chosen one by one
};

// Bases (orthonormal rows) and the least-squares assignment (empty without
// assign_after_rounds); weights are left empty. Reports its progress seed by seed, and stops
// (relume::Interrupted) within a seed or a row of an interruption. Fewer clusters than asked are returned only when
// there are fewer rows than clusters.
ClusterModel seed_clusters(const WorkingRows& rows, const SeedingOptions& options);

}  // namespace relume
