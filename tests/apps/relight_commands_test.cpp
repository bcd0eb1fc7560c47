// Tests of `relume relight` on .relume containers and of `relume relight-sequence`, run as
// commands on a small synthetic scene compressed once per suite: the OpenCL render (PoCL) agrees
// with the C++ reference and with the decompressed field relit as an uncompressed one, the
// residual cap trades accuracy, sequence frames equal single relights, and bad input is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <nlohmann/json.hpp>
#include <random>
#include <relume/image.hpp>

#include "support/test_support.hpp"

namespace relume {
namespace {

namespace fs = std::filesystem;

class RelightCommands : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = new testing::TempDir;
    run_or_fail("synth -o '" + path("scene") + "' --size 24x20 --lights 40 --samples 1");
    run_or_fail("compress '" + path("scene") + "' -o '" + path("scene.relume") +
                "' --clusters 4 --terms 2 --residual 6");
    run_or_fail("sky -o '" + path("sky.exr") + "'");
    std::mt19937 random(5);
    std::uniform_real_distribution<float> uniform(0.0f, 1.0f);
    std::ofstream lights(path("lights.txt"));
    for (int i = 0; i < 40; ++i)
      lights << uniform(random) << ' ' << uniform(random) << ' ' << uniform(random) << '\n';
  }
  static void TearDownTestSuite() { delete folder_; }

  static std::string path(const std::string& name) { return (*folder_ / name).string(); }
  static void run_or_fail(const std::string& arguments) {
    const auto result = testing::run_relume(arguments);
    ASSERT_EQ(result.exit_code, 0) << arguments << "\n" << result.output;
  }
  // `relume relight` of the container into `output` with extra arguments; returns the image.
  static Image relight(const std::string& input, const std::string& light_arguments,
                       const std::string& output) {
    run_or_fail("-y relight '" + input + "' " + light_arguments + " -o '" + path(output) + "'");
    return read_image(path(output));
  }

  static testing::TempDir* folder_;
};

testing::TempDir* RelightCommands::folder_ = nullptr;

TEST_F(RelightCommands, OpenClAgreesWithTheReferenceAndTheDecompressedField) {
  const std::string lights = "--lights '" + path("lights.txt") + "'";
  const Image opencl = relight(path("scene.relume"), lights, "opencl.exr");
  const Image reference = relight(path("scene.relume"), lights + " --cpu", "reference.exr");
  EXPECT_EQ(opencl.width, 24);
  EXPECT_EQ(opencl.height, 20);
  EXPECT_LT(testing::relative_squared_difference(opencl, reference),
            1e-10);  // squared: 1e-5 relative L2

  run_or_fail("decompress '" + path("scene.relume") + "' -o '" + path("decompressed") + "'");
  const Image decompressed = relight(path("decompressed"), lights, "decompressed.exr");
  EXPECT_LT(testing::relative_squared_difference(decompressed, reference), 1e-10);

  // Against the uncompressed scene: lossy, yet close.
  const Image original = relight(path("scene"), lights, "original.exr");
  const double error = testing::relative_squared_difference(opencl, original);
  EXPECT_GT(error, 0);
  EXPECT_LT(error, 0.05);
}

TEST_F(RelightCommands, FewerResidualEntriesAreLessAccurate) {
  const std::string lights = "--lights '" + path("lights.txt") + "'";
  const Image original = relight(path("scene"), lights, "original.exr");
  double previous = 0;
  for (const char* residual : {"all", "3", "0"}) {
    const Image image = relight(path("scene.relume"), lights + " --residual " + residual,
                                std::string("cap-") + residual + ".exr");
    const double error = testing::relative_squared_difference(image, original);
    EXPECT_GT(error, previous) << "--residual " << residual;
    previous = error;
  }
}

TEST_F(RelightCommands, SequenceFramesEqualSingleRelightsAndReportTheirError) {
  run_or_fail("relight-sequence '" + path("scene.relume") + "' --env '" + path("sky.exr") +
              "' --frames 3 --rotate-step 120 --batch 2 --residual 2 --compare --report '" +
              path("sequence.json") + "' -o '" + path("frames/%04d.exr") + "'");
  for (int frame = 0; frame < 3; ++frame) {
    const Image sequence = read_image(path("frames/000" + std::to_string(frame) + ".exr"));
    const Image single = relight(
        path("scene.relume"),
        "--env '" + path("sky.exr") + "' --rotate " + std::to_string(120 * frame) + " --residual 2",
        "single.exr");
    EXPECT_LT(testing::relative_squared_difference(sequence, single), 1e-10) << "frame " << frame;
  }
  EXPECT_FALSE(fs::exists(path("frames/0003.exr")));
  std::ifstream in(path("sequence.json"));
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_EQ(report["frames"], 3);
  EXPECT_EQ(report["residual_cap"], 2);
  EXPECT_GT(report["frames_per_second"].get<double>(), 0);
  ASSERT_EQ(report["per_frame"].size(), 3u);
  for (const auto& frame : report["per_frame"]) {
    EXPECT_GT(frame["error"].get<double>(), 0) << "2 of 6 entries differ from the full residual";
    EXPECT_LT(frame["error"].get<double>(), 0.5);
  }
}

TEST_F(RelightCommands, BadInputIsRefusedWithAMessageAndNoOutput) {
  auto result =
      testing::run_relume("relight-sequence '" + path("scene.relume") + "' --env '" +
                          path("sky.exr") + "' --frames 2 -o '" + path("bad/frame.exr") + "'");
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("frame-number conversion"), std::string::npos) << result.output;
  EXPECT_FALSE(fs::exists(path("bad")));

  result = testing::run_relume("relight '" + path("missing.relume") + "' --env '" +
                               path("sky.exr") + "' -o '" + path("missing.exr") + "'");
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("missing.relume"), std::string::npos) << result.output;
  EXPECT_FALSE(fs::exists(path("missing.exr")));

  {
    std::ofstream short_file(path("short.txt"));
    short_file << "1 1 1\n2 2 2\n";
  }
  result = testing::run_relume("relight '" + path("scene.relume") + "' --lights '" +
                               path("short.txt") + "' -o '" + path("short.exr") + "'");
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("short.txt"), std::string::npos) << result.output;
  EXPECT_FALSE(fs::exists(path("short.exr")));
}

// Options of a light source that was not chosen were ignored without a word (issue 35): a moved
// light's colour and spread need --light-dir, a map's layout and rotation need --env.
TEST_F(RelightCommands, OptionsOfAnotherLightSourceAreUsageErrors) {
  const std::string env = " --env '" + path("sky.exr") + "'";
  const std::string direction = " --light-dir 0,0,1";
  const std::vector<std::pair<std::string, std::string>> cases = {
      {env + " --spread 5", "--spread requires --light-dir"},
      {env + " --light-color 2,2,2", "--light-color requires --light-dir"},
      {direction + " --layout latlong", "--layout requires --env"},
      {direction + " --rotate 90", "--rotate requires --env"}};
  for (const auto& [options, message] : cases)
    for (const std::string& command : {"relight '" + path("scene.relume") + "'",
                                      "lights --dirs '" + path("scene") + "'"}) {
      const auto result = testing::run_relume(command + options + " -o '" + path("x.txt") + "'");
      EXPECT_EQ(result.exit_code, 2) << command << options << "\n" << result.output;
      EXPECT_NE(result.output.find(message), std::string::npos) << result.output;
      EXPECT_FALSE(fs::exists(path("x.txt")));
    }
}

// Black pixels (a masked background) under 2^128 became NaN and indexed the sRGB table (a
// segfault, exit 139). Exposures and light colours out of range are usage errors naming
// the option and the value; the largest exposure allowed still writes.
TEST_F(RelightCommands, ExposuresAndLightColoursOutOfRangeAreRefusedNamingThem) {
  const std::string relight_scene = "-y relight '" + path("scene.relume") + "' --light-dir 0,0,1 ";
  for (const char* exposure : {"128", "-41", "1e400", "nan"})
    for (const char* renderer : {"", "--cpu "}) {
      const auto result = testing::run_relume(relight_scene + renderer + "--exposure " + exposure +
                                              " -o '" + path("exposed.png") + "'");
      EXPECT_EQ(result.exit_code, 2) << exposure << "\n" << result.output;
      EXPECT_NE(result.output.find("--exposure must be a number of stops from -40 to 40"),
                std::string::npos)
          << result.output;
      EXPECT_NE(result.output.find(std::string("got '") + exposure + "'"), std::string::npos)
          << result.output;
      EXPECT_FALSE(fs::exists(path("exposed.png")));
    }
  const auto sequence = testing::run_relume(
      "relight-sequence '" + path("scene.relume") + "' --light-orbit 55 --frames 2 --exposure 200" +
      " -o '" + path("orbit/####.png") + "'");
  EXPECT_EQ(sequence.exit_code, 2) << sequence.output;
  EXPECT_NE(sequence.output.find("got '200'"), std::string::npos) << sequence.output;

  const auto colour = testing::run_relume(relight_scene + "--light-color 1e7,1,1 -o '" +
                                          path("coloured.png") + "'");
  EXPECT_EQ(colour.exit_code, 1) << colour.output;
  EXPECT_NE(colour.output.find("light colour (1e+07, 1, 1) must be three non-negative numbers up "
                               "to 1e+06"),
            std::string::npos)
      << colour.output;

  const Image exposed = relight(path("scene.relume"), "--light-dir 0,0,1 --exposure 40",
                                "exposed.png");
  EXPECT_EQ(*std::min_element(exposed.pixels.begin(), exposed.pixels.end()), 0.0f);
  EXPECT_EQ(*std::max_element(exposed.pixels.begin(), exposed.pixels.end()), 1.0f);
}

}  // namespace
}  // namespace relume
