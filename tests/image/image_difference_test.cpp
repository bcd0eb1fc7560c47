// Tests of the image comparison behind `relume compare` and relight-sequence --compare: hand
// computed figures, the all-zero edge cases, refused inputs, and the command on real EXR files.
#include "image/image_difference.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <relume/error.hpp>
#include <relume/image.hpp>

#include "support/test_support.hpp"

namespace relume {
namespace {

Image two_by_one(float a, float b, float c, float d, float e, float f) {
  Image image(2, 1, 3);
  image.pixels = {a, b, c, d, e, f};
  return image;
}

TEST(ImageDifference, HandComputedFigures) {
  const Image reference = two_by_one(1, 2, 2, 0, 1, 0);  // sum r^2 = 10
  const Image image = two_by_one(1, 2, 1, -0.5f, 1, 3);  // differences 0 0 -1 -0.5 0 3
  const ImageDifference d = image_difference(image, reference);
  EXPECT_DOUBLE_EQ(d.relative_squared_error, (1 + 0.25 + 9) / 10.0);
  EXPECT_DOUBLE_EQ(d.max_abs_difference, 3);
  EXPECT_EQ(d.max_x, 1);
  EXPECT_EQ(d.max_y, 0);
  EXPECT_EQ(d.max_channel, 2);
  EXPECT_EQ(d.negative_values, 1u);
  EXPECT_EQ(d.values, 6u);
  EXPECT_EQ(image_difference(reference, reference).relative_squared_error, 0);
}

TEST(ImageDifference, AllZeroReference) {
  const Image zero = two_by_one(0, 0, 0, 0, 0, 0);
  EXPECT_EQ(image_difference(zero, zero).relative_squared_error, 0);
  EXPECT_EQ(image_difference(two_by_one(0, 0, 0, 0, 0, 1e-9f), zero).relative_squared_error, 1);
}

TEST(ImageDifference, RefusesOtherSizesAndNonFiniteValues) {
  const Image reference = two_by_one(1, 2, 2, 0, 1, 0);
  EXPECT_THAT(
      testing::error_message(
          [&] { image_difference(Image(3, 1, 3), reference, "a.exr", "b.exr"); }),
      ::testing::AllOf(::testing::HasSubstr("a.exr is 3x1"), ::testing::HasSubstr("b.exr is 2x1")));
  const Image nan = two_by_one(1, 2, 2, 0, NAN, 0);
  EXPECT_THAT(testing::error_message([&] { image_difference(nan, reference, "a.exr"); }),
              ::testing::AllOf(::testing::HasSubstr("a.exr: pixel (1, 0) channel 1"),
                               ::testing::HasSubstr("expected a finite value")));
}

TEST(CompareCommand, PrintsAndWritesTheFiguresOfTwoFiles) {
  testing::TempDir dir;
  write_image(dir / "image.exr", two_by_one(1, 2, 1, -0.5f, 1, 3));
  write_image(dir / "reference.exr", two_by_one(1, 2, 2, 0, 1, 0));
  auto result = testing::run_relume("compare '" + (dir / "image.exr").string() + "' '" +
                                    (dir / "reference.exr").string() + "' --json '" +
                                    (dir / "d.json").string() + "'");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("relative squared error 1.025"), std::string::npos) << result.output;
  std::ifstream in(dir / "d.json");
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_DOUBLE_EQ(report["relative_squared_error"].get<double>(), 1.025);
  EXPECT_DOUBLE_EQ(report["relative_l2_error"].get<double>(), std::sqrt(1.025));
  EXPECT_EQ(report["negative_values"], 1);
  EXPECT_EQ(report["max_at"]["channel"], 2);

  write_image(dir / "small.exr", Image(1, 1, 3));
  result = testing::run_relume("compare '" + (dir / "small.exr").string() + "' '" +
                               (dir / "reference.exr").string() + "' --json '" +
                               (dir / "bad.json").string() + "'");
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("small.exr is 1x1"), std::string::npos) << result.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.json"));
}

}  // namespace
}  // namespace relume
