// Tests of quantized storage: aligned orthonormal bases reconstruct the same field, quantized
// values are exact multiples of their steps (entries that round to zero dropped, rows still
// sorted), the error-budget choice keeps its budget, quantized fields round-trip through the
// container bit for bit (weights through their camera-space prediction), and the 8-bit PSNR
// measures what it says. (Damaged quantized sections: tests/container/container_test.cpp.)
#include "model/quantization.hpp"

#include <algorithm>
#include <cmath>
#include <relume/container.hpp>
#include <relume/error.hpp>
#include <vector>

#include "container/weight_prediction.hpp"
#include "model/basis_alignment.hpp"
#include "model/compressed_field_checks.hpp"
#include "model/field_psnr.hpp"
#include "model/random_compressed_field.hpp"
#include "model/reconstruct_field.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

using testing::error_message;
using ::testing::HasSubstr;
using testing::noisy_original;
using testing::TempDir;

CompressedField sample_field(std::uint64_t seed = 5) {
  RandomFieldShape shape;
  shape.width = 12;
  shape.height = 9;
  shape.channels = 3;
  shape.lights = 24;
  shape.clusters = 4;
  shape.terms = 3;
  shape.residual_per_function = 6;
  shape.vary_residual = true;
  shape.stored_fraction = 0.8;
  shape.seed = seed;
  return random_compressed_field(shape);
}

double largest_difference(const ReflectanceField& a, const ReflectanceField& b) {
  return (a.values - b.values).cwiseAbs().maxCoeff();
}

// The squared error of `field`'s stored rows against `original` over those rows' energy: the
// measure the quantization budget holds (not Eq. 16's mean of per-function ratios).
double stored_squared_error(const ReflectanceField& original, const CompressedField& field) {
  const ReflectanceField approx = reconstruct_field(field);
  double difference = 0, energy = 0;
  for (const std::uint64_t function : field.stored_function) {
    const auto row = Eigen::Index(function);
    difference += (original.values.row(row) - approx.values.row(row)).cast<double>().squaredNorm();
    energy += original.values.row(row).cast<double>().squaredNorm();
  }
  return difference / energy;
}

TEST(BasisAlignment, KeepsEveryReconstructionAndMakesBasesOrthonormal) {
  CompressedField field = sample_field();
  const ReflectanceField before = reconstruct_field(field);
  align_cluster_bases(field);
  EXPECT_LT(largest_difference(reconstruct_field(field), before), 1e-5);
  for (int k = 0; k < field.clusters; ++k) {
    const Eigen::Map<const Eigen::Matrix<float, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>
        basis(field.basis(k), field.terms, field.lights);
    const Eigen::MatrixXf gram = basis * basis.transpose();
    EXPECT_LT((gram - Eigen::MatrixXf::Identity(field.terms, field.terms)).cwiseAbs().maxCoeff(),
              1e-5)
        << "cluster " << k;
  }
}

TEST(BasisAlignment, BringsClustersOfOneSubspaceToTheSameBasis) {
  // Two clusters whose bases span the same subspace in different coordinates: after alignment
  // their bases agree, so equal functions get equal weights in either cluster.
  CompressedField field = sample_field();
  const int t = field.terms, m = field.lights;
  std::vector<float> mixed(field.bases.begin(), field.bases.begin() + t * m);
  for (int j = 0; j < t; ++j)  // cluster 1 = an invertible mix of cluster 0's rows
    for (int i = 0; i < m; ++i)
      field.bases[std::size_t(t + j) * m + i] =
          mixed[std::size_t(j) * m + i] + 0.5f * mixed[std::size_t((j + 1) % t) * m + i];
  align_cluster_bases(field);
  for (int v = 0; v < t * m; ++v)
    EXPECT_NEAR(std::abs(field.bases[v]), std::abs(field.bases[t * m + v]), 1e-4) << v;
}

TEST(Quantization, ValuesBecomeMultiplesOfTheirStepsAndZerosLeaveTheResidual) {
  CompressedField field = sample_field();
  align_cluster_bases(field);
  const QuantizationSteps steps{0.01f, 0.05f, 9};
  const CompressedField q = quantize_values(field, steps);
  validate_compressed_field(q, "quantized");
  EXPECT_EQ(q.quantization.weight_step, 0.01f);
  EXPECT_EQ(q.quantization.residual_step, 0.05f);
  EXPECT_EQ(q.quantization.basis_bits, 9);
  ASSERT_EQ(q.quantization.basis_scales.size(), std::size_t(field.clusters * field.terms));
  for (Eigen::Index i = 0; i < q.weights.size(); ++i) {
    const double units = q.weights.data()[i] / 0.01;
    EXPECT_NEAR(units, std::round(units), 1e-3);
    EXPECT_LE(std::abs(q.weights.data()[i] - field.weights.data()[i]), 0.005f + 1e-6f);
  }
  EXPECT_LT(q.residual.nonzeros(), field.residual.nonzeros())
      << "sigma 0.1 values: some round to 0";
  for (float v : q.residual.values) {
    EXPECT_NE(v, 0.0f);
    EXPECT_NEAR(v / 0.05, std::round(v / 0.05), 1e-3);
  }
  for (std::size_t row = 0; row < q.quantization.basis_scales.size(); ++row)
    for (int i = 0; i < q.lights; ++i) {
      const double units = q.bases[row * q.lights + i] / q.quantization.basis_scales[row];
      EXPECT_NEAR(units, std::round(units), 1e-3);
      EXPECT_LE(std::abs(units), 255.0);
    }
  EXPECT_THAT(error_message([&] {
                quantize_values(field, {1e-9f, 0, 0});
              }),
              HasSubstr("needs more than 16 bits"));
  EXPECT_THAT(error_message([&] {
                quantize_values(field, {0, 0, 5});
              }),
              HasSubstr("basis bits must be 8 to 16"));
}

TEST(Quantization, TheChosenStepsKeepTheBudgetAndCoarserOnesWouldNot) {
  CompressedField field = sample_field();
  const ReflectanceField original = noisy_original(field, 0.05);
  for (double budget : {0.01, 0.1}) {
    CompressedField stored = field;
    QuantizationBudget asked;
    asked.relative_increase = budget;
    const QuantizationChoice choice = quantize_with_budget(original, stored, asked);
    const double before = stored_squared_error(original, field);
    const double after = stored_squared_error(original, stored);
    EXPECT_GT(after, before);
    EXPECT_LE(after, before * (1 + budget)) << budget;  // all rows are the sample here
    EXPECT_NEAR(choice.error_quantized, after, 1e-6 * after);
    // Four times coarser weights would break it.
    CompressedField aligned = field;
    align_cluster_bases(aligned);
    QuantizationSteps coarser = choice.steps;
    coarser.weight_step *= 4;
    EXPECT_GT(stored_squared_error(original, quantize_values(aligned, coarser)),
              before * (1 + budget));
  }
}

TEST(WeightPrediction, RoundTripsAnyIntegersWithMissingNeighbours) {
  CompressedField field = sample_field(8);
  std::vector<std::int32_t> integers(std::size_t(field.weights.size()));
  std::uint32_t state = 3;
  for (auto& q : integers) {
    state = state * 1664525u + 1013904223u;
    q = std::int32_t(state >> 16) % 65535 - 32767;  // the whole range, wrap-around included
  }
  const std::vector<std::uint8_t> every_term(std::size_t(field.clusters) * field.terms, 1);
  EXPECT_EQ(unpredict_weights(field, predict_weights(field, integers, every_term), every_term),
            integers);
  // Terms a cluster does not store have no error and decode as zeros.
  std::vector<std::uint8_t> some_terms = every_term;
  some_terms[1] = some_terms[2 * field.terms] = 0;  // cluster 0 term 1, cluster 2 term 0
  std::vector<std::int32_t> partial = integers;
  for (std::size_t r = 0; r < field.stored_rows(); ++r)
    for (int j = 0; j < field.terms; ++j)
      if (!some_terms[std::size_t(field.cluster[r]) * field.terms + j])
        partial[r * field.terms + j] = 0;
  const std::vector<std::uint16_t> fewer = predict_weights(field, partial, some_terms);
  EXPECT_EQ(fewer.size(), stored_weight_count(field, some_terms));
  EXPECT_LT(fewer.size(), integers.size());
  EXPECT_EQ(unpredict_weights(field, fewer, some_terms), partial);
  EXPECT_THROW(unpredict_weights(field, fewer, every_term), Error);
  // Smooth planes predict well: constant weights leave errors of 0 past the first row.
  std::fill(integers.begin(), integers.end(), 1234);
  const std::vector<std::uint16_t> errors = predict_weights(field, integers, every_term);
  std::size_t zero = 0;
  for (std::uint16_t e : errors) zero += e == 0;
  EXPECT_GT(zero, errors.size() * 3 / 4);
}

TEST(QuantizedContainer, RoundTripsBitForBitAndIsSmaller) {
  TempDir dir;
  CompressedField field = sample_field();
  align_cluster_bases(field);
  const CompressedField q = quantize_values(field, {0.002f, 0.004f, 10});
  write_container(dir / "f.relume", field);
  write_container(dir / "q.relume", q);
  ContainerOptions stored;
  const CompressedField back = read_container(dir / "q.relume", &stored);
  EXPECT_EQ(stored.weights, ValuePrecision::quantized);
  EXPECT_EQ(stored.residual, ValuePrecision::quantized);
  EXPECT_EQ(back.quantization.basis_bits, 10);
  EXPECT_EQ(back.quantization.basis_scales, q.quantization.basis_scales);
  EXPECT_EQ(back.quantization.weight_step, q.quantization.weight_step);
  EXPECT_EQ(back.bases, q.bases);
  EXPECT_EQ(back.residual.values, q.residual.values);
  EXPECT_EQ(back.residual.light_index, q.residual.light_index);
  for (Eigen::Index i = 0; i < q.weights.size(); ++i)
    ASSERT_EQ(back.weights.data()[i], q.weights.data()[i]) << i;
  EXPECT_LT(describe_container(dir / "q.relume").file_bytes,
            describe_container(dir / "f.relume").file_bytes * 3 / 4);
}

TEST(FieldPsnr, MatchesADirectComputationAndIsInfiniteWhenExact) {
  CompressedField field = sample_field();
  const ReflectanceField exact = reconstruct_field(field);
  EXPECT_TRUE(std::isinf(psnr_8bit(exact, field).whole_frame));
  ReflectanceField shifted = exact;
  // Every value of light 0 two levels higher (where that stays within [0, 255]).
  double squared = 0, counted = 0;
  for (Eigen::Index p = 0; p < shifted.values.rows(); ++p) {
    const double level = std::round(std::clamp(exact.values(p, 0) * 255.0, 0.0, 255.0));
    shifted.values(p, 0) = float((level + 2) / 255.0);
    const double moved = std::round(std::clamp(double(shifted.values(p, 0)) * 255.0, 0.0, 255.0));
    squared += (moved - level) * (moved - level);
    ++counted;
  }
  const double mse = squared / counted / field.lights;  // light 0 only; the others are exact
  EXPECT_NEAR(psnr_8bit(shifted, field).whole_frame, 20 * std::log10(255.0) - 10 * std::log10(mse),
              1e-9);
  EXPECT_THAT(error_message([&] { psnr_8bit(exact, field, 0.0); }), HasSubstr("white level"));
}

// The 8-bit levels are std::round's of the clamped values, also at and next to the halves, below
// 0 and above 255: each value against 0 adds the square of its level, as std::round counts it.
TEST(FieldPsnr, RoundsLikeStdRoundAtHalvesAndClampsOutOfRange) {
  const std::vector<float> values = {0.5f,
                                     std::nextafter(0.5f, 0.0f),
                                     std::nextafter(0.5f, 1.0f),
                                     1.5f,
                                     2.5f,
                                     std::nextafter(2.5f, 0.0f),
                                     127.49999f,
                                     254.5f,
                                     std::nextafter(254.5f, 0.0f),
                                     255.4f,
                                     300.0f,
                                     -0.4f,
                                     -7.0f,
                                     0.0f};
  const int lights = int(values.size());
  const std::vector<float> zero(values.size(), 0.0f);
  Psnr8Sums sums;
  sums.add(values.data(), zero.data(), lights, 1.0, true);
  for (int i = 0; i < lights; ++i) {
    const double level = std::round(std::clamp(double(values[std::size_t(i)]), 0.0, 255.0));
    EXPECT_EQ(sums.all[std::size_t(i)], level * level) << values[std::size_t(i)];
    EXPECT_EQ(sums.inside[std::size_t(i)], level * level) << values[std::size_t(i)];
  }
  EXPECT_EQ(sums.all[0], 1.0);  // 0.5 goes up
  EXPECT_EQ(sums.all[1], 0.0);  // just below it does not
}

// A rate search measures each point once for both figures: the same PSNR as psnr_8bit and the
// Eq. 16 error of relative_error over the mask (summed in other blocks: equal to rounding).
TEST(FieldPsnr, AndTheErrorInOnePassAreTheTwoMeasures) {
  RandomFieldShape shape;
  shape.width = 70;  // 70 x 40 x 3 functions: blocks of 4096 functions of both measures
  shape.height = 40;
  shape.lights = 16;
  shape.stored_fraction = 0.6;
  CompressedField field = random_compressed_field(shape);
  testing::add_dark_pixels(field);
  ReflectanceField original = reconstruct_field(field);
  for (Eigen::Index p = 0; p < original.values.rows(); ++p)
    original.values(p, p % shape.lights) += 0.01f * float(p % 5);
  std::vector<std::uint8_t> region(field.mask.size(), 1);
  for (std::size_t pixel = 0; pixel < region.size(); pixel += 3) region[pixel] = 0;
  const PsnrAndError both = psnr_8bit_and_error(original, field, 1.0, 3, 2, region);
  const Psnr8 psnr = psnr_8bit(original, field, 1.0, 3, 1, region);
  EXPECT_EQ(both.psnr.whole_frame, psnr.whole_frame);
  EXPECT_EQ(both.psnr.masked, psnr.masked);
  const RelativeError error = relative_error(original, field, true, 3, 1);
  ASSERT_GT(error.mean, 0);
  ASSERT_LT(error.functions_averaged + error.zero_energy_skipped, original.functions());  // masked
  EXPECT_NEAR(both.error.mean, error.mean, 1e-12 * error.mean);
  EXPECT_EQ(both.error.functions_averaged, error.functions_averaged);
  EXPECT_EQ(both.error.zero_energy_skipped, error.zero_energy_skipped);
}

// The PSNR of what the field does not store row by row: the stored rows' errors are left out,
// the dark pixels' and unstored functions' counted, so it bounds the field's own PSNR.
TEST(FieldPsnr, OfUnstoredCountsOnlyTheFunctionsWithoutStoredRows) {
  RandomFieldShape shape;
  shape.width = 12;
  shape.height = 9;
  shape.lights = 24;
  shape.stored_fraction = 0.4;  // a fifth of the pixels store no channel: half of them go dark
  CompressedField field = random_compressed_field(shape);
  testing::add_dark_pixels(field);
  ASSERT_FALSE(field.dark_pixels.empty());
  const ReflectanceField exact = reconstruct_field(field);
  ReflectanceField shifted = exact;
  const std::vector<std::int64_t> row_of = stored_row_of_function(field);
  double squared = 0;
  for (Eigen::Index p = 0; p < shifted.values.rows(); ++p) {
    // Stored functions three levels off at light 0, the others one level at light 1.
    const bool stored = row_of[std::size_t(p)] >= 0;
    const Eigen::Index light = stored ? 0 : 1;
    const double level = std::round(std::clamp(exact.values(p, light) * 255.0, 0.0, 255.0));
    const double target = level + (level >= 250 ? -1 : 1) * (stored ? 3 : 1);
    shifted.values(p, light) = float(target / 255.0);
    if (!stored) squared += (target - level) * (target - level);
  }
  ASSERT_GT(squared, 0);
  const double mse = squared / double(shifted.values.rows()) / field.lights;
  const double unstored = psnr_8bit_of_unstored(shifted, field).whole_frame;
  EXPECT_NEAR(unstored, 20 * std::log10(255.0) - 10 * std::log10(mse), 1e-9);
  EXPECT_LT(psnr_8bit(shifted, field).whole_frame, unstored - 1);
}

}  // namespace
}  // namespace relume
