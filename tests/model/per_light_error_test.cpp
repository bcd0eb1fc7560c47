// Tests of the worst per-light errors of a compressed field (lib/model/per_light_error.hpp): hand
// computed figures on a three-pixel field, the mask, the residual cap and refused shapes.
#include "model/per_light_error.hpp"

#include <gtest/gtest.h>

#include <relume/error.hpp>

#include "support/test_support.hpp"

namespace relume {
namespace {

// 3x1 pixels, one channel, 3 lights, one cluster of one term F = (1, 0.5, -0.2). Pixel 0 has
// weight 2 and one residual entry 0.1 at light 2: R~ = (2, 1, -0.3); pixel 1 weight 1, no
// residual: R~ = (1, 0.5, -0.2); pixel 2 is not stored: R~ = 0.
CompressedField hand_field() {
  CompressedField field;
  field.width = 3;
  field.height = 1;
  field.channels = 1;
  field.lights = 3;
  field.terms = 1;
  field.clusters = 1;
  field.mask = {1, 1, 1};
  field.directions.resize(3, 3);
  field.directions << 0, 0, 1, 1, 0, 1, 0, 1, 1;
  field.intensities.setOnes(3, 3);
  field.stored_function = {0, 1};
  field.cluster = {0, 0};
  field.weights.resize(2, 1);
  field.weights << 2, 1;
  field.bases = {1, 0.5f, -0.2f};
  field.residual.row_offsets = {0, 1, 1};
  field.residual.light_index = {2};
  field.residual.values = {0.1f};
  return field;
}

// The original: pixel 0 (2, 1.2, 0), pixel 1 (0.8, 0.5, 0.1), pixel 2 all zero.
ReflectanceField hand_original() {
  ReflectanceField field;
  field.width = 3;
  field.height = 1;
  field.channels = 1;
  field.values.resize(3, 3);
  field.values << 2, 1.2f, 0, 0.8f, 0.5f, 0.1f, 0, 0, 0;
  return field;
}

TEST(PerLightError, HandComputedFigures) {
  const PerLightError e = per_light_error(hand_original(), hand_field(), false);
  // Pixel 0: errors (0, 0.2, 0.3) over peak 2 -> 0.15; pixel 1: (0.2, 0, 0.3) over 0.8 -> 0.375.
  EXPECT_NEAR(e.largest, 0.375, 1e-6);
  EXPECT_EQ(e.function, 1);
  EXPECT_EQ(e.light, 2);
  EXPECT_NEAR(e.mean_of_largest, (0.15 + 0.375) / 2, 1e-6);
  EXPECT_EQ(e.functions_measured, 2);
  EXPECT_EQ(e.zero_peak_skipped, 1);
  ASSERT_EQ(e.functions_above.size(), 3u);  // levels 0.05, 0.1, 0.25
  EXPECT_DOUBLE_EQ(e.functions_above[0], 1.0);
  EXPECT_DOUBLE_EQ(e.functions_above[1], 1.0);
  EXPECT_DOUBLE_EQ(e.functions_above[2], 0.5);
  // Light 2 of pixels 0 and 1 reconstructs below zero where the original is >= 0.
  EXPECT_EQ(e.negative_values, 2);
  EXPECT_EQ(e.values_measured, 9);
  EXPECT_NEAR(e.most_negative, -0.2 / 0.8, 1e-6);
}

TEST(PerLightError, MaskAndResidualCap) {
  CompressedField field = hand_field();
  field.mask = {1, 0, 1};  // pixel 1 outside: only pixel 0 is measured
  const PerLightError masked = per_light_error(hand_original(), field, true);
  EXPECT_NEAR(masked.largest, 0.15, 1e-6);
  EXPECT_EQ(masked.function, 0);
  EXPECT_EQ(masked.negative_values, 1);
  EXPECT_NEAR(masked.most_negative, -0.3 / 2, 1e-6);
  // Without its residual entry pixel 0 is (2, 1, -0.4): error 0.4 / 2 at light 2.
  const PerLightError capped = per_light_error(hand_original(), field, true, 0);
  EXPECT_NEAR(capped.largest, 0.2, 1e-6);
  EXPECT_NEAR(capped.most_negative, -0.2, 1e-6);
  // A residual that fixes the undershoot: no negative value left.
  field.residual.values = {0.4f};
  const PerLightError fixed = per_light_error(hand_original(), field, true);
  EXPECT_EQ(fixed.negative_values, 0);
  EXPECT_EQ(fixed.most_negative, 0);
  EXPECT_NEAR(fixed.largest, 0.1, 1e-6);  // light 1: 1.2 against 1
  EXPECT_EQ(fixed.light, 1);
}

TEST(PerLightError, RefusesOtherShapesAndBadCaps) {
  ReflectanceField other = hand_original();
  other.width = 1;
  other.height = 3;
  EXPECT_THAT(testing::error_message([&] { per_light_error(other, hand_field(), false); }),
              ::testing::HasSubstr("different shapes"));
  EXPECT_THAT(
      testing::error_message([&] { per_light_error(hand_original(), hand_field(), false, -2); }),
      ::testing::HasSubstr("residual cap -2"));
}

}  // namespace
}  // namespace relume
