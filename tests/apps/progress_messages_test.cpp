// Tests of what long commands say while they work, run as commands on a small synthetic scene:
// a line per clustering iteration on the default (OpenCL) assignment path, a progress bar while
// images load, relight-sequence's set-up time reported apart from frames/s, and option values
// refused before anything loads.
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>

#include "support/test_support.hpp"

namespace relume {
namespace {

// Occurrences of `part` in `text`.
std::size_t count_of(const std::string& text, const std::string& part) {
  std::size_t count = 0;
  for (auto at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++count;
  return count;
}

class ProgressMessages : public testing::CommandSuite {
 protected:
  static void SetUpTestSuite() {
    CommandSuite::SetUpTestSuite();
    const auto result = testing::run_relume("synth -o '" + path("scene") +
                                            "' --size 16x12 --lights 20 --samples 1");
    ASSERT_EQ(result.exit_code, 0) << result.output;
  }
};

TEST_F(ProgressMessages, CompressSaysEveryIterationAndShowsTheImagesLoading) {
  // RELUME_QUIET=0: the progress bars print (as plain lines, stderr is no terminal here).
  const auto result = testing::run_command(
      "RELUME_QUIET=0 " + std::string(RELUME_BINARY) + " compress '" + path("scene") + "' -o '" +
      path("scene.relume") + "' --clusters 3 --terms 2 --residual 3 --iterations 3 --report '" +
      path("report.json") + "'");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  std::ifstream in(path("report.json"));
  const nlohmann::json report = nlohmann::json::parse(in);
  ASSERT_NE(report["assignment_device"], "cpu") << "the default path is the OpenCL assignment";
  const std::size_t iterations = report["clustering"]["iterations"].size();
  ASSERT_GE(iterations, 2u);
  EXPECT_EQ(count_of(result.output, "compress: iteration "), iterations) << result.output;
  EXPECT_NE(result.output.find("compress: iteration 1: L1 objective "), std::string::npos);
  EXPECT_NE(result.output.find("functions changed cluster"), std::string::npos);
  EXPECT_NE(result.output.find("loading 20 images"), std::string::npos) << result.output;

  const auto quiet = testing::run_relume("-q -y compress '" + path("scene") + "' -o '" +
                                         path("scene.relume") + "' --clusters 3 --terms 2");
  ASSERT_EQ(quiet.exit_code, 0) << quiet.output;
  EXPECT_EQ(quiet.output, "");
}

TEST_F(ProgressMessages, RelightSequenceReportsItsSetUpApartFromFramesPerSecond) {
  ASSERT_EQ(testing::run_relume("-y compress '" + path("scene") + "' -o '" + path("s.relume") +
                                "' --clusters 3 --terms 2 --residual 3")
                .exit_code,
            0);
  const auto result = testing::run_relume(
      "relight-sequence '" + path("s.relume") + "' --light-orbit 30 --frames 5 --batch 2 -o '" +
      path("frames/%02d.exr") + "' --report '" + path("sequence.json") + "'");
  ASSERT_EQ(result.exit_code, 0) << result.output;
  EXPECT_NE(result.output.find("set-up "), std::string::npos) << result.output;
  EXPECT_NE(result.output.find("not counted in frames/s"), std::string::npos) << result.output;
  std::ifstream in(path("sequence.json"));
  const nlohmann::json report = nlohmann::json::parse(in);
  EXPECT_GT(report["setup_seconds"].get<double>(), 0);
  EXPECT_GT(report["frames_per_second"].get<double>(), 0);
  EXPECT_EQ(report["per_frame"].size(), 5u);
}

TEST_F(ProgressMessages, OptionValuesAreRefusedBeforeAnythingLoads) {
  // The input-encoding note comes with loading; a bad --residual is refused before it.
  const auto result =
      testing::run_relume("relight '" + path("scene") + "' --light-dir 0,0,1 --residual 5x -o '" +
                          path("never.exr") + "'");
  EXPECT_NE(result.exit_code, 0);
  EXPECT_NE(result.output.find("5x"), std::string::npos) << result.output;
  EXPECT_EQ(result.output.find("input "), std::string::npos) << result.output;
  const auto frames =
      testing::run_relume("relight-sequence '" + path("missing.relume") +
                          "' --light-orbit 30 --frames 0 -o '" + path("f/%d.exr") + "'");
  EXPECT_EQ(frames.exit_code, 2) << frames.output;
  EXPECT_NE(frames.output.find("--frames: Value 0 not in range 1 to 100000"), std::string::npos)
      << "checked before the (missing) container is read: " << frames.output;
}

}  // namespace
}  // namespace relume
