// Tests of moving a light through the commands: `relight --light-dir` at a captured direction
// equals that light's own image (uncompressed and compressed), `lights --light-dir` writes
// weights that sum to the colour, `relight-sequence --light-orbit` changes the image
// continuously (consecutive frames differ less when the orbit steps less), `--light-path`
// follows a file, and malformed directions are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <relume/image.hpp>

#include "field/light_file.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

namespace fs = std::filesystem;

class MovedLightCommands : public testing::CommandSuite {
 protected:
  static void SetUpTestSuite() {
    CommandSuite::SetUpTestSuite();
    make_small_scene();
  }

  static Image relight(const std::string& input, const std::string& light_arguments,
                       const std::string& output) {
    run_or_fail("-y relight '" + input + "' " + light_arguments + " -o '" + path(output) + "'");
    return read_image(path(output));
  }
  // "x,y,z" of captured light `light` (0-based).
  static std::string captured_direction(int light) {
    const LightDirections directions = read_light_directions(path("scene"));
    char text[128];
    std::snprintf(text, sizeof text, "%.9g,%.9g,%.9g", directions(light, 0), directions(light, 1),
                  directions(light, 2));
    return text;
  }
  // A light vector file that lights only `light` with `rgb`.
  static std::string one_hot_lights(int light, const std::string& rgb) {
    const std::string file = path("one-hot-" + std::to_string(light) + ".txt");
    std::ofstream out(file);
    for (int i = 0; i < 40; ++i) out << (i == light ? rgb : "0 0 0") << '\n';
    return file;
  }
};

TEST_F(MovedLightCommands, AtACapturedDirectionTheImageIsThatLightsImage) {
  // Three lights towards the camera (lights behind the scene leave its visible side black).
  const LightDirections directions = read_light_directions(path("scene"));
  std::vector<int> front;
  for (int i = 0; i < 40 && front.size() < 3; ++i)
    if (directions(i, 2) > 0.3f) front.push_back(i);
  ASSERT_EQ(front.size(), 3u);
  for (const int light : front) {
    const std::string dir = "--light-dir " + captured_direction(light);
    const std::string one_hot = "--lights '" + one_hot_lights(light, "1 0.5 2") + "'";
    for (const std::string& input : {path("scene"), path("scene.relume")}) {
      const Image moved = relight(input, dir + " --light-color 1,0.5,2", "moved.exr");
      const Image captured = relight(input, one_hot, "captured.exr");
      EXPECT_LT(testing::relative_squared_difference(moved, captured), 1e-12)
          << input << " light " << light;
    }
  }
}

TEST_F(MovedLightCommands, LightsWritesWeightsThatSumToTheColour) {
  run_or_fail("lights --dirs '" + path("scene") +
              "' --light-dir 0.3,0.5,0.8 --light-color 2,1,0.5 --spread 10 -o '" +
              path("weights.txt") + "'");
  const LightRgb rows = read_rgb_rows(path("weights.txt"), "weight");
  ASSERT_EQ(rows.rows(), 40);
  EXPECT_GE(rows.minCoeff(), 0.0f);
  EXPECT_NEAR(rows.col(0).sum(), 2.0, 1e-5);
  EXPECT_NEAR(rows.col(1).sum(), 1.0, 1e-5);
  EXPECT_NEAR(rows.col(2).sum(), 0.5, 1e-5);
  int carrying = 0;
  for (int i = 0; i < 40; ++i) carrying += rows(i, 1) > 0;
  EXPECT_GT(carrying, 3) << "a 10-degree disc light spreads over more than one triangle";
}

// The largest squared difference between consecutive frames of an orbit at `step` degrees,
// relative to the mean energy of a frame.
double largest_frame_change(const std::string& container, const std::string& folder, int frames,
                            double step) {
  const auto result = testing::run_relume(
      "relight-sequence '" + container + "' --light-orbit 25 --frames " + std::to_string(frames) +
      " --rotate-step " + std::to_string(step) + " -o '" + folder + "/%04d.exr'");
  EXPECT_EQ(result.exit_code, 0) << result.output;
  double largest = 0, energy = 0;
  Image previous;
  for (int frame = 0; frame < frames; ++frame) {
    char name[32];
    std::snprintf(name, sizeof name, "/%04d.exr", frame);
    const Image image = read_image(folder + name);
    double change = 0;
    for (std::size_t i = 0; i < image.pixels.size(); ++i) {
      energy += double(image.pixels[i]) * image.pixels[i] / frames;
      if (frame > 0) change += std::pow(double(image.pixels[i]) - previous.pixels[i], 2);
    }
    largest = std::max(largest, change);
    previous = image;
  }
  return largest / energy;
}

TEST_F(MovedLightCommands, ASlowOrbitChangesTheImageContinuously) {
  const double coarse = largest_frame_change(path("scene.relume"), path("coarse"), 12, 8);
  const double fine = largest_frame_change(path("scene.relume"), path("fine"), 12, 2);
  EXPECT_GT(fine, 0) << "the light moves, so the image changes";
  // A 2-degree step changes a frame by little (measured 0.047 of a frame's energy; light
  // spacing here is about 30 degrees). Squared differences: a quarter of the step gives about a
  // sixteenth (measured 0.026), where snapping from one captured light to the next would give
  // the same jumps, only fewer of them.
  EXPECT_LT(fine, 0.1);
  EXPECT_LT(fine, 0.25 * coarse);
}

TEST_F(MovedLightCommands, ALightPathFileGivesOneFramePerDirection) {
  {
    std::ofstream out(path("path.txt"));
    out << "# x y z per frame\n0.2 0.1 1\n-0.5 0.3 0.6\n0 -1 0.2\n";
  }
  run_or_fail("relight-sequence '" + path("scene.relume") + "' --light-path '" + path("path.txt") +
              "' -o '" + path("path/%02d.exr") + "'");
  EXPECT_TRUE(fs::exists(path("path/02.exr")));
  EXPECT_FALSE(fs::exists(path("path/03.exr")));
  const Image single = relight(path("scene.relume"), "--light-dir=-0.5,0.3,0.6", "single.exr");
  EXPECT_LT(testing::relative_squared_difference(read_image(path("path/01.exr")), single), 1e-12);
}

TEST_F(MovedLightCommands, MalformedDirectionsAreRefused) {
  auto result = testing::run_relume("relight '" + path("scene.relume") +
                                    "' --light-dir 0,0,0 -o '" + path("zero.exr") + "'");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("zero"), std::string::npos) << result.output;
  EXPECT_FALSE(fs::exists(path("zero.exr")));
  result = testing::run_relume("relight '" + path("scene.relume") + "' --light-dir 1,2 -o '" +
                               path("two.exr") + "'");
  EXPECT_EQ(result.exit_code, 2) << result.output;
  result = testing::run_relume("relight '" + path("scene.relume") + "' --light-dir 0,0,1 --env x" +
                               " -o '" + path("both.exr") + "'");
  EXPECT_EQ(result.exit_code, 2) << result.output;
}

}  // namespace
}  // namespace relume
