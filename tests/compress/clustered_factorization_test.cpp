// Tests of clustered sparse residual factorization: planted clusters are recovered to near
// exactness, the full residual is lossless, masked and all-zero functions cost nothing, the Haar
// basis round-trips, the size rules merge and split clusters, and the thread count changes nothing.
#include "compress/clustered_factorization.hpp"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <relume/error.hpp>
#include <set>

#include "compress/cluster_basis.hpp"
#include "compress/cluster_size_rules.hpp"
#include "compress/noise_model.hpp"
#include "model/compressed_field_checks.hpp"
#include "model/reconstruct_field.hpp"

namespace relume {
namespace {

struct PlantedField {
  ReflectanceField field;
  std::vector<int> cluster;  // per function
};

// A field of `clusters` clusters: every function is exactly w F^k + a residual with `outliers`
// non-zeros at random lights.
PlantedField planted_field(int width, int height, int clusters, int terms, int lights, int outliers,
                           std::uint64_t seed) {
  std::mt19937_64 random(seed);
  std::normal_distribution<float> normal;
  std::uniform_real_distribution<float> uniform(0.5f, 2.0f);
  PlantedField planted;
  ReflectanceField& field = planted.field;
  field.width = width;
  field.height = height;
  field.channels = 3;
  field.mask.assign(std::size_t(width) * height, 1);
  field.directions.setZero(lights, 3);
  field.directions.col(2).setOnes();
  field.intensities.setOnes(lights, 3);
  std::vector<RowMatrixF> bases;
  for (int k = 0; k < clusters; ++k) {
    RowMatrixF f(terms, lights);
    for (int i = 0; i < f.size(); ++i) f.data()[i] = normal(random);
    bases.push_back(f);
  }
  field.values.resize(field.pixels() * 3, lights);
  for (std::int64_t p = 0; p < field.functions(); ++p) {
    const int k = static_cast<int>(random() % clusters);
    planted.cluster.push_back(k);
    Eigen::RowVectorXf w(terms);
    for (int j = 0; j < terms; ++j) w[j] = normal(random);
    field.values.row(p) = w * bases[k];
    for (int e = 0; e < outliers; ++e) {
      const int light = static_cast<int>(random() % lights);
      field.values(p, light) += (random() % 2 ? 1.0f : -1.0f) * uniform(random);
    }
  }
  return planted;
}

CompressionOptions options_for(int clusters, int terms, int residual) {
  CompressionOptions options;
  options.clustering.clusters = clusters;
  options.clustering.terms = terms;
  options.clustering.quiet = true;
  options.clustering.threads = 2;
  // Every function is planted in a cluster of its own choosing, whatever its pixel's other
  // channels: each channel is clustered on its own.
  options.clustering.shared_pixel_clusters = false;
  options.residual.entries = residual;
  // The planted functions are exact and spatially unrelated, so that no estimate tells them
  // from noise: no noise floor, every function stored.
  options.noise_floor = 0;
  return options;
}

// The fraction of functions whose cluster agrees with the planted one after matching each found
// cluster to the planted cluster most of its members come from.
double cluster_purity(const CompressedField& compressed, const std::vector<int>& planted) {
  std::vector<std::map<int, int>> votes(compressed.clusters);
  for (std::size_t r = 0; r < compressed.stored_rows(); ++r)
    ++votes[compressed.cluster[r]][planted[compressed.stored_function[r]]];
  std::size_t agreeing = 0;
  for (const auto& counts : votes) {
    int best = 0;
    for (const auto& [k, count] : counts) best = std::max(best, count);
    agreeing += best;
  }
  return double(agreeing) / compressed.stored_rows();
}

TEST(ClusteredFactorization, RecoversPlantedClustersWithTheirSparseResidual) {
  const PlantedField planted = planted_field(40, 20, 8, 4, 96, 3, 7);
  CompressionStats stats;
  const CompressedField compressed = compress_field(planted.field, options_for(8, 4, 3), stats);
  EXPECT_EQ(compressed.clusters, 8);
  EXPECT_EQ(compressed.stored_rows(), std::size_t(planted.field.functions()));
  EXPECT_GT(cluster_purity(compressed, planted.cluster), 0.999);
  const RelativeError error = relative_error(planted.field, compressed, false);
  EXPECT_LT(error.mean, 1e-4) << "after " << stats.clustering.iterations.size() << " iterations";
  EXPECT_NO_THROW(validate_compressed_field(compressed, "planted"));
}

TEST(ClusteredFactorization, SameResultOnAnyThreadCount) {
  // Noise keeps the clustering from being trivial; 300 lights make seeding's projections of the
  // sample run in more than one block of rows.
  PlantedField planted = planted_field(40, 30, 6, 3, 300, 4, 13);
  std::mt19937_64 random(5);
  std::normal_distribution<float> normal(0.0f, 0.05f);
  for (std::int64_t p = 0; p < planted.field.values.size(); ++p)
    planted.field.values.data()[p] += normal(random);
  const auto compress_on = [&](unsigned threads) {
    CompressionOptions options = options_for(6, 3, 4);
    options.clustering.threads = threads;
    CompressionStats stats;
    return compress_field(planted.field, options, stats);
  };
  const CompressedField one = compress_on(1);
  ASSERT_EQ(one.clusters, 6);
  for (unsigned threads : {2u, 3u}) {
    const CompressedField many = compress_on(threads);
    EXPECT_EQ(many.cluster, one.cluster) << threads << " threads";
    EXPECT_EQ(many.bases, one.bases) << threads << " threads";
    EXPECT_EQ(many.weights, one.weights) << threads << " threads";
    EXPECT_EQ(many.residual.values, one.residual.values) << threads << " threads";
  }
}

TEST(ClusteredFactorization, FullResidualIsLossless) {
  PlantedField planted = planted_field(16, 8, 3, 2, 40, 0, 11);
  std::mt19937_64 random(3);
  std::normal_distribution<float> normal;
  for (std::int64_t p = 0; p < planted.field.values.size(); ++p)
    planted.field.values.data()[p] += normal(random);  // far from low rank
  const CompressedField compressed = [&] {
    CompressionStats stats;
    return compress_field(planted.field, options_for(4, 2, 40), stats);
  }();
  EXPECT_EQ(compressed.residual.nonzeros(), compressed.stored_rows() * 40);
  const ReflectanceField back = reconstruct_field(compressed);
  const float scale = planted.field.values.cwiseAbs().maxCoeff();
  EXPECT_LT((back.values - planted.field.values).cwiseAbs().maxCoeff(), 1e-5f * scale);
  EXPECT_LT(relative_error(planted.field, compressed, false).mean, 1e-11);
}

TEST(ClusteredFactorization, MaskedAndAllZeroFunctionsAreNotStored) {
  PlantedField planted = planted_field(12, 10, 2, 2, 24, 0, 5);
  ReflectanceField& field = planted.field;
  for (int x = 0; x < 12; ++x) field.mask[x] = 0;             // first row outside the mask
  field.values.row(field.function_index(3, 4, 1)).setZero();  // one zero function inside
  CompressionStats stats;
  const CompressedField compressed = compress_field(field, options_for(2, 2, 4), stats);
  EXPECT_EQ(stats.outside_mask, 12 * 3);
  EXPECT_EQ(stats.all_zero, 1);
  EXPECT_EQ(compressed.stored_rows(), std::size_t(field.functions() - 12 * 3 - 1));
  const std::set<std::uint32_t> stored(compressed.stored_function.begin(),
                                       compressed.stored_function.end());
  EXPECT_EQ(stored.count(std::uint32_t(field.function_index(3, 4, 1))), 0u);
  EXPECT_EQ(stored.count(std::uint32_t(field.function_index(5, 0, 2))), 0u);
  EXPECT_EQ(stored.count(std::uint32_t(field.function_index(5, 1, 2))), 1u);
}

TEST(ClusteredFactorization, HaarBasisReconstructsInTheLightBasis) {
  PlantedField planted = planted_field(16, 8, 3, 3, 50, 2, 13);
  CompressionOptions options = options_for(3, 3, 50);
  options.transform = BasisTransform::haar;
  CompressionStats stats;
  const CompressedField compressed = compress_field(planted.field, options, stats);
  EXPECT_EQ(compressed.transform, BasisTransform::haar);
  EXPECT_LT(relative_error(planted.field, compressed, false).mean, 1e-10);
}

TEST(ClusteredFactorization, MultiresolutionRecoversSpatiallyCoherentClusters) {
  // Clusters laid out in vertical bands, as in an image: the low-resolution clustering sees them.
  PlantedField planted = planted_field(48, 16, 4, 3, 64, 2, 17);
  ReflectanceField& field = planted.field;
  std::mt19937_64 random(5);
  std::normal_distribution<float> normal;
  std::vector<RowMatrixF> bases;
  for (int k = 0; k < 4; ++k)
    bases.push_back(RowMatrixF::NullaryExpr(3, 64, [&] { return normal(random); }));
  for (std::int64_t p = 0; p < field.functions(); ++p) {
    const int x = static_cast<int>((p / 3) % field.width);
    const int k = x / 12;
    planted.cluster[p] = k;
    Eigen::RowVectorXf w(3);
    for (int j = 0; j < 3; ++j) w[j] = normal(random);
    field.values.row(p) = w * bases[k];
    field.values(p, static_cast<int>(random() % 64)) += 1.0f;
  }
  CompressionOptions options = options_for(4, 3, 1);
  options.multires_levels = 1;
  options.refine_iterations = 1;
  CompressionStats stats;
  const CompressedField compressed = compress_field(field, options, stats);
  ASSERT_TRUE(stats.multires.has_value());
  EXPECT_EQ(stats.multires->low_width, 24);
  EXPECT_GT(cluster_purity(compressed, planted.cluster), 0.99);
  EXPECT_LT(relative_error(field, compressed, false).mean, 1e-3);
}

TEST(ClusteredFactorization, SizeRulesMergeSmallAndSplitLargeClusters) {
  const PlantedField planted = planted_field(20, 10, 2, 2, 32, 0, 23);
  CompressionOptions options = options_for(2, 2, 0);
  options.clustering.sizes.maximum = 200;  // 600 functions: at least 3 clusters
  CompressionStats stats;
  const CompressedField split = compress_field(planted.field, options, stats);
  EXPECT_GE(split.clusters, 3);
  std::vector<int> sizes(split.clusters, 0);
  for (const auto k : split.cluster) ++sizes[k];
  for (const int size : sizes) EXPECT_LE(size, 200);
}

TEST(ClusteredFactorization, SmallClustersMergeIntoTheClusterThatFitsTheirRows) {
  // Rows from two planted subspaces; a third cluster holds 5 rows of subspace 0 with a random
  // basis. With a minimum of 10 it is dissolved and its rows join cluster 0.
  const PlantedField planted = planted_field(10, 10, 2, 2, 32, 0, 29);
  const PreparedRows prepared =
      prepare_rows(planted.field, false, noise_floor_model(planted.field, 0), 1);
  ClusterModel model;
  model.terms = 2;
  model.lights = 32;
  model.clusters = 3;
  std::vector<std::vector<std::uint32_t>> planted_members(2);
  for (std::size_t r = 0; r < prepared.rows.rows(); ++r)
    planted_members[planted.cluster[prepared.functions[r]]].push_back(std::uint32_t(r));
  for (int k = 0; k < 2; ++k) {
    const auto basis = least_squares_subspace(prepared.rows, planted_members[k], 2);
    model.bases.insert(model.bases.end(), basis.begin(), basis.end());
  }
  std::mt19937_64 random(1);
  std::normal_distribution<float> normal;
  for (int i = 0; i < 64; ++i) model.bases.push_back(normal(random));
  model.assignment.resize(prepared.rows.rows());
  for (std::size_t r = 0; r < prepared.rows.rows(); ++r)
    model.assignment[r] = planted.cluster[prepared.functions[r]];
  for (int m = 0; m < 5; ++m) model.assignment[planted_members[0][m]] = 2;
  model.weights.setZero(prepared.rows.rows(), 2);
  const SizeRuleChanges changes =
      enforce_cluster_sizes(prepared.rows, model, {10, 0}, 3, IrlsSettings{}, 1);
  EXPECT_EQ(changes.merged, 1);
  EXPECT_EQ(changes.rows_moved, 5u);
  EXPECT_EQ(model.clusters, 2);
  EXPECT_EQ(model.bases.size(), 2u * 2 * 32);
  for (int m = 0; m < 5; ++m) EXPECT_EQ(model.assignment[planted_members[0][m]], 0);
}

// The pixels whose channels are not all in one cluster.
std::size_t split_pixels(const CompressedField& compressed) {
  std::map<std::uint32_t, std::set<std::uint32_t>> clusters;
  for (std::size_t r = 0; r < compressed.stored_rows(); ++r)
    clusters[compressed.stored_function[r] / 3].insert(compressed.cluster[r]);
  std::size_t split = 0;
  for (const auto& [pixel, set] : clusters) split += set.size() > 1;
  return split;
}

TEST(ClusteredFactorization, SharedPixelClustersPutAPixelsChannelsInOneCluster) {
  // Each pixel's three channels are multiples of one function of its cluster (a colour times a
  // shading) plus noise that lets the channels' own fits prefer different clusters.
  const int width = 30, height = 20, clusters = 6, terms = 3, lights = 48;
  PlantedField planted = planted_field(width, height, clusters, terms, lights, 0, 17);
  ReflectanceField& field = planted.field;
  std::mt19937_64 random(3);
  std::uniform_real_distribution<float> colour(0.3f, 1.0f);
  std::normal_distribution<float> noise(0.0f, 1.0f);
  for (std::int64_t q = 0; q < field.pixels(); ++q)
    for (int c = 1; c < 3; ++c)
      field.values.row(q * 3 + c) = colour(random) * field.values.row(q * 3);
  for (std::int64_t i = 0; i < field.values.size(); ++i) field.values.data()[i] += noise(random);
  const auto compressed_with = [&](bool shared, CompressionStats& stats) {
    CompressionOptions options = options_for(clusters, terms, 0);
    options.clustering.shared_pixel_clusters = shared;
    return compress_field(field, options, stats);
  };
  CompressionStats separate_stats, shared_stats;
  const CompressedField separate = compressed_with(false, separate_stats);
  const CompressedField shared = compressed_with(true, shared_stats);
  ASSERT_GT(split_pixels(separate), std::size_t(width * height / 20)) << "the test needs splits";
  EXPECT_EQ(split_pixels(shared), 0u);
  EXPECT_GT(shared_stats.clustering.iterations.back().split_pixels, 0u)
      << "the last reassignment split pixels that the sharing joined";
  // Joining costs some fit, not much: the channels' shapes are alike.
  const double separate_error = relative_error(field, separate, false).mean;
  const double shared_error = relative_error(field, shared, false).mean;
  EXPECT_LT(shared_error, 1.1 * separate_error);
  EXPECT_NO_THROW(validate_compressed_field(shared, "shared"));
}

TEST(ClusteredFactorization, RefusesBadSettings) {
  const PlantedField planted = planted_field(4, 4, 1, 2, 16, 0, 1);
  CompressionStats stats;
  EXPECT_THROW(compress_field(planted.field, options_for(2, 16, 0), stats), Error);
  EXPECT_THROW(compress_field(planted.field, options_for(0, 2, 0), stats), Error);
  CompressionOptions options = options_for(2, 2, 0);
  options.clustering.sizes = {10, 15};
  EXPECT_THROW(compress_field(planted.field, options, stats), Error);
  ReflectanceField bad = planted.field;
  bad.values(5, 3) = std::nanf("");
  EXPECT_THROW(compress_field(bad, options_for(2, 2, 0), stats), Error);
}

}  // namespace
}  // namespace relume
