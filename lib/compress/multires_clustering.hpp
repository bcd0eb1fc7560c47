// Multi-resolution clustering (issue 4): the field is downsampled `levels` times in camera space
// (lib/field/downsample.hpp), clustered there, and every full-resolution function is then assigned
// to the best cluster among those used by any function (any colour channel) of the 3x3
// low-resolution pixels around its position; full-resolution iterations may refine the result
// afterwards.
#pragma once

#include <relume/field.hpp>

#include "compress/cluster_iterations.hpp"
#include "compress/cluster_model.hpp"

namespace relume {

struct MultiresTrace {
  int levels = 0;
  int low_width = 0, low_height = 0;
  std::size_t low_rows = 0;
  double downsample_seconds = 0;
  ClusteringTrace low;            // the clustering at low resolution
  double assignment_seconds = 0;  // full-resolution neighbourhood assignment
  double mean_pool_size = 0;      // distinct clusters offered per full-resolution function
};

// The full-resolution model (bases, assignment, weights) for `full`, the prepared rows of
// `field`. `haar_transform` and `noise` must match how `full` was prepared; the low
// resolution is weighted by `full`'s light scale.
ClusterModel multires_start(const ReflectanceField& field, const PreparedRows& full, int levels,
                            bool haar_transform, const NoiseModel& noise,
                            const ClusteringOptions& options, MultiresTrace& trace);

}  // namespace relume
