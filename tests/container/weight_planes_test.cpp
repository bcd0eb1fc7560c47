// The weights stored as JPEG 2000 planes: the plane coder alone (byte bounds, exact decoding,
// refusals), the colour transforms between W and the planes (fixed, and each term's principal
// axes), and the container's weight_planes and weight_colour sections (round trip, what a reader
// and a writer refuse).
#include "model/weight_planes.hpp"

#include <gtest/gtest.h>

#include <Eigen/LU>
#include <array>
#include <cmath>
#include <cstring>
#include <relume/container.hpp>
#include <relume/error.hpp>

#include "container/jpeg2000_planes.hpp"
#include "container/weight_plane_coding.hpp"
#include "core/atomic_file.hpp"
#include "model/random_compressed_field.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

using testing::error_message;

// Smooth planes with some texture: plane c is a tilted sinusoid of its own frequency.
IntegerPlanes smooth_planes(int width, int height, int count) {
  IntegerPlanes planes{width, height, count, {}};
  for (int c = 0; c < count; ++c)
    for (int y = 0; y < height; ++y)
      for (int x = 0; x < width; ++x)
        planes.samples.push_back(std::int32_t(
            std::lround(12000 * std::sin(0.05 * (c + 1) * x + 0.03 * y) + 300 * c)));
  return planes;
}

double rms_difference(const IntegerPlanes& a, const IntegerPlanes& b) {
  double sum = 0;
  for (std::size_t i = 0; i < a.samples.size(); ++i)
    sum += std::pow(double(a.samples[i]) - b.samples[i], 2);
  return std::sqrt(sum / double(a.samples.size()));
}

TEST(Jpeg2000Planes, CodestreamsStayWithinTheirBoundAndErrShrinkWithBytes) {
  const IntegerPlanes planes = smooth_planes(96, 80, 6);
  // Every coding pass of every code block: the most bytes these planes can use.
  const std::size_t all_passes = encode_jpeg2000_planes(planes, 1u << 30, 1).size();
  double previous_error = HUGE_VAL;
  for (const std::uint64_t bound : {all_passes / 8, all_passes / 3, all_passes - 100}) {
    const std::vector<std::uint8_t> coded = encode_jpeg2000_planes(planes, bound, 1);
    EXPECT_LE(coded.size(), bound);
    EXPECT_GE(coded.size(), 0.98 * double(bound)) << "the rate allocation left bytes unused";
    const IntegerPlanes back =
        decode_jpeg2000_planes(coded.data(), coded.size(), 96, 80, 6, 1, "test");
    const double error = rms_difference(planes, back);
    EXPECT_LT(error, previous_error) << bound << " bytes";
    previous_error = error;
  }
  EXPECT_LT(previous_error, 20.0);  // of samples up to 13500
}

TEST(Jpeg2000Planes, DecodingIsTheSameEveryTimeAndForAnyThreads) {
  const IntegerPlanes planes = smooth_planes(64, 48, 4);
  const std::vector<std::uint8_t> coded = encode_jpeg2000_planes(planes, 3000, 2);
  const IntegerPlanes one = decode_jpeg2000_planes(coded.data(), coded.size(), 64, 48, 4, 1, "t");
  const IntegerPlanes two = decode_jpeg2000_planes(coded.data(), coded.size(), 64, 48, 4, 2, "t");
  EXPECT_EQ(one.samples, two.samples);
}

TEST(Jpeg2000Planes, OtherShapesAndDamagedCodestreamsAreRefused) {
  const IntegerPlanes planes = smooth_planes(40, 30, 3);
  std::vector<std::uint8_t> coded = encode_jpeg2000_planes(planes, 2000, 1);
  const auto decode_error = [&](int width, int height, int count) {
    return error_message([&] {
      decode_jpeg2000_planes(coded.data(), coded.size(), width, height, count, 1, "section 'x'");
    });
  };
  EXPECT_NE(decode_error(40, 30, 4).find("section 'x': the codestream holds 3 planes of 40x30, "
                                         "expected 4 signed 16-bit planes of 40x30"),
            std::string::npos);
  EXPECT_NE(decode_error(41, 30, 3).find("expected 3 signed 16-bit planes of 41x30"),
            std::string::npos);
  std::vector<std::uint8_t> garbage(100, 0x5a);
  EXPECT_NE(error_message([&] {
              decode_jpeg2000_planes(garbage.data(), garbage.size(), 40, 30, 3, 1, "s");
            }).find("s: not a JPEG 2000 codestream"),
            std::string::npos);
  coded.resize(coded.size() / 2);  // strict mode: a truncated codestream is an error
  EXPECT_NE(decode_error(40, 30, 3).find("s"), std::string::npos);
  EXPECT_NE(decode_error(40, 30, 3).find("does not decode"), std::string::npos);
}

// A field of one basis whose weights are smooth images: 20 x 16 pixels, 3 channels, 12 lights,
// 4 terms, every function stored (function p is stored row p); its W coded as planes.
CompressedField planes_field(std::uint64_t plane_bytes) {
  RandomFieldShape shape;
  shape.width = 20;
  shape.height = 16;
  shape.channels = 3;
  shape.lights = 12;
  shape.clusters = 1;
  shape.terms = 4;
  shape.residual_per_function = 2;
  shape.stored_fraction = 1.0;
  CompressedField field = random_compressed_field(shape);
  for (std::size_t r = 0; r < field.stored_rows(); ++r) {
    const std::uint32_t p = field.stored_function[r];
    const int x = int(p / 3) % 20, y = int(p / 3) / 20, c = int(p % 3);
    for (int j = 0; j < 4; ++j)
      field.weights(Eigen::Index(r), j) = float(std::cos(0.2 * x * (j + 1) + 0.1 * y) + 0.3 * c);
  }
  code_weights_as_planes(field, plane_bytes, 1);
  return field;
}

TEST(WeightPlanes, TheColourTransformIsOrthonormalAndExactBothWays) {
  CompressedField field = planes_field(1u << 20);
  const RowMatrixF before = field.weights;
  const std::vector<float> planes = weight_planes(field);
  double weight_energy = before.cast<double>().squaredNorm(), plane_energy = 0;
  for (const float v : planes) plane_energy += double(v) * v;
  EXPECT_NEAR(plane_energy, weight_energy, 1e-5 * weight_energy);  // orthonormal
  // Back from the planes as integers of one step: within a step of each weight.
  const QuantizedWeightPlanes quantized = quantize_weight_planes(field);
  set_weights_from_integer_planes(field, quantized.planes.samples, quantized.step);
  EXPECT_LT((field.weights - before).cwiseAbs().maxCoeff(), quantized.step);
  // Luma is the channels' sum over sqrt(3): pixel 5, term 0.
  const std::size_t area = 20 * 16;
  EXPECT_NEAR(planes[5], (before(15, 0) + before(16, 0) + before(17, 0)) / std::sqrt(3.0f), 1e-5);
  EXPECT_NEAR(planes[4 * area + 5], (before(15, 0) - before(16, 0)) / std::sqrt(2.0f), 1e-5);
}

// Term j's three channels are colour_j times one smooth image: the principal axes put each term
// in its first plane to within the angles' rounding, where the fixed transform spreads the
// coloured terms over all three.
TEST(WeightPlanes, EachTermsPrincipalColourAxesTakeNearlyAllOfItInItsFirstPlane) {
  CompressedField field = planes_field(1u << 20);
  field.coded_weights = {};
  const double colours[3][3] = {{0.9, 0.5, 0.2}, {1.0, 1.0, 1.0}, {0.1, 0.3, 1.0}};
  field.terms = 3;
  field.weights.conservativeResize(Eigen::NoChange, 3);
  for (std::size_t r = 0; r < field.stored_rows(); ++r) {
    const std::uint32_t p = field.stored_function[r];
    const int x = int(p / 3) % 20, y = int(p / 3) / 20, c = int(p % 3);
    for (int j = 0; j < 3; ++j)
      field.weights(Eigen::Index(r), j) =
          float(colours[j][c] * (1.5 + std::sin(0.3 * x + 0.2 * y * (j + 1))));
  }
  const auto off_first_plane_share = [&](int j) {
    const std::vector<float> planes = weight_planes(field);
    const std::size_t area = 20 * 16;
    double first = 0, other = 0;
    for (int a = 0; a < 3; ++a)
      for (std::size_t q = 0; q < area; ++q)
        (a == 0 ? first : other) +=
            std::pow(double(planes[(std::size_t(a) * 3 + std::size_t(j)) * area + q]), 2);
    return other / (first + other);
  };
  EXPECT_GT(off_first_plane_share(0), 0.03);  // the fixed transform: luma, R - G, R + G - 2B
  EXPECT_GT(off_first_plane_share(2), 0.3);
  EXPECT_LT(off_first_plane_share(1), 1e-12);  // a grey term is all luma
  field.coded_weights.colour_angles = principal_colour_angles(field);
  ASSERT_EQ(field.coded_weights.colour_angles.size(), 9u);
  for (int j = 0; j < 3; ++j) EXPECT_LT(off_first_plane_share(j), 1e-7) << "term " << j;
  // Still orthonormal, and back from the planes within a step of each weight.
  const RowMatrixF before = field.weights;
  const QuantizedWeightPlanes quantized = quantize_weight_planes(field);
  set_weights_from_integer_planes(field, quantized.planes.samples, quantized.step);
  EXPECT_LT((field.weights - before).cwiseAbs().maxCoeff(), quantized.step);
}

// Other channel counts have no colour transform: component a is channel a, in every term.
TEST(WeightPlanes, FieldsOfOneOrFourChannelsKeepTheirChannelsAsPlanes) {
  for (const int channels : {1, 4}) {
    const CompressedField field = random_compressed_field({.width = 6,
                                                           .height = 5,
                                                           .channels = channels,
                                                           .lights = 8,
                                                           .clusters = 1,
                                                           .terms = 2,
                                                           .residual_per_function = 2});
    EXPECT_TRUE(principal_colour_angles(field).empty());
    const std::vector<float> planes = weight_planes(field);
    ASSERT_EQ(planes.size(), std::size_t(channels) * 2 * 30);
    for (std::size_t r = 0; r < field.stored_rows(); ++r) {
      const std::uint32_t p = field.stored_function[r];
      const std::size_t pixel = p / std::uint32_t(channels), c = p % std::uint32_t(channels);
      for (std::size_t j = 0; j < 2; ++j)
        EXPECT_EQ(planes[(c * 2 + j) * 30 + pixel], field.weights(Eigen::Index(r), Eigen::Index(j)))
            << channels << " channels, row " << r;
    }
  }
}

TEST(WeightPlanes, ColourRotationsAreRotations) {
  for (const std::array<std::int16_t, 3> angles : {std::array<std::int16_t, 3>{0, 0, 0},
                                                   {32767, -32767, 12345},
                                                   {-20000, 16384, 7},
                                                   {100, -16384, -32767},
                                                   {-1, 1, 31000}}) {
    const auto r = colour_rotation(angles.data());
    Eigen::Matrix3d m;
    for (int a = 0; a < 3; ++a)
      for (int c = 0; c < 3; ++c) m(a, c) = r[std::size_t(a)][std::size_t(c)];
    EXPECT_LT((m * m.transpose() - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(), 1e-14);
    EXPECT_NEAR(m.determinant(), 1.0, 1e-14);
  }
}

// A rate search quantizes the planes once and codes them at several sizes: each size gives
// the codestream and W that coding the field whole gives.
TEST(WeightPlanes, PlanesQuantizedOnceCodeAsTheWholeFieldDoes) {
  const CompressedField field = planes_field(3000);
  const QuantizedWeightPlanes quantized = quantize_weight_planes(field);
  for (const std::uint64_t bytes : {1200u, 2500u}) {
    CompressedField whole = field, once = field;
    code_weights_as_planes(whole, bytes, 1);
    code_quantized_planes(once, quantized, bytes, 2);
    EXPECT_EQ(once.coded_weights.codestream, whole.coded_weights.codestream);
    EXPECT_EQ(once.coded_weights.step, whole.coded_weights.step);
    EXPECT_EQ(once.weights, whole.weights);
    EXPECT_NE(once.weights, field.weights);  // fewer bytes: other weights
  }
}

// planes_field with each term's principal colour axes, coded in `plane_bytes`.
CompressedField principal_planes_field(std::uint64_t plane_bytes) {
  CompressedField field = planes_field(1u << 20);
  field.coded_weights.colour_angles = principal_colour_angles(field);
  code_weights_as_planes(field, plane_bytes, 1);
  return field;
}

TEST(WeightPlanes, CodedWeightsRoundTripThroughTheContainerBitForBit) {
  testing::TempDir dir;
  const CompressedField field = principal_planes_field(3000);
  EXPECT_LE(field.coded_weights.codestream.size(), 3000u);
  write_container(dir.path() / "planes.relume", field);
  const ContainerLayout layout = describe_container(dir.path() / "planes.relume");
  EXPECT_EQ(layout.version, 6u);
  EXPECT_EQ(layout.section("weights").raw_bytes, 0u);
  EXPECT_EQ(layout.section("weight_planes").raw_bytes, field.coded_weights.codestream.size());
  EXPECT_EQ(layout.section("weight_colour").raw_bytes, 6u * 4);
  const CompressedField back = read_container(dir.path() / "planes.relume");
  EXPECT_EQ(back.coded_weights.codestream, field.coded_weights.codestream);
  EXPECT_EQ(back.coded_weights.step, field.coded_weights.step);
  EXPECT_EQ(back.coded_weights.colour_angles, field.coded_weights.colour_angles);
  ASSERT_EQ(back.weights.rows(), field.weights.rows());
  EXPECT_EQ(std::memcmp(back.weights.data(), field.weights.data(),
                        sizeof(float) * std::size_t(field.weights.size())),
            0);
  EXPECT_EQ(back.residual.values, field.residual.values);
  // Written again, the same bytes: the codestream is stored as it is.
  write_container(dir.path() / "again.relume", back);
  EXPECT_EQ(read_file(dir.path() / "again.relume"), read_file(dir.path() / "planes.relume"));
}

TEST(WeightPlanes, AnAlteredOrCutCodestreamOrColourIsRefusedNamingTheSection) {
  testing::TempDir dir;
  write_container(dir.path() / "planes.relume", principal_planes_field(3000));
  const std::string original = read_file(dir.path() / "planes.relume");
  for (const std::string name : {"weight_planes", "weight_colour"}) {
    const ContainerSection section = describe_container(dir.path() / "planes.relume").section(name);
    std::string altered = original;
    altered[section.offset + section.bytes / 2] ^= 0x5A;
    write_file_atomically(dir.path() / "altered.relume", altered);
    EXPECT_NE(error_message([&] {
                read_container(dir.path() / "altered.relume");
              }).find("section '" + name + "' is corrupt"),
              std::string::npos);
    write_file_atomically(dir.path() / "cut.relume", original.substr(0, section.offset + 1));
    EXPECT_NE(error_message([&] {
                read_container(dir.path() / "cut.relume");
              }).find("section '" + name + "'"),
              std::string::npos)
        << name;
  }
}

// Angles that are not 3 per term of a three-channel field's planes are refused before writing.
TEST(WeightPlanes, ColourAnglesThatDoNotFitTheFieldAreRefused) {
  testing::TempDir dir;
  CompressedField field = principal_planes_field(3000);
  field.coded_weights.colour_angles.pop_back();
  EXPECT_NE(error_message([&] {
              write_container(dir.path() / "x.relume", field);
            }).find("11 colour angles of the weight planes, expected none, or 3 per term"),
            std::string::npos);
  field = principal_planes_field(3000);
  field.coded_weights.colour_angles[4] = -32768;
  EXPECT_NE(error_message([&] {
              write_container(dir.path() / "x.relume", field);
            }).find("a colour angle of the weight planes is -32768"),
            std::string::npos);
}

TEST(WeightPlanes, AReaderRefusesPlanesThatDoNotMatchTheHeaderNamingTheSection) {
  testing::TempDir dir;
  // A codestream of other planes (5 terms) under a header of 4 terms.
  CompressedField field = planes_field(3000);
  CompressedField other = field;
  other.terms = 5;
  other.weights.conservativeResize(Eigen::NoChange, 5);
  other.weights.col(4).setConstant(0.5f);
  code_weights_as_planes(other, 3000, 1);
  field.coded_weights = other.coded_weights;
  write_container(dir.path() / "mismatch.relume", field);
  const std::string message =
      error_message([&] { read_container(dir.path() / "mismatch.relume"); });
  EXPECT_NE(message.find("section 'weight_planes': the codestream holds 15 planes of 20x16, "
                         "expected 12 signed 16-bit planes of 20x16"),
            std::string::npos)
      << message;
}

}  // namespace
}  // namespace relume
