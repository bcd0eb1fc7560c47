// Implementation of multi-resolution clustering (see multires_clustering.hpp).
#include "compress/multires_clustering.hpp"

#include <algorithm>
#include <chrono>
#include <relume/error.hpp>

#include "core/elapsed_time.hpp"
#include "core/progress.hpp"
#include "field/downsample.hpp"

namespace relume {
namespace {

// For every full-resolution row, the distinct clusters of the low-resolution functions in the
// 3x3 pixel neighbourhood of its position (empty when none is stored there).
CandidateLists neighbourhood_pools(const ReflectanceField& field, const PreparedRows& full,
                                   const ReflectanceField& low, const PreparedRows& low_rows,
                                   const ClusterModel& low_model, int levels) {
  std::vector<std::int32_t> cluster_of(static_cast<std::size_t>(low.functions()), -1);
  for (std::size_t r = 0; r < low_rows.functions.size(); ++r)
    cluster_of[low_rows.functions[r]] = low_model.assignment[r];
  const int channels = field.channels;
  CandidateLists pools;
  pools.width = 9 * channels;
  pools.clusters.assign(full.functions.size() * pools.width, -1);
  for (std::size_t r = 0; r < full.functions.size(); ++r) {
    const std::int64_t pixel = full.functions[r] / channels;
    const int x = std::min(int(pixel % field.width) >> levels, low.width - 1);
    const int y = std::min(int(pixel / field.width) >> levels, low.height - 1);
    std::int32_t* pool = pools.clusters.data() + r * pools.width;
    int size = 0;
    for (int dy = -1; dy <= 1; ++dy) {
      for (int dx = -1; dx <= 1; ++dx) {
        const int nx = x + dx, ny = y + dy;
        if (nx < 0 || ny < 0 || nx >= low.width || ny >= low.height) continue;
        for (int c = 0; c < channels; ++c) {
          const std::int32_t k = cluster_of[low.function_index(nx, ny, c)];
          if (k >= 0 && std::find(pool, pool + size, k) == pool + size) pool[size++] = k;
        }
      }
    }
  }
  return pools;
}

}  // namespace

ClusterModel multires_start(const ReflectanceField& field, const PreparedRows& full, int levels,
                            bool haar_transform, const NoiseModel& noise,
                            const ClusteringOptions& options, MultiresTrace& trace) {
  trace.levels = levels;
  auto start = Clock::now();
  const ReflectanceField low = downsample_field(field, levels);
  const PreparedRows low_rows =
      prepare_rows(low, haar_transform, noise, options.threads, full.light_scale);
  trace.downsample_seconds = seconds_since(start);
  trace.low_width = low.width;
  trace.low_height = low.height;
  trace.low_rows = low_rows.rows.rows();
  if (low_rows.rows.rows() == 0)
    throw Error("multi-resolution clustering: the field downsampled " + std::to_string(levels) +
                " times (" + std::to_string(low.width) + "x" + std::to_string(low.height) +
                ") has no function to cluster; use fewer levels");

  ClusterModel model = cluster_rows(low_rows.rows, options, trace.low);

  start = Clock::now();
  const CandidateLists pools = neighbourhood_pools(field, full, low, low_rows, model, levels);
  std::size_t offered = 0;
  for (const std::int32_t k : pools.clusters) offered += k >= 0;
  trace.mean_pool_size = full.functions.empty() ? 0 : double(offered) / full.functions.size();
  CandidateOptions candidate_options;
  candidate_options.count = options.candidates;
  candidate_options.pool = &pools;
  const CandidateLists candidates =
      nearest_subspace_candidates(full.rows, model, candidate_options, options.threads);
  AssignmentResult result;
  if (options.assign) {
    result = options.assign(full.rows, model, candidates);
  } else {
    ProgressReporter progress("compress: full-resolution assignment", full.rows.rows(),
                              options.quiet);
    result = assign_to_best_cluster(full.rows, model, candidates, options.weight_fit,
                                    options.threads, &progress);
    progress.finish();
  }
  model.assignment = std::move(result.best);
  model.weights = std::move(result.weights);
  enforce_cluster_sizes(full.rows, model, options.sizes, options.candidates, options.weight_fit,
                        options.threads);
  trace.assignment_seconds = seconds_since(start);
  return model;
}

}  // namespace relume
