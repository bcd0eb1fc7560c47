// Tests of the black pixels, chroma outliers and channel sums behind `relume compare`, on crafted
// images whose counts are known.
#include "image/lit_pixel_faults.hpp"

#include <gtest/gtest.h>

#include <relume/image.hpp>

#include "support/test_support.hpp"

namespace relume {
namespace {

Image row_of(std::vector<float> values) {
  Image image(int(values.size() / 3), 1, 3);
  image.pixels = std::move(values);
  return image;
}

// Pixels 0 and 6 are the 99th percentile of the lit luminances: the white is 1 / 0.9; lit from
// 2/255 of it (luminance 0.0087), black below 1/255 (0.0044).
const Image reference = row_of({
    1,          1,          1,       // 0: the peak, kept
    0.5f,       0.5f,       0.5f,    // 1: goes black (clamped to 0)
    0.3f,       0.2f,       0.1f,    // 2: chromaticity (0.5, 0.33, 0.17) becomes (0.43, 0.43, 0.14)
    0.001f,     0.001f,     0.001f,  // 3: not lit, goes to 0 and does not count
    0.02f,      0.02f,      0.02f,   // 4: lit, relit at 0.5/255: black, and no colour change
    1.5f / 255, 1.5f / 255, 0,       // 5: not lit (luminance 1.39/255 of 1)
    1,          1,          1,       // 6: as pixel 0
});
// clang-format off
const Image relit = row_of({
    1, 1, 1,
    0, 0, 0,
    0.3f, 0.3f, 0.1f,
    0, 0, 0,
    0.5f / 255, 0.5f / 255, 0.5f / 255,
    0, 0, 0,
    1, 1, 1,
});
// clang-format on

TEST(LitPixelFaults, CountsCraftedBlackPixelsAndChromaOutliers) {
  const LitPixelFaults faults = lit_pixel_faults(relit, reference);
  EXPECT_NEAR(faults.white, 1 / 0.9, 1e-7);
  EXPECT_EQ(faults.lit_pixels, 5u);
  EXPECT_EQ(faults.black_pixels, 2u);
  ASSERT_EQ(faults.black_examples.size(), 2u);
  EXPECT_EQ(faults.black_examples[0].x, 1);
  EXPECT_EQ(faults.black_examples[1].x, 4);
  // Pixel 1 has no colour left (counts, difference 1), pixel 2 is 0.095 off in green.
  EXPECT_EQ(faults.chroma_outliers, 2u);
  EXPECT_DOUBLE_EQ(faults.largest_chroma_difference, 1);
  EXPECT_EQ(faults.largest_chroma_at.x, 1);
  const double red = 2 + 0.5 + 0.3 + 0.001 + 0.02 + 1.5 / 255;
  ASSERT_EQ(faults.channel_sum_ratio.size(), 3u);
  EXPECT_NEAR(*faults.channel_sum_ratio[0], (2 + 0.3 + 0.5 / 255) / red, 1e-6);
  EXPECT_NEAR(*faults.channel_sum_ratio[2], (2 + 0.1 + 0.5 / 255) / (2 + 0.5 + 0.1 + 0.001 + 0.02),
              1e-6);
}

TEST(LitPixelFaults, ChromaWithinTheToleranceAndTheMask) {
  // Pixel 2 alone, with green 0.22 instead of 0.2: chromaticity moves by 0.02 at most.
  const Image near = row_of({0.3f, 0.22f, 0.1f});
  const LitPixelFaults faults = lit_pixel_faults(near, row_of({0.3f, 0.2f, 0.1f}));
  EXPECT_EQ(faults.lit_pixels, 1u);
  EXPECT_EQ(faults.chroma_outliers, 0u);
  EXPECT_NEAR(faults.largest_chroma_difference, 0.22 / 0.62 - 0.2 / 0.6, 1e-6);
  // Inside a mask that holds only pixel 0, nothing is wrong.
  const LitPixelFaults masked = lit_pixel_faults(relit, reference, {1, 0, 0, 0, 0, 0, 0});
  EXPECT_EQ(masked.lit_pixels, 1u);
  EXPECT_EQ(masked.black_pixels, 0u);
  EXPECT_EQ(masked.chroma_outliers, 0u);
  EXPECT_DOUBLE_EQ(*masked.channel_sum_ratio[1], 1);
}

TEST(LitPixelFaults, ABlackReferenceHasNoLitPixels) {
  const LitPixelFaults faults = lit_pixel_faults(relit, row_of(std::vector<float>(21, 0.0f)));
  EXPECT_EQ(faults.lit_pixels, 0u);
  EXPECT_FALSE(faults.channel_sum_ratio[0].has_value());
}

}  // namespace
}  // namespace relume
