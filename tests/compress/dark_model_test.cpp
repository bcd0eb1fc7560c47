// Tests of the dark model (the noise floor): pixels whose every channel is at the noise level get
// no stored rows and relight as their mean per channel; compress, the container, reconstruction,
// the CPU reference and the OpenCL kernels all agree on it, and inconsistent dark sets are
// refused by name.
#include <cmath>
#include <relume/container.hpp>
#include <relume/error.hpp>

#include "compress/cluster_model.hpp"
#include "compress/clustered_factorization.hpp"
#include "model/compressed_field_checks.hpp"
#include "opencl/runtime.hpp"
#include "relight/compressed_relight_reference.hpp"
#include "relight/opencl_relighter.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

using ::testing::HasSubstr;
using testing::error_message;

constexpr float floor_level = 0.01f;

// 16x12 pixels, 3 channels, 20 lights: a bright disc of glossy-ish functions on a background of
// small noise (RMS well below floor_level), with one background pixel brighter than the floor.
ReflectanceField disc_on_dark_background() {
  ReflectanceField field;
  field.width = 16;
  field.height = 12;
  field.channels = 3;
  const int lights = 20;
  field.values.resize(field.pixels() * 3, lights);
  field.directions.resize(lights, 3);
  for (int i = 0; i < lights; ++i) {
    const double angle = 0.3 * i;
    field.directions.row(i) << float(std::cos(angle) * 0.6), float(std::sin(angle) * 0.6), 0.8f;
  }
  field.directions.rowwise().normalize();
  field.intensities = LightRgb::Ones(lights, 3);
  field.mask.assign(std::size_t(field.pixels()), 1);
  std::uint32_t state = 7;
  auto noise = [&] {
    state = state * 1664525u + 1013904223u;
    return float(double(state >> 8) / double(1 << 24) - 0.5);
  };
  for (int y = 0; y < field.height; ++y)
    for (int x = 0; x < field.width; ++x) {
      const bool disc = (x - 8) * (x - 8) + (y - 6) * (y - 6) < 16;
      for (int c = 0; c < 3; ++c)
        for (int i = 0; i < lights; ++i)
          field.values(field.function_index(x, y, c), i) =
              disc ? float(0.2 + 0.1 * c + 0.3 * std::max(0.0, std::cos(0.3 * i - x * 0.2)))
                   : 0.004f + 0.006f * noise();
    }
  for (int i = 0; i < lights; ++i) field.values(field.function_index(0, 0, 1), i) = 0.05f;
  return field;
}

TEST(DarkModel, PixelsAtTheNoiseFloorShareTheirMeanAndGetNoRows) {
  const ReflectanceField field = disc_on_dark_background();
  const PreparedRows prepared = prepare_rows(field, false, floor_level, 1);
  std::size_t disc = 0;
  for (int y = 0; y < field.height; ++y)
    for (int x = 0; x < field.width; ++x) disc += (x - 8) * (x - 8) + (y - 6) * (y - 6) < 16;
  EXPECT_EQ(prepared.dark_pixels.size(), std::size_t(field.pixels()) - disc - 1);
  EXPECT_EQ(prepared.functions.size(), (disc + 1) * 3);
  EXPECT_EQ(prepared.dark_pixels.front(), 1u) << "pixel 0 has a channel above the floor";
  ASSERT_EQ(prepared.dark.size(), std::size_t(3 * field.lights()));
  double mean = 0;
  for (std::uint32_t q : prepared.dark_pixels) mean += field.values(q * 3 + 2, 5);
  EXPECT_NEAR(prepared.dark[2 * field.lights() + 5], mean / prepared.dark_pixels.size(), 1e-7);
  // No floor: every non-zero function is stored.
  EXPECT_TRUE(prepare_rows(field, false, 0.0f, 1).dark_pixels.empty());
}

TEST(DarkModel, CompressReconstructsStoresAndRelightsDarkPixelsAsTheirMean) {
  const ReflectanceField field = disc_on_dark_background();
  CompressionOptions options;
  options.clustering.clusters = 2;
  options.clustering.terms = 2;
  options.clustering.quiet = true;
  options.residual = ResidualBudget{3};
  options.noise_floor = floor_level;
  CompressionStats stats;
  const CompressedField compressed = compress_field(field, options, stats);
  EXPECT_EQ(stats.dark_pixels, compressed.dark_pixels.size());
  EXPECT_GT(compressed.dark_pixels.size(), 100u);
  validate_compressed_field(compressed, "dark");
  // The residual threshold follows the floor unless set: no entry at or below it.
  EXPECT_FLOAT_EQ(stats.residual_threshold, floor_level);
  for (float v : compressed.residual.values) EXPECT_GT(std::abs(v), floor_level);

  const ReflectanceField back = reconstruct_field(compressed);
  const std::uint32_t q = compressed.dark_pixels[10];
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < field.lights(); ++i)
      EXPECT_EQ(back.values(q * 3 + c, i), compressed.dark[std::size_t(c) * field.lights() + i]);
  // The background costs no more than its noise: its Eq. 16 error is the noise's share.
  EXPECT_LT(relative_error(field, compressed, true).mean, 0.3);

  testing::TempDir dir;
  write_container(dir / "d.relume", compressed);
  const CompressedField read = read_container(dir / "d.relume");
  EXPECT_EQ(read.dark_pixels, compressed.dark_pixels);
  EXPECT_EQ(read.dark, compressed.dark);

  OpenClContext context(select_opencl_device("portable computing language"));
  OpenClRelighter relighter(context, read);
  LightRgb light = LightRgb::Zero(field.lights(), 3);
  for (int i = 0; i < field.lights(); ++i) light.row(i) << 0.5f + 0.1f * i, 1.0f, 2.0f - 0.05f * i;
  const Image expected = relight_compressed_reference(read, light);
  const Image image = relighter.relight(light);
  for (std::size_t p = 0; p < expected.pixels.size(); ++p)
    ASSERT_NEAR(image.pixels[p], expected.pixels[p], 1e-5 * (1 + std::abs(expected.pixels[p])))
        << "function " << p;
  double dark_value = 0;
  for (int i = 0; i < field.lights(); ++i) dark_value += read.dark[field.lights() + i] * light(i, 1);
  EXPECT_NEAR(image.pixels[q * 3 + 1], dark_value, 1e-5);
  // Batched, and the residual term alone leaves the dark pixels at zero.
  const std::vector<Image> batch = relighter.relight_batch({light, light * 2.0f, light}, 2);
  EXPECT_NEAR(batch[1].pixels[q * 3 + 1], 2 * dark_value, 1e-5);
  EXPECT_EQ(relighter.relight_residual(light).pixels[q * 3 + 1], 0.0f);
}

TEST(DarkModel, InconsistentDarkSetsAreRefusedByName) {
  const ReflectanceField field = disc_on_dark_background();
  CompressionOptions options;
  options.clustering.clusters = 2;
  options.clustering.terms = 2;
  options.clustering.quiet = true;
  options.noise_floor = floor_level;
  CompressionStats stats;
  const CompressedField good = compress_field(field, options, stats);
  CompressedField bad = good;
  bad.dark.pop_back();
  EXPECT_THAT(error_message([&] { validate_compressed_field(bad, "f"); }),
              HasSubstr("dark values, expected 60"));
  bad = good;
  bad.dark_pixels.push_back(bad.dark_pixels.back());
  EXPECT_THAT(error_message([&] { validate_compressed_field(bad, "f"); }),
              HasSubstr("expected strictly ascending pixels"));
  bad = good;
  bad.dark_pixels.insert(bad.dark_pixels.begin(), bad.stored_function[0] / 3);
  EXPECT_THAT(error_message([&] { validate_compressed_field(bad, "f"); }),
              HasSubstr("expected a pixel to be stored or dark, not both"));
  bad = good;
  bad.mask[bad.dark_pixels[3]] = 0;
  EXPECT_THAT(error_message([&] { validate_compressed_field(bad, "f"); }),
              HasSubstr("lies outside the mask"));
}

}  // namespace
}  // namespace relume
