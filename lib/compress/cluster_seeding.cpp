// Implementation of k-means++-like subspace seeding and the least-squares rounds
// (see cluster_seeding.hpp).
#include "compress/cluster_seeding.hpp"

#include <algorithm>
#include <numeric>
#include <random>

#include "compress/cluster_assignment.hpp"
#include "compress/cluster_basis.hpp"
#include "core/interruption.hpp"
#include "core/parallel.hpp"
#include "core/progress.hpp"

namespace relume {
namespace {

// Rows of the sample projected on `directions` (rows of unit length), a block of rows per task:
// the block stays in cache while it is multiplied. One product of the whole sample made Eigen
// copy (pack) all of it first and ran on one thread: at 1024 lights about 1 GFLOP/s and most of
// the seeding's time.
Eigen::MatrixXf project_sample(const RowMatrixF& sample,
                               const Eigen::Ref<const RowMatrixF>& directions, unsigned threads) {
  constexpr Eigen::Index block_rows = 256;
  Eigen::MatrixXf projection(sample.rows(), directions.rows());
  const auto blocks = static_cast<std::size_t>((sample.rows() + block_rows - 1) / block_rows);
  parallel_for(blocks, threads, [&](std::size_t block, unsigned) {
    const Eigen::Index begin = static_cast<Eigen::Index>(block) * block_rows;
    const Eigen::Index size = std::min(block_rows, sample.rows() - begin);
    projection.middleRows(begin, size).noalias() =
        sample.middleRows(begin, size) * directions.transpose();
  });
  return projection;
}

// Squared distance of every sample row (unit norm) from the span of `basis` (orthonormal rows).
Eigen::VectorXf distance_to_subspace(const RowMatrixF& sample, const std::vector<float>& basis,
                                     int terms, unsigned threads) {
  const Eigen::Map<const RowMatrixF> f(basis.data(), terms, sample.cols());
  const Eigen::MatrixXf projection = project_sample(sample, f, threads);
  return (1.0f - projection.rowwise().squaredNorm().array()).max(0.0f).matrix();
}

// Indices (into the sample) of the `count` smallest values of `score`.
std::vector<std::uint32_t> smallest(const Eigen::VectorXf& score, std::size_t count) {
  std::vector<std::uint32_t> order(static_cast<std::size_t>(score.size()));
  std::iota(order.begin(), order.end(), 0u);
  count = std::min(count, order.size());
  std::partial_sort(order.begin(), order.begin() + count, order.end(),
                    [&](std::uint32_t a, std::uint32_t b) { return score[a] < score[b]; });
  order.resize(count);
  return order;
}

// The subspace grown from sample row `seed`: the least-squares subspace of its 2t most similar
// rows by |cosine|, then of the `grow` rows closest to that subspace.
std::vector<float> grow_subspace(const WorkingRows& sample_rows, std::size_t seed, int terms,
                                 std::size_t grow, unsigned threads) {
  const RowMatrixF& sample = sample_rows.values;
  const Eigen::VectorXf cosine =
      -project_sample(sample, sample.row(static_cast<Eigen::Index>(seed)), threads)
           .col(0)
           .cwiseAbs();
  std::vector<float> basis =
      least_squares_subspace(sample_rows, smallest(cosine, std::size_t(2 * terms)), terms);
  return least_squares_subspace(
      sample_rows, smallest(distance_to_subspace(sample, basis, terms, threads), grow), terms);
}

}  // namespace

ClusterModel seed_clusters(const WorkingRows& rows, const SeedingOptions& options) {
  const int lights = rows.lights();
  const std::size_t count = rows.rows();
  std::mt19937_64 random(options.seed);

  // The sample the seeds are drawn from.
  std::vector<std::uint32_t> picked(count);
  std::iota(picked.begin(), picked.end(), 0u);
  const std::size_t sample_size = std::min<std::size_t>(count, std::size_t(options.sample_rows));
  for (std::size_t k = 0; k < sample_size; ++k)
    std::swap(picked[k], picked[k + random() % (count - k)]);
  WorkingRows sample;
  sample.values.resize(static_cast<Eigen::Index>(sample_size), lights);
  sample.norms.assign(sample_size, 1.0f);
  for (std::size_t k = 0; k < sample_size; ++k)
    sample.values.row(static_cast<Eigen::Index>(k)) = rows.values.row(picked[k]);

  ClusterModel model;
  model.terms = options.terms;
  model.lights = lights;
  model.clusters = static_cast<int>(std::min<std::size_t>(std::size_t(options.clusters), count));
  model.bases.reserve(std::size_t(model.clusters) * model.terms * lights);
  const std::size_t grow = std::max<std::size_t>(
      std::size_t(4 * options.terms), sample_size / std::size_t(std::max(1, model.clusters)) / 2);
  Eigen::VectorXf distance = Eigen::VectorXf::Ones(static_cast<Eigen::Index>(sample_size));
  std::size_t seed = random() % std::max<std::size_t>(1, sample_size);
  // A seed takes milliseconds; 100,000 of them took minutes without a word or a look at signals.
  ProgressReporter progress("compress: seeding clusters", std::uint64_t(model.clusters),
                            options.quiet);
  for (int k = 0; k < model.clusters; ++k) {
    progress.advance();
    const std::vector<float> basis =
        grow_subspace(sample, seed, options.terms, grow, options.threads);
    model.bases.insert(model.bases.end(), basis.begin(), basis.end());
    distance = distance.cwiseMin(
        distance_to_subspace(sample.values, basis, options.terms, options.threads));
    // Next seed: drawn with probability proportional to the distance (k-means++).
    const double total = distance.cast<double>().sum();
    if (!(total > 0)) {
      seed = random() % sample_size;
      continue;
    }
    double target = std::uniform_real_distribution<double>(0.0, total)(random);
    seed = sample_size - 1;
    for (std::size_t s = 0; s < sample_size; ++s) {
      target -= distance[static_cast<Eigen::Index>(s)];
      if (target <= 0) {
        seed = s;
        break;
      }
    }
  }
  progress.finish();

  // Least-squares k-subspace rounds over all rows.
  CandidateOptions nearest;
  nearest.count = 1;
  for (int round = 0; round <= options.l2_rounds; ++round) {
    throw_if_interrupted();
    if (round == options.l2_rounds && !options.assign_after_rounds) {
      model.assignment.clear();
      break;
    }
    const CandidateLists best = nearest_subspace_candidates(rows, model, nearest, options.threads);
    model.assignment.assign(best.clusters.begin(), best.clusters.end());
    if (round == options.l2_rounds) break;
    const auto members = model.members();
    parallel_for(std::size_t(model.clusters), options.threads, [&](std::size_t k, unsigned) {
      if (members[k].empty()) return;  // kept as it is; the size rules remove it later
      float* current = model.basis(static_cast<int>(k));
      const std::vector<float> basis =
          least_squares_subspace(rows, members[k], options.terms, nullptr, current);
      std::copy(basis.begin(), basis.end(), current);
    });
  }
  return model;
}

}  // namespace relume
