// Tests of the dark model (issue 32): the noise deviation is estimated from the field; pixels whose
// every channel is, within that noise, a multiple of one dark shape get no stored rows and relight
// as their block's gain x the shape; compress, the container, reconstruction, the CPU reference
// and the OpenCL kernels all agree on it, and inconsistent dark sets are refused by name.
#include <cmath>
#include <limits>
#include <random>
#include <relume/container.hpp>
#include <relume/error.hpp>

#include "compress/cluster_model.hpp"
#include "compress/clustered_factorization.hpp"
#include "compress/noise_model.hpp"
#include "compress/rate_control.hpp"
#include "model/compressed_field_checks.hpp"
#include "opencl/runtime.hpp"
#include "relight/compressed_relight_reference.hpp"
#include "relight/opencl_relighter.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

using testing::error_message;
using ::testing::HasSubstr;

constexpr float noise_sigma = 0.002f;

bool in_disc(int x, int y) { return (x - 8) * (x - 8) + (y - 6) * (y - 6) < 16; }

// 16x12 pixels, 3 channels, 20 lights: a bright disc of glossy-ish functions on a background that
// is an ambient shape over the lights, vignetted (its gain grows with x), plus normal noise of
// deviation noise_sigma; one background pixel (0, 0) is constant in channel 1, no multiple of the
// shape.
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
  std::mt19937 random(7);
  std::normal_distribution<float> noise(0.0f, noise_sigma);
  for (int y = 0; y < field.height; ++y)
    for (int x = 0; x < field.width; ++x)
      for (int c = 0; c < 3; ++c)
        for (int i = 0; i < lights; ++i)
          field.values(field.function_index(x, y, c), i) =
              in_disc(x, y)
                  ? float(0.2 + 0.1 * c + 0.3 * std::max(0.0, std::cos(0.3 * i - x * 0.2)))
                  : float(0.02 * (1 + 0.02 * x) * (1 + 0.5 * std::sin(0.7 * i))) + noise(random);
  for (int i = 0; i < lights; ++i) field.values(field.function_index(0, 0, 1), i) = 0.05f;
  return field;
}

std::size_t disc_pixels(const ReflectanceField& field) {
  std::size_t disc = 0;
  for (int y = 0; y < field.height; ++y)
    for (int x = 0; x < field.width; ++x) disc += in_disc(x, y);
  return disc;
}

TEST(NoiseModel, EstimatesTheDeviationOfNormalNoiseOnATexturedImage) {
  // A smooth gradient and a sharp vertical edge under noise of a known deviation per channel.
  ReflectanceField field;
  field.width = 64;
  field.height = 48;
  field.channels = 3;
  const int lights = 8;
  field.values.resize(field.pixels() * 3, lights);
  field.directions = LightDirections::Zero(lights, 3);
  field.directions.col(2).setOnes();
  field.intensities = LightRgb::Ones(lights, 3);
  std::mt19937 random(3);
  const float sigma[3] = {0.001f, 0.004f, 0.02f};
  for (int c = 0; c < 3; ++c) {
    std::normal_distribution<float> noise(0.0f, sigma[c]);
    for (int y = 0; y < field.height; ++y)
      for (int x = 0; x < field.width; ++x)
        for (int i = 0; i < lights; ++i)
          field.values(field.function_index(x, y, c), i) =
              float(0.1 + 0.005 * x + 0.01 * i + (x > 31 ? 0.5 : 0.0)) + noise(random);
  }
  const NoiseModel model = estimate_noise(field, 2);
  ASSERT_EQ(model.sigma.size(), 3u);
  for (int c = 0; c < 3; ++c) {
    EXPECT_NEAR(model.sigma[c], sigma[c], 0.1 * sigma[c]) << "channel " << c;
    EXPECT_FLOAT_EQ(model.threshold[c], dark_threshold_sigmas * model.sigma[c]);
  }
  EXPECT_TRUE(model.estimated);
  // Quantized input: never below the rounding's own noise.
  field.values.setConstant(0.25f);
  field.noise_floor = 1.0f / 255;
  const NoiseModel flat = estimate_noise(field, 2);
  for (int c = 0; c < 3; ++c) EXPECT_FLOAT_EQ(flat.sigma[c], float(1.0 / 255 / std::sqrt(12.0)));
  // Non-finite input is refused by name before anything is estimated.
  field.values(5, 2) = std::nanf("");
  EXPECT_THAT(error_message([&] { estimate_noise(field, 1); }), HasSubstr("non-finite value nan"));
  field.values(5, 2) = std::numeric_limits<float>::infinity();
  EXPECT_THAT(error_message([&] { estimate_noise(field, 1); }), HasSubstr("non-finite value inf"));
  field.values(5, 2) = -std::numeric_limits<float>::infinity();
  EXPECT_THAT(error_message([&] { estimate_noise(field, 1); }), HasSubstr("non-finite value -inf"));
  // The largest finite value is accepted.
  field.values(5, 2) = std::numeric_limits<float>::max();
  EXPECT_NO_THROW(check_finite_values(field));
}

TEST(DarkModel, BackgroundPixelsAreGainTimesTheDarkShapeAndGetNoRows) {
  const ReflectanceField field = disc_on_dark_background();
  const NoiseModel noise = estimate_noise(field, 1);
  for (float sigma : noise.sigma) EXPECT_NEAR(sigma, noise_sigma, 0.25 * noise_sigma);
  const PreparedRows prepared = prepare_rows(field, false, noise, 1);
  const std::size_t disc = disc_pixels(field);
  EXPECT_EQ(prepared.dark_pixels.size(), std::size_t(field.pixels()) - disc - 1);
  EXPECT_EQ(prepared.functions.size(), (disc + 1) * 3);
  EXPECT_EQ(prepared.dark_pixels.front(), 1u) << "pixel 0 is no multiple of the shape";
  ASSERT_EQ(prepared.dark.size(), std::size_t(3 * field.lights()));
  ASSERT_EQ(prepared.dark_gains.size(), prepared.dark_pixels.size() * 3);
  // The gains follow the vignetting: the right blocks' gains are larger than the left ones'.
  const auto gain_at = [&](std::uint32_t pixel) {
    const auto at =
        std::lower_bound(prepared.dark_pixels.begin(), prepared.dark_pixels.end(), pixel);
    return prepared.dark_gains[std::size_t(at - prepared.dark_pixels.begin()) * 3];
  };
  EXPECT_GT(gain_at(15), gain_at(1) * 1.08f);
  for (float gain : prepared.dark_gains)
    EXPECT_NEAR(gain / prepared.dark_gain_step, std::round(gain / prepared.dark_gain_step), 1e-3);
  // A floor of zero: no pixel is dark, every non-zero function is stored.
  EXPECT_TRUE(prepare_rows(field, false, noise_floor_model(field, 0), 1).dark_pixels.empty());
}

TEST(DarkModel, CompressReconstructsStoresAndRelightsDarkPixelsAsGainTimesShape) {
  const ReflectanceField field = disc_on_dark_background();
  CompressionOptions options;
  options.clustering.clusters = 2;
  options.clustering.terms = 2;
  options.clustering.quiet = true;
  options.residual = ResidualBudget{3};
  CompressionStats stats;
  const CompressedField compressed = compress_field(field, options, stats);
  EXPECT_TRUE(stats.noise.estimated);
  EXPECT_EQ(stats.dark_pixels, compressed.dark_pixels.size());
  EXPECT_EQ(compressed.dark_pixels.size(), std::size_t(field.pixels()) - disc_pixels(field) - 1);
  ASSERT_EQ(compressed.dark_gains.size(), compressed.dark_pixels.size() * 3);
  validate_compressed_field(compressed, "dark");
  // The residual threshold follows the noise unless set: no entry at or below it.
  EXPECT_GT(stats.residual_threshold, 0.5f * residual_threshold_sigmas * noise_sigma);
  EXPECT_LT(stats.residual_threshold, 2.0f * residual_threshold_sigmas * noise_sigma);
  for (float v : compressed.residual.values) EXPECT_GT(std::abs(v), stats.residual_threshold);

  const ReflectanceField back = reconstruct_field(compressed);
  double background_error = 0;
  for (std::size_t d = 0; d < compressed.dark_pixels.size(); ++d) {
    const std::uint32_t q = compressed.dark_pixels[d];
    for (int c = 0; c < 3; ++c)
      for (int i = 0; i < field.lights(); ++i) {
        EXPECT_FLOAT_EQ(
            back.values(q * 3 + c, i),
            dark_gain(compressed, d, c) * compressed.dark[std::size_t(c) * field.lights() + i]);
        background_error += std::pow(back.values(q * 3 + c, i) - field.values(q * 3 + c, i), 2);
      }
  }
  // The background is kept to its noise: the RMS of what the model leaves is about one deviation.
  EXPECT_LT(std::sqrt(background_error / (compressed.dark_pixels.size() * 3.0 * field.lights())),
            1.3 * noise_sigma);

  testing::TempDir dir;
  write_container(dir / "d.relume", compressed);
  const CompressedField read = read_container(dir / "d.relume");
  EXPECT_EQ(read.dark_pixels, compressed.dark_pixels);
  EXPECT_EQ(read.dark, compressed.dark);
  EXPECT_EQ(read.dark_gains, compressed.dark_gains);
  EXPECT_EQ(read.dark_gain_step, compressed.dark_gain_step);

  OpenClContext context(select_opencl_device("portable computing language"));
  OpenClRelighter relighter(context, read);
  LightRgb light = LightRgb::Zero(field.lights(), 3);
  for (int i = 0; i < field.lights(); ++i) light.row(i) << 0.5f + 0.1f * i, 1.0f, 2.0f - 0.05f * i;
  const Image expected = relight_compressed_reference(read, light);
  const Image image = relighter.relight(light);
  for (std::size_t p = 0; p < expected.pixels.size(); ++p)
    ASSERT_NEAR(image.pixels[p], expected.pixels[p], 1e-5 * (1 + std::abs(expected.pixels[p])))
        << "function " << p;
  const std::size_t d = read.dark_pixels.size() - 1;
  const std::uint32_t q = read.dark_pixels[d];
  double dark_value = 0;
  for (int i = 0; i < field.lights(); ++i)
    dark_value += read.dark[field.lights() + i] * light(i, 1);
  dark_value *= dark_gain(read, d, 1);
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
  CompressionStats stats;
  const CompressedField good = compress_field(field, options, stats);
  ASSERT_FALSE(good.dark_gains.empty());
  CompressedField bad = good;
  bad.dark.pop_back();
  EXPECT_THAT(error_message([&] { validate_compressed_field(bad, "f"); }),
              HasSubstr("dark values, expected 60"));
  bad = good;
  bad.dark_gains.pop_back();
  EXPECT_THAT(error_message([&] { validate_compressed_field(bad, "f"); }), HasSubstr("dark gains"));
  bad = good;
  bad.dark_gains[4] = -1;
  EXPECT_THAT(error_message([&] { validate_compressed_field(bad, "f"); }), HasSubstr("dark gain"));
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

// A byte target with room to code the background's noise: the one basis gets past the PSNR that
// the dark pixels' error leaves any clustered pair (known from the prepared rows, before any
// factoring), so no pair is factored, and the clustered pairs alone under the same target indeed
// reach less.
TEST(DarkModel, AByteTargetFactorsNoPairThatTheDarkPixelsKeepBehindTheOneBasis) {
  const ReflectanceField field = disc_on_dark_background();
  CompressionOptions options;
  options.clustering.quiet = true;
  RateTarget target;
  target.bytes = 30000;  // of 46,080 as float32
  target.region.assign(std::size_t(field.pixels()), 1);
  CompressionStats stats;
  const TargetSearch both =
      compress_to_rate_target(field, options, target, ContainerOptions{}, nullptr, stats);
  ASSERT_TRUE(both.explanation["met"].get<bool>()) << both.explanation.dump();
  EXPECT_EQ(both.field.clusters, 1);
  EXPECT_FALSE(both.field.coded_weights.empty());
  std::size_t factored = 0, kept_behind = 0;
  for (const auto& tried : both.explanation["tried"]) factored += tried["model"] == "clustered";
  for (const auto& pair : both.explanation["not_factored"])
    kept_behind += pair["why"].get<std::string>().find("dark pixels") != std::string::npos;
  EXPECT_EQ(factored, 0u) << both.explanation.dump();
  EXPECT_EQ(kept_behind, 9u) << both.explanation.dump();

  target.one_basis = false;
  const TargetSearch clustered =
      compress_to_rate_target(field, options, target, ContainerOptions{}, nullptr, stats);
  EXPECT_LT(clustered.explanation["chosen"]["point"]["psnr_8bit"].get<double>(),
            both.explanation["chosen"]["point"]["psnr_8bit"].get<double>());
}

}  // namespace
}  // namespace relume
