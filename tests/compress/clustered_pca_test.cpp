// Tests of clustered PCA (the paper's baseline) and of the trimmed least-squares refit: planted
// clustered low-rank data is recovered to near exactness by both forms of CPCA, a CPCA container
// relights through the same OpenCL kernels as the L1 method's (against the CPU reference), the
// paper's trade appears on planted data with sparse spikes (CPCA ahead without residual, the L1
// method ahead with it), and the refit never loses at its budget.
#include "compress/clustered_pca.hpp"

#include <gtest/gtest.h>

#include <map>
#include <random>
#include <relume/error.hpp>
#include <relume/relight.hpp>

#include "compress/clustered_factorization.hpp"
#include "compress/storage_precision.hpp"
#include "compress/trimmed_refit.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

struct PlantedSpec {
  int width = 24, height = 20;  // 3 channels each
  int clusters = 4;
  int rank = 3;  // of every cluster's subspace (about its mean)
  int lights = 32;
  float offset = 0.0f;  // size of each cluster's mean relative to its spread
  float noise = 0.0f;   // Gaussian, per value
  int spikes = 0;       // sparse spikes per function at random lights
  std::uint64_t seed = 7;
};

struct Planted {
  ReflectanceField field;
  std::vector<int> cluster;  // per function
};

// Every function is mean_k + w F_k (+ noise and spikes) for a random cluster k.
Planted planted_clusters(const PlantedSpec& spec) {
  std::mt19937_64 random(spec.seed);
  std::normal_distribution<float> normal;
  Planted planted;
  ReflectanceField& field = planted.field;
  field.width = spec.width;
  field.height = spec.height;
  field.channels = 3;
  field.mask.assign(std::size_t(spec.width) * spec.height, 1);
  field.directions.resize(spec.lights, 3);
  for (int i = 0; i < spec.lights; ++i) {
    const double angle = 2.0 * M_PI * i / spec.lights, height = 0.2 + 0.7 * (i % 4) / 3.0;
    const double ring = std::sqrt(1 - height * height);
    field.directions.row(i) << ring * std::cos(angle), ring * std::sin(angle), height;
  }
  field.intensities.setOnes(spec.lights, 3);
  std::vector<RowMatrixF> bases;
  std::vector<Eigen::RowVectorXf> means;
  for (int k = 0; k < spec.clusters; ++k) {
    RowMatrixF f(spec.rank, spec.lights);
    for (int i = 0; i < f.size(); ++i) f.data()[i] = normal(random);
    bases.push_back(f);
    Eigen::RowVectorXf mean(spec.lights);
    for (int i = 0; i < spec.lights; ++i) mean[i] = spec.offset * normal(random);
    means.push_back(mean);
  }
  field.values.resize(field.pixels() * field.channels, spec.lights);
  for (std::int64_t p = 0; p < field.functions(); ++p) {
    const int k = static_cast<int>(random() % spec.clusters);
    planted.cluster.push_back(k);
    Eigen::RowVectorXf w(spec.rank);
    for (int j = 0; j < spec.rank; ++j) w[j] = normal(random);
    field.values.row(p) = means[k] + w * bases[k];
    for (int i = 0; i < spec.lights; ++i) field.values(p, i) += spec.noise * normal(random);
    for (int e = 0; e < spec.spikes; ++e)
      field.values(p, static_cast<int>(random() % spec.lights)) += (random() % 2 ? 4.0f : -4.0f);
  }
  return planted;
}

CompressionOptions options_for(CompressionMethod method, int clusters, int terms, int entries) {
  CompressionOptions options;
  options.method = method;
  options.clustering.clusters = clusters;
  options.clustering.terms = terms;
  options.clustering.quiet = true;
  options.clustering.threads = 2;
  // Each function is planted in its own cluster, whatever its pixel's other channels.
  options.clustering.shared_pixel_clusters = false;
  options.residual.entries = entries;
  // The planted functions are exact and spatially unrelated, so that no estimate tells them
  // from noise: no noise floor, every function stored.
  options.noise_floor = 0;
  return options;
}

// True when every found cluster's functions come from one planted cluster.
bool clusters_are_pure(const CompressedField& compressed, const std::vector<int>& planted) {
  std::map<std::uint32_t, int> source;
  for (std::size_t r = 0; r < compressed.stored_rows(); ++r) {
    const int from = planted[compressed.stored_function[r]];
    const auto [at, inserted] = source.emplace(compressed.cluster[r], from);
    if (!inserted && at->second != from) return false;
  }
  return true;
}

double masked_error(const ReflectanceField& field, const CompressedField& compressed, int cap) {
  return relative_error(field, compressed, true, cap, 2).mean;
}

TEST(ClusteredPca, RecoversPlantedLinearSubspaces) {
  const Planted planted = planted_clusters({});
  CompressionStats stats;
  const CompressedField compressed =
      compress_field(planted.field, options_for(CompressionMethod::cpca, 4, 3, 0), stats);
  EXPECT_EQ(compressed.clusters, 4);
  EXPECT_LT(masked_error(planted.field, compressed, 0), 1e-6);
  EXPECT_TRUE(clusters_are_pure(compressed, planted.cluster));
  ASSERT_FALSE(stats.clustering.iterations.empty());
  EXPECT_TRUE(stats.clustering.settled);
}

TEST(ClusteredPca, RecoversPlantedAffineClustersWithTheirMeans) {
  PlantedSpec spec;
  spec.offset = 3.0f;  // clusters far from the origin: a mean plus 3 components each
  const Planted planted = planted_clusters(spec);
  CompressionOptions options = options_for(CompressionMethod::cpca, 4, 4, 0);
  options.pca.centering = PcaCentering::mean;
  CompressionStats stats;
  const CompressedField compressed = compress_field(planted.field, options, stats);
  EXPECT_LT(masked_error(planted.field, compressed, 0), 1e-6);
  EXPECT_TRUE(clusters_are_pure(compressed, planted.cluster));
  // The stored bases are orthonormal (the mean folded into the span).
  for (int k = 0; k < compressed.clusters; ++k) {
    const Eigen::Map<const RowMatrixF> f(compressed.basis(k), compressed.terms, compressed.lights);
    EXPECT_LT(((f * f.transpose()) - Eigen::MatrixXf::Identity(4, 4)).cwiseAbs().maxCoeff(), 1e-4)
        << "cluster " << k;
  }
  // With one term fewer the affine data does not fit without the mean's direction.
  CompressionOptions fewer = options_for(CompressionMethod::cpca, 4, 3, 0);
  CompressionStats fewer_stats;
  EXPECT_GT(masked_error(planted.field, compress_field(planted.field, fewer, fewer_stats), 0),
            1e-3);
}

TEST(ClusteredPca, RelightsThroughTheSameKernelsAsTheL1Method) {
  PlantedSpec spec;
  spec.noise = 0.05f;
  spec.spikes = 2;
  const Planted planted = planted_clusters(spec);
  CompressionStats stats;
  CompressedField stored =
      compress_field(planted.field, options_for(CompressionMethod::cpca, 4, 3, 3), stats);
  store_with_precision(planted.field, stored, StoragePrecision{});
  LightRgb light(spec.lights, 3);
  std::mt19937_64 random(11);
  std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
  for (int i = 0; i < light.size(); ++i) light.data()[i] = uniform(random);
  const Image reference = relight_compressed_reference(stored, light);
  Relighter relighter(stored);  // OpenCL (PoCL in the tests)
  for (const int cap : {0, 2, all_residual_entries}) {
    const Image image = relighter.relight(light, cap);
    const Image expected = relight_compressed_reference(stored, light, cap);
    ASSERT_EQ(image.pixels.size(), expected.pixels.size());
    double largest = 0, scale = 0;
    for (std::size_t v = 0; v < image.pixels.size(); ++v) {
      largest = std::max(largest, double(std::fabs(image.pixels[v] - expected.pixels[v])));
      scale = std::max(scale, double(std::fabs(expected.pixels[v])));
    }
    EXPECT_LT(largest, 1e-4 * scale) << "cap " << cap;
  }
  // The residual matters to the relit image: cap 0 and the full residual differ.
  double change = 0;
  const Image no_residual = relighter.relight(light, 0);
  for (std::size_t v = 0; v < reference.pixels.size(); ++v)
    change = std::max(change, double(std::fabs(no_residual.pixels[v] - reference.pixels[v])));
  EXPECT_GT(change, 1e-3);
}

// Low-rank clusters with noise and 3 large spikes per function: least squares fits the noise best
// when no residual is kept, L1 isolates the spikes for the residual to take.
Planted spiky_field() {
  PlantedSpec spec;
  spec.noise = 0.02f;
  spec.spikes = 3;
  spec.lights = 48;
  return planted_clusters(spec);
}

TEST(ClusteredPca, ShowsThePapersTradeAgainstTheL1Method) {
  const Planted planted = spiky_field();
  CompressionStats l1_stats, cpca_stats;
  const CompressedField l1 =
      compress_field(planted.field, options_for(CompressionMethod::l1, 4, 3, 6), l1_stats);
  const CompressedField cpca =
      compress_field(planted.field, options_for(CompressionMethod::cpca, 4, 3, 6), cpca_stats);
  const double l1_at_0 = masked_error(planted.field, l1, 0);
  const double cpca_at_0 = masked_error(planted.field, cpca, 0);
  const double l1_at_3 = masked_error(planted.field, l1, 3);
  const double cpca_at_3 = masked_error(planted.field, cpca, 3);
  EXPECT_LT(cpca_at_0, l1_at_0);
  EXPECT_LT(l1_at_3, 0.5 * cpca_at_3);
}

TEST(TrimmedRefit, NeverLosesAtItsBudgetAndMeasuresWhatItMinimises) {
  const Planted planted = spiky_field();
  for (const int entries : {0, 2, 3}) {
    CompressionOptions options = options_for(CompressionMethod::l1, 4, 3, entries);
    CompressionStats plain_stats, refit_stats;
    const CompressedField plain = compress_field(planted.field, options, plain_stats);
    options.trimmed_refit_rounds = 2;
    const CompressedField refit = compress_field(planted.field, options, refit_stats);
    ASSERT_TRUE(refit_stats.trimmed_refit) << entries;
    const TrimmedRefitTrace& trace = *refit_stats.trimmed_refit;
    const double plain_error = masked_error(planted.field, plain, entries);
    const double refit_error = masked_error(planted.field, refit, entries);
    EXPECT_LE(refit_error, plain_error * (1 + 1e-5)) << entries;
    // Its objective is the Eq. 16 error at the budget times the rows, falling every round.
    const double rows = double(refit.stored_rows());
    EXPECT_NEAR(trace.objective_before / rows, plain_error, 1e-4 * plain_error + 1e-9) << entries;
    EXPECT_NEAR(trace.objective_after.back() / rows, refit_error, 1e-4 * refit_error + 1e-9)
        << entries;
    for (std::size_t round = 1; round < trace.objective_after.size(); ++round)
      EXPECT_LE(trace.objective_after[round], trace.objective_after[round - 1] * (1 + 1e-9));
  }
  // Without residual the refit turns the L1 clusters into least-squares ones: at least as good
  // as clustered PCA on this data.
  CompressionOptions options = options_for(CompressionMethod::l1, 4, 3, 0);
  options.trimmed_refit_rounds = 2;
  CompressionStats refit_stats, cpca_stats;
  const double refit_at_0 =
      masked_error(planted.field, compress_field(planted.field, options, refit_stats), 0);
  const double cpca_at_0 = masked_error(
      planted.field,
      compress_field(planted.field, options_for(CompressionMethod::cpca, 4, 3, 0), cpca_stats), 0);
  EXPECT_LE(refit_at_0, cpca_at_0 * (1 + 1e-3));
}

TEST(ClusteredPca, RefusesWhatItCannotDo) {
  const Planted planted = planted_clusters({});
  CompressionOptions options = options_for(CompressionMethod::cpca, 4, 3, 0);
  options.multires_levels = 1;
  CompressionStats stats;
  EXPECT_THAT(testing::error_message([&] { compress_field(planted.field, options, stats); }),
              ::testing::HasSubstr("multi-resolution"));
  EXPECT_THAT(testing::error_message([] { parse_compression_method("pca"); }),
              ::testing::HasSubstr("'pca'"));
  EXPECT_THAT(testing::error_message([] { parse_pca_centering("median"); }),
              ::testing::HasSubstr("'median'"));
}

}  // namespace
}  // namespace relume
