// The non-negative projection of relume::Relighter (RelighterOptions::allow_negative): a field
// compressed from non-negative data and relit under a non-negative light has its negative values
// set to 0, on PoCL and with the CPU reference alike, and nothing else changes; signed light
// vectors, --allow-negative and fields not known to be non-negative keep every value. Also that
// compression marks the field and the container keeps the mark.
#include <gtest/gtest.h>

#include <cmath>
#include <relume/container.hpp>
#include <relume/relight.hpp>

#include "compress/clustered_factorization.hpp"
#include "model/random_compressed_field.hpp"
#include "support/test_support.hpp"
#include "synth/synthetic_scene.hpp"

namespace relume {
namespace {

RandomFieldShape shape() {
  RandomFieldShape shape;
  shape.width = 24;
  shape.height = 16;
  shape.lights = 19;
  shape.clusters = 3;
  shape.terms = 3;
  shape.residual_per_function = 4;
  shape.seed = 11;
  return shape;  // weights in [-1, 1]: the relit images have negative values
}

std::size_t negatives(const Image& image) {
  std::size_t count = 0;
  for (const float value : image.pixels) count += value < 0;
  return count;
}

class NonNegativeRelighting : public ::testing::TestWithParam<bool> {};  // CPU reference?

TEST_P(NonNegativeRelighting, SetsExactlyTheNegativeValuesToZero) {
  CompressedField field = random_compressed_field(shape());
  const LightRgb light = random_light_vector(field.lights, 5);
  RelighterOptions options;
  options.cpu_reference = GetParam();
  const Image raw = Relighter(field, options).relight(light);
  const std::size_t expected = negatives(raw);
  ASSERT_GT(expected, 10u);

  field.non_negative = true;
  Relighter projecting(field, options);
  const Image projected = projecting.relight(light);
  EXPECT_EQ(projecting.last_projected_values(), expected);
  EXPECT_EQ(negatives(projected), 0u);
  for (std::size_t i = 0; i < raw.pixels.size(); ++i)
    ASSERT_EQ(projected.pixels[i], raw.pixels[i] < 0 ? 0.0f : raw.pixels[i]) << "value " << i;

  // The batch form projects every frame the same way (its kernel sums in another order, so the
  // values agree to rounding, and none is negative).
  const std::vector<Image> batch = projecting.relight_batch({light, light});
  EXPECT_GT(projecting.last_projected_values(), 2 * expected * 9 / 10);
  for (const Image& image : batch) {
    EXPECT_EQ(negatives(image), 0u);
    for (std::size_t i = 0; i < image.pixels.size(); ++i)
      ASSERT_NEAR(image.pixels[i], projected.pixels[i], 1e-4f * (1 + std::fabs(raw.pixels[i])));
  }
}

TEST_P(NonNegativeRelighting, KeepsNegativesForSignedLightsAndWhenAllowed) {
  CompressedField field = random_compressed_field(shape());
  field.non_negative = true;
  LightRgb signed_light = random_light_vector(field.lights, 5);
  signed_light(3, 1) = -0.25f;  // a signed light vector (spherical harmonics, differences)
  RelighterOptions options;
  options.cpu_reference = GetParam();
  Relighter projecting(field, options);
  EXPECT_GT(negatives(projecting.relight(signed_light)), 0u);
  EXPECT_EQ(projecting.last_projected_values(), 0u);

  options.allow_negative = true;
  Relighter allowing(field, options);
  EXPECT_GT(negatives(allowing.relight(random_light_vector(field.lights, 5))), 0u);
  EXPECT_EQ(allowing.last_projected_values(), 0u);
}

INSTANTIATE_TEST_SUITE_P(Backends, NonNegativeRelighting, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& info) {
                           return std::string(info.param ? "cpu_reference" : "opencl");
                         });

TEST(NonNegativeMark, CompressionMarksNonNegativeDataAndTheContainerKeepsIt) {
  testing::TempDir dir;
  SynthOptions scene;
  scene.width = 24;
  scene.height = 16;
  scene.lights = 20;
  scene.samples_per_axis = 1;
  ReflectanceField field = render_synthetic_field(scene);
  ASSERT_TRUE((field.values.array() >= 0).all());
  CompressionOptions options;
  options.clustering.clusters = 2;
  options.clustering.terms = 2;
  CompressionStats stats;
  const CompressedField marked = compress_field(field, options, stats);
  EXPECT_TRUE(marked.non_negative);
  write_container(dir / "marked.relume", marked);
  EXPECT_TRUE(read_container(dir / "marked.relume").non_negative);

  field.values(0, 0) = -0.01f;
  const CompressedField signed_field = compress_field(field, options, stats);
  EXPECT_FALSE(signed_field.non_negative);
  write_container(dir / "signed.relume", signed_field);
  EXPECT_FALSE(read_container(dir / "signed.relume").non_negative);
}

}  // namespace
}  // namespace relume
