// Minimum and maximum cluster sizes (issue 4). A cluster with fewer rows than the minimum (an
// empty one included) is dissolved: each of its rows moves to its best surviving cluster, which is
// its second-best cluster whenever that survives. A cluster with more rows than the maximum is
// split into two equal halves along the direction its basis explains worst, so the cluster count
// grows. Cluster ids are renumbered densely afterwards.
#pragma once

#include <algorithm>
#include <cstddef>

#include "compress/cluster_function_fit.hpp"
#include "compress/cluster_model.hpp"

namespace relume {

struct ClusterSizeLimits {
  int minimum = -1;  // rows; clusters below it are merged away; -1 = max(8, 2 * terms)
  int maximum = 0;   // rows; 0 = no maximum; otherwise at least 2 * minimum

  int minimum_for(int terms) const { return minimum >= 0 ? minimum : std::max(8, 2 * terms); }
};

struct SizeRuleChanges {
  int merged = 0;  // clusters dissolved
  int split = 0;   // splits made (each adds one cluster)
  std::size_t rows_moved = 0;
};

// Throws Error when maximum is set and below 2 * minimum (halves would be merged again).
void validate_size_limits(const ClusterSizeLimits& limits, int terms);

// Applies both rules to `model` (assignment, weights, bases and cluster count). Moved rows get
// their weights refitted; split halves get the least-squares basis of their rows.
SizeRuleChanges enforce_cluster_sizes(const WorkingRows& rows, ClusterModel& model,
                                      const ClusterSizeLimits& limits, int candidates,
                                      const IrlsSettings& settings, unsigned threads);

}  // namespace relume
