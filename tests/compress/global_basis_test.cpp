// The one-basis model's basis quantization (compress/global_basis.hpp): steps as coarse as keep
// the basis's error at basis_error_share of the truncation error or of the noise, finer for the
// strong terms, and the 12-bit steps of each term's largest value when nothing is truncated and
// no noise is known; and the basis refitted to the weights as their coding left them.
#include "compress/global_basis.hpp"

#include <gtest/gtest.h>

#include <Eigen/QR>
#include <cmath>

#include "container/weight_plane_coding.hpp"
#include "model/random_compressed_field.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

ReflectanceField sample_original(double noise = 0.01) {
  RandomFieldShape shape;
  shape.width = 40;
  shape.height = 32;
  shape.lights = 20;
  shape.clusters = 3;
  shape.terms = 3;
  shape.residual_per_function = 2;
  return testing::noisy_original(random_compressed_field(shape), noise);
}

// Mean squared difference per value between the field and W F over the stored functions.
double stored_error(const ReflectanceField& original, const CompressedField& field,
                    const Eigen::MatrixXd& basis) {
  double sum = 0;
  for (std::size_t r = 0; r < field.stored_function.size(); ++r) {
    const Eigen::RowVectorXd x = original.values.row(field.stored_function[r]).cast<double>();
    const Eigen::RowVectorXd w = field.weights.row(Eigen::Index(r)).cast<double>();
    sum += (x - w * basis).squaredNorm();
  }
  return sum / (double(field.stored_function.size()) * original.lights());
}

Eigen::MatrixXd stored_basis(const CompressedField& field) {
  Eigen::MatrixXd basis(field.terms, field.lights);
  for (int j = 0; j < field.terms; ++j)
    for (int i = 0; i < field.lights; ++i)
      basis(j, i) = field.bases[std::size_t(j) * field.lights + i];
  return basis;
}

// The largest integer of term j as stored.
double largest_integer(const CompressedField& field, int j) {
  double largest = 0;
  for (int i = 0; i < field.lights; ++i)
    largest = std::max(largest, std::abs(field.bases[std::size_t(j) * field.lights + i]) /
                                    double(field.quantization.basis_scales[std::size_t(j)]));
  return largest;
}

TEST(GlobalBasis, TheQuantizedBasisAddsAboutItsShareToTheTruncationError) {
  const ReflectanceField original = sample_original();
  const Eigen::MatrixXd directions = global_basis_directions(original, original.lights());
  const int terms = 12;  // past the 9 of the random clusters: the last terms are noise
  const CompressedField field = global_basis_field(original, directions, terms);
  ASSERT_EQ(field.quantization.basis_bits, global_basis_bits);
  const double truncation = stored_error(original, field, directions.topRows(terms));
  const double quantized = stored_error(original, field, stored_basis(field));
  ASSERT_GT(truncation, 0);
  EXPECT_GT(quantized, truncation * (1 + 0.3 * basis_error_share));
  EXPECT_LT(quantized, truncation * (1 + 3 * basis_error_share));
  // Far coarser than 12 bits where little weight rides on a term, finer on the strongest.
  const double twelve_bits = std::ldexp(1.0, global_basis_bits - 1) - 1;
  EXPECT_LT(largest_integer(field, terms - 1), twelve_bits / 8);
  EXPECT_GT(largest_integer(field, 0), 4 * largest_integer(field, terms - 1));
}

// The projections run in blocks spread over the threads: the field is the same for any count.
TEST(GlobalBasis, TheFieldIsTheSameForAnyThreadCount) {
  const ReflectanceField original = sample_original();
  const Eigen::MatrixXd directions = global_basis_directions(original, original.lights());
  const CompressedField one = global_basis_field(original, directions, 9, 1);
  const CompressedField two = global_basis_field(original, directions, 9, 2);
  EXPECT_EQ(one.weights, two.weights);
  EXPECT_EQ(one.bases, two.bases);
  EXPECT_EQ(one.quantization.basis_scales, two.quantization.basis_scales);
}

TEST(GlobalBasis, TheWholeBasisKeepsTwelveBitsOfEachTerm) {
  const ReflectanceField original = sample_original();
  const Eigen::MatrixXd directions = global_basis_directions(original, original.lights());
  const CompressedField field = global_basis_field(original, directions, original.lights());
  for (int j = 0; j < field.terms; ++j)
    EXPECT_NEAR(largest_integer(field, j), std::ldexp(1.0, global_basis_bits - 1) - 1, 1e-3);
  const double mean_square = original.values.cast<double>().squaredNorm() /
                             double(original.values.size());
  EXPECT_LT(stored_error(original, field, stored_basis(field)), 1e-6 * mean_square);
}

// Given the sensor noise, the whole basis (nothing truncated) is stored no finer than adds
// basis_error_share of the noise's energy: the coded weights' error is at least about the noise,
// so twelve bits a value would buy nothing (at 96 terms of 96 lights on the 8-bit ball, half the
// basis's bytes).
TEST(GlobalBasis, TheWholeBasisOfANoisyFieldAddsItsShareOfTheNoise) {
  const double noise = 0.01;
  const ReflectanceField original = sample_original(noise);
  const Eigen::MatrixXd directions = global_basis_directions(original, original.lights());
  const std::vector<float> sigma(std::size_t(original.channels), float(noise));
  const CompressedField field =
      global_basis_field(original, directions, original.lights(), 0, sigma);
  const double quantized = stored_error(original, field, stored_basis(field));
  EXPECT_GT(quantized, 0.3 * basis_error_share * noise * noise);
  EXPECT_LT(quantized, 3 * basis_error_share * noise * noise);
  const double twelve_bits = std::ldexp(1.0, global_basis_bits - 1) - 1;
  for (int j = 0; j < field.terms; ++j) EXPECT_LT(largest_integer(field, j), twelve_bits / 2);
}

// A field of 12 terms whose W is coded as JPEG 2000 planes in few bytes: far from its projection.
// (Refit tests use a field with little noise, where the coding's error is most of the error.)
CompressedField coarsely_coded(const ReflectanceField& original) {
  const Eigen::MatrixXd directions = global_basis_directions(original, original.lights());
  CompressedField field = global_basis_field(original, directions, 12, 1);
  code_weights_as_planes(field, 10000, 1);
  return field;
}

// The least-squares basis for the field's W, solved here by the normal equations in double (the
// least-norm one: a term the coding zeroed has a zero row).
Eigen::MatrixXd least_squares_basis(const ReflectanceField& original,
                                    const CompressedField& field) {
  Eigen::MatrixXd gram = Eigen::MatrixXd::Zero(field.terms, field.terms);
  Eigen::MatrixXd cross = Eigen::MatrixXd::Zero(field.terms, field.lights);
  for (std::size_t r = 0; r < field.stored_function.size(); ++r) {
    const Eigen::VectorXd w = field.weights.row(Eigen::Index(r)).transpose().cast<double>();
    gram += w * w.transpose();
    cross += w * original.values.row(field.stored_function[r]).cast<double>();
  }
  return gram.completeOrthogonalDecomposition().solve(cross);
}

TEST(GlobalBasis, TheRefitBasisIsTheLeastSquaresBasisOfTheCodedWeightsQuantized) {
  const ReflectanceField original = sample_original(0.001);
  CompressedField field = coarsely_coded(original);
  const RowMatrixF coded_weights = field.weights;
  const double before = stored_error(original, field, stored_basis(field));
  const Eigen::MatrixXd best = least_squares_basis(original, field);
  const double least = stored_error(original, field, best);
  ASSERT_LT(least, 0.99 * before);  // the coding left room for the refit
  refit_global_basis(original, field, 1);
  EXPECT_EQ(field.weights, coded_weights);  // only the basis changes
  const double after = stored_error(original, field, stored_basis(field));
  EXPECT_GE(after, least);
  // Most of the way from the basis the weights were coded for to the least-squares one: what is
  // left is the basis's quantization.
  EXPECT_LT(after - least, 0.25 * (before - least));
  // Within a step of the least-squares basis, each term at its own step (where weights use it).
  const Eigen::MatrixXd stored = stored_basis(field);
  for (int j = 0; j < field.terms; ++j)
    if (field.weights.col(j).squaredNorm() > 0)
      EXPECT_LE((stored.row(j) - best.row(j)).cwiseAbs().maxCoeff(),
                0.5001 * field.quantization.basis_scales[std::size_t(j)] + 1e-6)
          << "term " << j;
}

TEST(GlobalBasis, TheRefitIsTheSameForAnyThreadCount) {
  const ReflectanceField original = sample_original();
  CompressedField one = coarsely_coded(original), two = one;
  refit_global_basis(original, one, 1);
  refit_global_basis(original, two, 2);
  EXPECT_EQ(one.bases, two.bases);
  EXPECT_EQ(one.quantization.basis_scales, two.quantization.basis_scales);
}

// A term whose weights the coding zeroed everywhere is not determined by the fit: it keeps the
// basis it was coded for, finite, and the error is still lowered.
TEST(GlobalBasis, ARefitTermWithNoWeightKeepsItsBasis) {
  const ReflectanceField original = sample_original();
  CompressedField field = coarsely_coded(original);
  ASSERT_GT(field.weights.col(3).squaredNorm(), 0);
  field.weights.col(3).setZero();
  const Eigen::MatrixXd coded_for = stored_basis(field);
  const double before = stored_error(original, field, coded_for);
  refit_global_basis(original, field, 1);
  const Eigen::MatrixXd refit = stored_basis(field);
  ASSERT_TRUE(refit.allFinite());
  EXPECT_LE((refit.row(3) - coded_for.row(3)).cwiseAbs().maxCoeff(),
            0.5001 * field.quantization.basis_scales[3] + 1e-6);
  EXPECT_LT(stored_error(original, field, refit), before);
}

}  // namespace
}  // namespace relume
