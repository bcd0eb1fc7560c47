// Numerical extremes through the whole pipeline (compress, container, reconstruction, Eq. 16,
// CPU and OpenCL relighting): values from 1e-8 to 1e8 in one image, all-zero fields and rows,
// one light, one pixel, terms = lights - 1, an environment map with a sun of 1e6, and the OpenCL
// kernels' float accumulation against a double reference. No NaN or Inf may come out of finite
// input; what cannot be compressed (one light) is refused with an Error.
#include <cmath>
#include <random>
#include <relume/compress.hpp>
#include <relume/container.hpp>
#include <relume/error.hpp>
#include <relume/lighting.hpp>
#include <relume/relight.hpp>

#include "support/test_support.hpp"

namespace relume {
namespace {

// A width x height x 3 field of `lights` lights, values from `value(p, i)`, lights on a spiral.
template <typename Value>
ReflectanceField make_field(int width, int height, int lights, Value value) {
  ReflectanceField field;
  field.width = width;
  field.height = height;
  field.channels = 3;
  field.values.resize(std::int64_t(width) * height * 3, lights);
  for (std::int64_t p = 0; p < field.values.rows(); ++p)
    for (int i = 0; i < lights; ++i) field.values(p, i) = value(p, i);
  field.mask.assign(std::size_t(width) * height, 1);
  field.directions.resize(lights, 3);
  for (int i = 0; i < lights; ++i) {
    const double z = 1 - (i + 0.5) / lights, r = std::sqrt(1 - z * z), phi = 2.4 * i;
    field.directions.row(i) << float(r * std::cos(phi)), float(r * std::sin(phi)), float(z);
  }
  field.intensities = LightRgb::Ones(lights, 3);
  for (int i = 0; i < lights; ++i) field.image_names.push_back(std::to_string(i) + ".exr");
  return field;
}

CompressOptions small_options(int clusters, int terms) {
  CompressOptions options;
  options.clusters = clusters;
  options.terms = terms;
  options.iterations = 3;
  options.assign = "cpu";
  options.threads = 2;
  // The fields are exact, patterned without spatial coherence, so that no estimate tells them
  // from noise: no noise floor, every function stored.
  options.noise_floor = 0;
  return options;
}

void expect_all_finite(const CompressedField& c) {
  for (std::size_t v = 0; v < c.bases.size(); ++v) ASSERT_TRUE(std::isfinite(c.bases[v]));
  ASSERT_TRUE(c.weights.allFinite());
  for (float v : c.residual.values) ASSERT_TRUE(std::isfinite(v));
}

void expect_all_finite(const Image& image) {
  for (float v : image.pixels) ASSERT_TRUE(std::isfinite(v));
}

// Compresses, writes and reads back, reconstructs and relights; everything must be finite.
CompressedField round_trip(const ReflectanceField& field, const CompressOptions& options) {
  const CompressedField compressed = compress(field, options);
  expect_all_finite(compressed);
  testing::TempDir dir;
  write_container(dir / "f.relume", compressed);
  const CompressedField read = read_container(dir / "f.relume");
  const ReflectanceField back = reconstruct_field(read);
  EXPECT_TRUE(back.values.allFinite());
  const RelativeError error = relative_error(field, read, false);
  EXPECT_TRUE(std::isfinite(error.mean));
  const LightRgb light = LightRgb::Ones(field.lights(), 3);
  expect_all_finite(relight_compressed_reference(read, light));
  return read;
}

TEST(NumericalExtremes, ValuesFrom1eMinus8To1e8InOneImage) {
  std::mt19937 random(3);
  std::uniform_real_distribution<double> exponent(-8, 8);
  const ReflectanceField field = make_field(
      16, 12, 24, [&](std::int64_t, int) { return float(std::pow(10.0, exponent(random))); });
  const CompressedField read = round_trip(field, small_options(4, 3));
  EXPECT_GT(read.stored_rows(), 0u);
}

TEST(NumericalExtremes, AllZeroFieldAndZeroRows) {
  const ReflectanceField zero = make_field(8, 8, 12, [](std::int64_t, int) { return 0.0f; });
  const CompressedField read = round_trip(zero, small_options(2, 2));
  EXPECT_EQ(read.stored_rows(), 0u);  // nothing to store: relights to exactly 0
  const ReflectanceField half = make_field(8, 8, 12, [](std::int64_t p, int i) {
    return p % 2 ? 0.0f : 0.1f + 0.01f * float((p + i) % 7);
  });
  const CompressedField stored = round_trip(half, small_options(2, 2));
  EXPECT_EQ(stored.stored_rows(), std::size_t(half.functions() / 2));
}

TEST(NumericalExtremes, OneLightIsRefusedOnePixelAndTermsLightsMinusOneWork) {
  const ReflectanceField one_light =
      make_field(4, 4, 1, [](std::int64_t p, int) { return 0.1f * float(p % 5 + 1); });
  EXPECT_THROW(compress(one_light, small_options(1, 1)), Error);
  const ReflectanceField one_pixel =
      make_field(1, 1, 6, [](std::int64_t p, int i) { return 0.2f + 0.1f * float(p + i); });
  round_trip(one_pixel, small_options(1, 2));
  const ReflectanceField few_lights = make_field(
      6, 5, 4, [](std::int64_t p, int i) { return 0.05f + 0.01f * float((3 * p + 5 * i) % 11); });
  const CompressedField read = round_trip(few_lights, small_options(2, 3));  // terms = lights - 1
  EXPECT_EQ(read.terms, 3);
}

TEST(NumericalExtremes, SunOf1e6GivesFiniteLightAndImages) {
  SkyOptions sky;
  sky.width = 512;  // pixels of 0.7 degrees: the 2-degree sun covers several
  sky.sun_radiance = 1e6;
  const EnvironmentMap map =
      make_environment_map(render_sky(sky), EnvironmentLayout::latlong, "sun 1e6");
  ReflectanceField field = make_field(
      8, 6, 40, [](std::int64_t p, int i) { return 0.02f * float((p * 7 + i * 3) % 13); });
  // A light towards the sun (elevation 35, azimuth 30 degrees), so that its energy is not
  // "outside the light set".
  const double e = 35 * M_PI / 180, a = 30 * M_PI / 180;
  field.directions.row(0) << float(std::cos(e) * std::sin(a)), float(std::sin(e)),
      float(-std::cos(e) * std::cos(a));
  const LightVector light = integrate_light_vector(map, field.directions, 0, 2);
  ASSERT_TRUE(light.rgb.allFinite());
  EXPECT_GT(light.rgb.maxCoeff(), 1000.0f);  // the sun's energy (about 3800) arrived
  expect_all_finite(relight_field(field, light.rgb, 2));
  const CompressedField compressed = compress(field, small_options(2, 3));
  expect_all_finite(relight_compressed_reference(compressed, light.rgb));
}

TEST(NumericalExtremes, OpenClFloatAccumulationAgainstADoubleReference) {
  // 200 lights, values spanning 1e-4..1e4 and a light vector spanning 1e-3..1e6 (a sun): the
  // kernels accumulate in float; the reference in double. Each pixel may differ by a few float
  // roundings of the sum of |terms| (4 eps per accumulated term is generous), never more.
  std::mt19937 random(5);
  std::uniform_real_distribution<double> exponent(-4, 4);
  const ReflectanceField field = make_field(
      10, 8, 200, [&](std::int64_t, int) { return float(std::pow(10.0, exponent(random))); });
  const CompressedField compressed = compress(field, small_options(3, 4));
  LightRgb light(field.lights(), 3);
  for (int i = 0; i < field.lights(); ++i)
    for (int c = 0; c < 3; ++c) light(i, c) = i == 17 ? 1e6f : float(std::pow(10.0, -3 + (i % 7)));
  const Image reference = relight_compressed_reference(compressed, light);
  Image kernels;
  try {
    RelighterOptions raw;  // the kernels' own sums, as the reference has them
    raw.allow_negative = true;
    kernels = Relighter(compressed, raw).relight(light);
  } catch (const Error& e) {
    GTEST_SKIP() << "no OpenCL device: " << e.what();
  }
  expect_all_finite(kernels);
  // Bound per pixel: float epsilon x (sum over the terms of |w F I| + |E I|) x terms.
  const double eps = 1.1920929e-7;
  ReflectanceField back = reconstruct_field(compressed);
  for (std::size_t k = 0; k < reference.pixels.size(); ++k) {
    double magnitude = 0;
    const int c = int(k % 3);
    for (int i = 0; i < field.lights(); ++i)
      magnitude += std::abs(double(back.values(std::int64_t(k), i)) * light(i, c));
    const double bound = 4 * eps * (field.lights() + compressed.terms) * magnitude + 1e-30;
    EXPECT_LE(std::abs(double(kernels.pixels[k]) - double(reference.pixels[k])), bound) << k;
  }
}

}  // namespace
}  // namespace relume
