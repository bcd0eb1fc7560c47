// Tests of light weighting: the scales follow each light's RMS to the asked exponent (with its
// floor), a residual row chosen in the weighted domain comes back in field units sorted as every
// row is, a weighted compression is exact with its full residual and valid, it makes the dim
// lights' relative errors smaller than the unweighted one does, and it refuses the Haar basis.
#include "compress/light_weighting.hpp"

#include <random>
#include <relume/error.hpp>

#include "compress/clustered_factorization.hpp"
#include "model/compressed_field_checks.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

using testing::error_message;
using ::testing::HasSubstr;

// A 12x10 RGB field of 24 lights: two clusters of rank 4 (more than the 2 terms fitted), lights
// 12 to 23 a hundred times dimmer than lights 0 to 11, as lights that only graze an object are.
ReflectanceField dim_back_lights_field() {
  std::mt19937_64 random(11);
  std::normal_distribution<float> normal;
  ReflectanceField field;
  field.width = 12;
  field.height = 10;
  field.channels = 3;
  const int lights = 24, rank = 4;
  field.mask.assign(std::size_t(field.pixels()), 1);
  field.directions.setZero(lights, 3);
  field.directions.col(2).setOnes();
  field.intensities.setOnes(lights, 3);
  RowMatrixF bases[2] = {RowMatrixF(rank, lights), RowMatrixF(rank, lights)};
  for (RowMatrixF& f : bases)
    for (int v = 0; v < f.size(); ++v) f.data()[v] = std::abs(normal(random)) + 0.1f;
  field.values.resize(field.pixels() * field.channels, lights);
  for (std::int64_t p = 0; p < field.functions(); ++p) {
    Eigen::RowVectorXf w(rank);
    for (int j = 0; j < rank; ++j) w[j] = std::abs(normal(random));
    field.values.row(p) = w * bases[p % 2];
  }
  field.values.rightCols(12) *= 0.01f;
  return field;
}

CompressionOptions options_for(double light_weighting, int residual) {
  CompressionOptions options;
  options.clustering.clusters = 2;
  options.clustering.terms = 2;
  options.clustering.quiet = true;
  options.clustering.threads = 2;
  options.residual.entries = residual;
  options.light_weighting = light_weighting;
  return options;
}

// Relative error of each light's image: sum_p (R - R~)^2 / sum_p R^2.
std::vector<double> per_light_errors(const ReflectanceField& original,
                                     const CompressedField& compressed) {
  const ReflectanceField approx = reconstruct_field(compressed);
  std::vector<double> errors;
  for (int i = 0; i < original.lights(); ++i)
    errors.push_back((original.values.col(i) - approx.values.col(i)).squaredNorm() /
                     original.values.col(i).squaredNorm());
  return errors;
}

TEST(LightWeighting, ScalesFollowTheLightsRmsToTheExponent) {
  const ReflectanceField field = dim_back_lights_field();
  const std::vector<float> full = light_weighting_scales(field, 1.0);
  const std::vector<float> half = light_weighting_scales(field, 0.5);
  ASSERT_EQ(full.size(), 24u);
  float largest = 0;
  for (int i = 0; i < 24; ++i) {
    const double rms =
        std::sqrt(field.values.col(i).cast<double>().squaredNorm() / double(field.functions()));
    EXPECT_NEAR(half[i], std::sqrt(full[i]), 1e-6) << i;
    largest = std::max(largest, full[i]);
    if (i >= 12) {
      EXPECT_LT(full[i], 0.05f) << "dim light " << i << " rms " << rms;
    }
  }
  EXPECT_FLOAT_EQ(largest, 1.0f);
  EXPECT_EQ(light_weighting_scales(field, 0.0), std::vector<float>(24, 1.0f));
  // A light that never reaches the object gets the floor, 1e-3 of the brightest.
  ReflectanceField dark = field;
  dark.values.col(5).setZero();
  EXPECT_NEAR(light_weighting_scales(dark, 1.0)[5], 1e-3f, 1e-9f);
  EXPECT_THAT(error_message([&] { light_weighting_scales(field, 1.5); }),
              HasSubstr("exponent in [0, 1], got 1.5"));
}

TEST(LightWeighting, AWeightedRowComesBackInFieldUnitsSorted) {
  ResidualRows rows;
  rows.row_offsets = {0, 1};
  rows.values = {9.0f, 0.5f, -0.25f, 0.25f};  // a previous row, then weighted values
  rows.light_index = {7, 0, 1, 2};
  rows.row_offsets.push_back(4);
  unweight_residual_row(rows, 1, {1.0f, 8.0f, 0.5f, 1.0f, 1.0f, 1.0f, 1.0f, 1.0f});
  EXPECT_EQ(rows.values, (std::vector<float>{9.0f, -2.0f, 0.5f, 0.125f}));
  EXPECT_EQ(rows.light_index, (std::vector<std::uint32_t>{7, 1, 0, 2}));
}

TEST(LightWeighting, WeightedCompressionIsExactWithItsFullResidualAndValid) {
  const ReflectanceField field = dim_back_lights_field();
  CompressionStats stats;
  const CompressedField compressed = compress_field(field, options_for(1.0, 24), stats);
  validate_compressed_field(compressed, "weighted");
  EXPECT_LT(relative_error(field, compressed, false).mean, 1e-10);
}

TEST(LightWeighting, DimLightsKeepTheirAccuracy) {
  const ReflectanceField field = dim_back_lights_field();
  CompressionStats plain_stats, weighted_stats;
  const CompressedField plain = compress_field(field, options_for(0.0, 2), plain_stats);
  const CompressedField weighted = compress_field(field, options_for(1.0, 2), weighted_stats);
  const std::vector<double> plain_errors = per_light_errors(field, plain);
  const std::vector<double> weighted_errors = per_light_errors(field, weighted);
  const double plain_worst = *std::max_element(plain_errors.begin() + 12, plain_errors.end());
  const double weighted_worst =
      *std::max_element(weighted_errors.begin() + 12, weighted_errors.end());
  EXPECT_LT(weighted_worst, 0.5 * plain_worst);
  // The trade: Eq. 16, which the bright lights dominate, is no better weighted.
  EXPECT_GE(relative_error(field, weighted, false).mean,
            0.99 * relative_error(field, plain, false).mean);
}

TEST(LightWeighting, RefusesTheHaarBasisAndExponentsOutOfRange) {
  const ReflectanceField field = dim_back_lights_field();
  CompressionOptions haar = options_for(0.5, 2);
  haar.transform = BasisTransform::haar;
  CompressionStats stats;
  EXPECT_THAT(error_message([&] { compress_field(field, haar, stats); }),
              HasSubstr("use one of --light-weighting and --transform haar"));
  EXPECT_THAT(error_message([&] { compress_field(field, options_for(-0.1, 2), stats); }),
              HasSubstr("light weighting must be an exponent in [0, 1]"));
}

}  // namespace
}  // namespace relume
