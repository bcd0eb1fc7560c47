// Implementation of one cluster per pixel (see pixel_clusters.hpp).
#include "compress/pixel_clusters.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace relume {
namespace {

// A pixel's rows [first, first + count), the distinct clusters they are in, ascending, and where
// its rows' kept fits start in share_pixel_clusters' arrays.
struct SplitPixel {
  std::size_t first = 0, count = 0, kept = 0;
  std::vector<std::int32_t> clusters;
};

// The pixels whose rows `cluster` puts in more than one cluster.
std::vector<SplitPixel> split_pixels(const WorkingRows& rows,
                                     const std::vector<std::int32_t>& cluster) {
  std::vector<SplitPixel> split;
  const std::size_t count = rows.pixel.size();
  std::size_t kept = 0;
  for (std::size_t first = 0, end = 0; first < count; first = end) {
    bool one_cluster = true;
    for (end = first + 1; end < count && rows.pixel[end] == rows.pixel[first]; ++end)
      one_cluster = one_cluster && cluster[end] == cluster[first];
    if (one_cluster) continue;
    SplitPixel pixel{
        first,
        end - first,
        kept,
        {cluster.begin() + std::ptrdiff_t(first), cluster.begin() + std::ptrdiff_t(end)}};
    std::sort(pixel.clusters.begin(), pixel.clusters.end());
    pixel.clusters.erase(std::unique(pixel.clusters.begin(), pixel.clusters.end()),
                         pixel.clusters.end());
    kept += pixel.count;
    split.push_back(std::move(pixel));
  }
  return split;
}

}  // namespace

PixelClusterChange share_pixel_clusters(const WorkingRows& rows, AssignmentResult& assigned,
                                        const CandidateFits& fit) {
  PixelClusterChange change;
  if (rows.pixel.empty()) return change;
  const std::vector<SplitPixel> split = split_pixels(rows, assigned.best);
  change.split_pixels = split.size();
  if (split.empty()) return change;
  std::size_t passes = 0;
  for (const SplitPixel& pixel : split) passes = std::max(passes, pixel.clusters.size());

  // The chosen slot of every split pixel, its cost so far (summed L1 residual x norm), and its
  // rows' fits to that slot's cluster (from the pixel's `kept` on).
  std::vector<std::size_t> chosen(split.size(), 0);
  std::vector<double> cost(split.size(), HUGE_VAL);
  const std::size_t kept_rows = split.back().kept + split.back().count;
  std::vector<float> objective(kept_rows);
  RowMatrixF weights(Eigen::Index(kept_rows), assigned.weights.cols());
  // Pass s fits every split pixel's rows to its s-th cluster; a pass keeps the fits of the pixels
  // whose cost it lowers.
  for (std::size_t s = 0; s < passes; ++s) {
    CandidateLists lists;
    lists.width = 1;
    lists.clusters.assign(rows.rows(), -1);
    for (const SplitPixel& pixel : split)
      if (s < pixel.clusters.size())
        std::fill_n(lists.clusters.begin() + std::ptrdiff_t(pixel.first), pixel.count,
                    pixel.clusters[s]);
    const AssignmentResult result = fit(lists);
    for (std::size_t g = 0; g < split.size(); ++g) {
      const SplitPixel& pixel = split[g];
      if (s >= pixel.clusters.size()) continue;
      double sum = 0;
      for (std::size_t r = pixel.first; r < pixel.first + pixel.count; ++r)
        sum += double(result.objective[r]) * rows.norms[r];
      if (sum >= cost[g]) continue;
      cost[g] = sum;
      chosen[g] = s;
      for (std::size_t i = 0; i < pixel.count; ++i) {
        objective[pixel.kept + i] = result.objective[pixel.first + i];
        weights.row(Eigen::Index(pixel.kept + i)) =
            result.weights.row(Eigen::Index(pixel.first + i));
      }
    }
  }
  for (std::size_t g = 0; g < split.size(); ++g) {
    const SplitPixel& pixel = split[g];
    const std::int32_t cluster = pixel.clusters[chosen[g]];
    for (std::size_t i = 0; i < pixel.count; ++i) {
      const std::size_t r = pixel.first + i;
      change.rows_moved += assigned.best[r] != cluster;
      assigned.best[r] = cluster;
      assigned.objective[r] = objective[pixel.kept + i];
      assigned.weights.row(Eigen::Index(r)) = weights.row(Eigen::Index(pixel.kept + i));
    }
  }
  return change;
}

}  // namespace relume
