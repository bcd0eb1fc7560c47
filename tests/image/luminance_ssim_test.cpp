// Tests of the luminance SSIM behind `relume compare`: identical images score 1, constant images
// and a two-pixel image against hand computations, the mask, and refused inputs.
#include "image/luminance_ssim.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <relume/image.hpp>

#include "support/test_support.hpp"

namespace relume {
namespace {

Image grey(int width, int height, std::vector<float> values) {
  Image image(width, height, 1);
  image.pixels = std::move(values);
  return image;
}

TEST(LuminanceSsim, IdenticalImagesScoreOne) {
  Image image(20, 16, 3);
  std::mt19937 random(7);
  std::uniform_real_distribution<float> value(0, 4);
  for (float& v : image.pixels) v = value(random);
  const LuminanceSsim ssim = luminance_ssim(image, image);
  EXPECT_NEAR(ssim.mean, 1, 1e-12);
  EXPECT_NEAR(ssim.worst_1_percent, 1, 1e-12);
  EXPECT_NEAR(ssim.minimum, 1, 1e-12);
  EXPECT_EQ(ssim.windows, 20u * 16u);
}

TEST(LuminanceSsim, ConstantImagesCompareTheirMeans) {
  // The reference's white is 1 / 0.9: it shows as 0.9, the image as 0.45 (before sRGB). No
  // structure: SSIM = (2 a r + C1) / (a^2 + r^2 + C1), C1 = 0.01^2.
  const Image reference = grey(3, 3, std::vector<float>(9, 1.0f));
  const Image image = grey(3, 3, std::vector<float>(9, 0.5f));
  const double r = linear_to_srgb(0.9f), a = linear_to_srgb(0.45f);
  const double expected = (2 * a * r + 1e-4) / (a * a + r * r + 1e-4);
  const LuminanceSsim ssim = luminance_ssim(image, reference);
  EXPECT_NEAR(ssim.white, 1 / 0.9, 1e-7);
  EXPECT_NEAR(ssim.mean, expected, 1e-7);
  EXPECT_NEAR(ssim.worst_1_percent, expected, 1e-7);
}

TEST(LuminanceSsim, TwoSwappedPixelsAgainstAHandComputation) {
  // Reference (1, 0), image (0, 1): shown as (s, 0) and (0, s), s = sRGB(0.9). Each window weighs
  // its centre 1 and the other pixel e = exp(-1 / (2 1.5^2)), renormalised: w0 = 1 / (1 + e) on
  // the centre, w1 = e / (1 + e). Window 0: mu_a = w1 s, mu_r = w0 s, var_a = var_r = w0 w1 s^2,
  // cov = -w0 w1 s^2; window 1 mirrors it.
  const double e = std::exp(-1 / 4.5), w0 = 1 / (1 + e), w1 = e / (1 + e);
  const double s2 = std::pow(double(linear_to_srgb(0.9f)), 2), c1 = 1e-4, c2 = 9e-4;
  const double expected = (2 * w0 * w1 * s2 + c1) * (-2 * w0 * w1 * s2 + c2) /
                          (((w0 * w0 + w1 * w1) * s2 + c1) * (2 * w0 * w1 * s2 + c2));
  const LuminanceSsim ssim = luminance_ssim(grey(2, 1, {0, 1}), grey(2, 1, {1, 0}));
  EXPECT_NEAR(ssim.mean, expected, 1e-7);
  EXPECT_NEAR(ssim.minimum, expected, 1e-7);
  EXPECT_LT(ssim.mean, 0);  // anti-correlated
}

TEST(LuminanceSsim, HighlightsAboveTheWhiteClip) {
  // 200 pixels at 1 and one at 100: the white is 1 / 0.9, and the highlight shown at 50 instead
  // changes nothing a person sees.
  Image reference(201, 1, 1);
  for (float& v : reference.pixels) v = 1;
  reference.pixels[100] = 100;
  Image image = reference;
  image.pixels[100] = 50;
  EXPECT_NEAR(luminance_ssim(image, reference).minimum, 1, 1e-12);
}

TEST(LuminanceSsim, RgbIsComparedByItsLuminance) {
  // A change of colour at equal luminance is not a change of luminance.
  Image reference(1, 1, 3), image(1, 1, 3);
  reference.pixels = {0.5f, 0.5f, 0.5f};
  image.pixels = {0.5f + 0.7152f * 0.1f, 0.5f - 0.2126f * 0.1f, 0.5f};
  EXPECT_NEAR(luminance_ssim(image, reference).mean, 1, 1e-6);
}

TEST(LuminanceSsim, OnlyTheMaskCounts) {
  const Image reference = grey(4, 1, {1, 1, 0.2f, 0.9f});
  const Image image = grey(4, 1, {1, 1, 5, 0});
  const LuminanceSsim inside = luminance_ssim(image, reference, {1, 1, 0, 0});
  EXPECT_NEAR(inside.mean, 1, 1e-12);
  EXPECT_EQ(inside.windows, 2u);
  EXPECT_LT(luminance_ssim(image, reference).minimum, 0.5);
}

TEST(LuminanceSsim, RefusesImagesOfOtherSizes) {
  EXPECT_THAT(testing::error_message([] {
                luminance_ssim(Image(3, 1, 1), Image(2, 1, 1), {}, "relit.exr", "reference.exr");
              }),
              ::testing::AllOf(::testing::HasSubstr("relit.exr is 3x1"),
                               ::testing::HasSubstr("reference.exr is 2x1")));
}

}  // namespace
}  // namespace relume
