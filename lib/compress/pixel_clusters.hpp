// One cluster for all colour channels of a pixel (issue 33). Clustering each channel on its own
// puts a pixel's red, green and blue into unrelated clusters wherever their fits are close; each
// channel's error then comes from a different basis, and a relit pixel turns red, green or
// magenta. After each reassignment, every pixel whose channels landed in different clusters has
// each of its channels fitted to each of those clusters, and all of them move to the cluster with
// the smallest summed L1 residual in the rows' units (the unit-norm objective times the norm, so a
// bright channel counts as much as it shows). In one cluster, channels that are multiples of each
// other are fitted as the same multiples (an L1 fit is scale-equivariant): their error is grey.
#pragma once

#include <cstddef>
#include <functional>

#include "compress/cluster_assignment.hpp"
#include "compress/cluster_model.hpp"

namespace relume {

// Runs the fits of every row against its candidates (the CPU path or the OpenCL kernel).
using CandidateFits = std::function<AssignmentResult(const CandidateLists& candidates)>;

struct PixelClusterChange {
  std::size_t split_pixels = 0;  // pixels whose channels were in more than one cluster
  std::size_t rows_moved = 0;    // rows that changed cluster
};

// Moves the channels of every pixel that `assigned` splits (rows.pixel; nothing when it is empty)
// into one cluster, as above: their best cluster, weights and L1 objective become those of
// their fits to it (`fit` runs them against `assigned`'s rows and bases).
PixelClusterChange share_pixel_clusters(const WorkingRows& rows, AssignmentResult& assigned,
                                        const CandidateFits& fit);

}  // namespace relume
