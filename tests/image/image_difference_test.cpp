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
  EXPECT_DOUBLE_EQ(d.mean_squared_difference, (1 + 0.25 + 9) / 6.0);
  EXPECT_DOUBLE_EQ(peak_signal_to_noise_db(d), -10 * std::log10((1 + 0.25 + 9) / 6.0));
  EXPECT_EQ(image_difference(reference, reference).relative_squared_error, 0);
  EXPECT_TRUE(std::isinf(peak_signal_to_noise_db(image_difference(reference, reference))));
  // A difference of 1/255 everywhere: RMS 1/255, PSNR 20 log10(255) = 48.13 dB.
  Image shifted = reference;
  for (float& v : shifted.pixels) v += 1.0f / 255;
  const ImageDifference step = image_difference(shifted, reference);
  EXPECT_NEAR(std::sqrt(step.mean_squared_difference), 1.0 / 255, 1e-7);
  EXPECT_NEAR(peak_signal_to_noise_db(step), 20 * std::log10(255.0), 1e-4);
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
  EXPECT_DOUBLE_EQ(report["rms"].get<double>(), std::sqrt(10.25 / 6));
  EXPECT_NEAR(report["psnr_db"].get<double>(), -10 * std::log10(10.25 / 6), 1e-9);
  EXPECT_NE(result.output.find("RMS 1.307"), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("PSNR -2.33 dB"), std::string::npos) << result.output;

  write_image(dir / "small.exr", Image(1, 1, 3));
  result = testing::run_relume("compare '" + (dir / "small.exr").string() + "' '" +
                               (dir / "reference.exr").string() + "' --json '" +
                               (dir / "bad.json").string() + "'");
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("small.exr is 1x1"), std::string::npos) << result.output;
  EXPECT_FALSE(std::filesystem::exists(dir / "bad.json"));
}

TEST(CompareCommand, FailAboveTheThresholdAndJsonOnStdout) {
  testing::TempDir dir;
  write_image(dir / "image.exr", two_by_one(1, 2, 1, -0.5f, 1, 3));
  write_image(dir / "reference.exr", two_by_one(1, 2, 2, 0, 1, 0));
  const std::string compare =
      "compare '" + (dir / "image.exr").string() + "' '" + (dir / "reference.exr").string() + "'";
  auto result = testing::run_relume(compare + " --fail 2");
  EXPECT_EQ(result.exit_code, 0) << "1.025 is below 2: " << result.output;
  result = testing::run_relume(compare + " --fail 1 --json '" + (dir / "f.json").string() + "'");
  EXPECT_EQ(result.exit_code, 1) << result.output;
  EXPECT_NE(result.output.find("is above --fail 1"), std::string::npos) << result.output;
  std::ifstream in(dir / "f.json");
  const nlohmann::json failed = nlohmann::json::parse(in);  // written before failing
  EXPECT_EQ(failed["failed"], true);
  EXPECT_EQ(failed["fail_threshold"], 1);

  // --json -: stdout holds only the JSON (the text line goes to stderr).
  const std::string stdout_file = (dir / "stdout.json").string();
  // (run_command adds 2>&1 at the end: the group keeps stderr away from the file.)
  const auto json = testing::run_command("{ " + std::string(RELUME_BINARY) + " " + compare +
                                         " --json - 2>/dev/null; } > '" + stdout_file + "'");
  ASSERT_EQ(json.exit_code, 0) << json.output;
  std::ifstream printed(stdout_file);
  const nlohmann::json parsed = nlohmann::json::parse(printed);
  EXPECT_DOUBLE_EQ(parsed["relative_squared_error"].get<double>(), 1.025);
  EXPECT_NE(parsed["software"].get<std::string>().find("relume"), std::string::npos);
  EXPECT_FALSE(std::filesystem::exists("-"));
  // Identical images: PSNR is infinite, null in JSON.
  const auto same = testing::run_command(std::string(RELUME_BINARY) + " compare '" +
                                         (dir / "reference.exr").string() + "' '" +
                                         (dir / "reference.exr").string() + "' --json -");
  ASSERT_EQ(same.exit_code, 0) << same.output;
  EXPECT_NE(same.output.find("PSNR infinite"), std::string::npos) << same.output;
  EXPECT_NE(same.output.find("\"psnr_db\": null"), std::string::npos) << same.output;
}

}  // namespace
}  // namespace relume
