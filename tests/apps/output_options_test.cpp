// Tests of how the commands write their outputs, run as commands on a small synthetic scene:
// nothing is overwritten silently (-y/--overwrite, before or after the command's name; decompress
// refuses a non-empty folder; outputs are checked before any work), and a batch compress refuses
// inputs whose containers would collide.
#include <gtest/gtest.h>

#include <fstream>
#include <relume/image.hpp>

#include "core/atomic_file.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

namespace fs = std::filesystem;

class OutputOptions : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = new testing::TempDir;
    run_or_fail("synth -o '" + path("scene") + "' --size 16x12 --lights 20 --samples 1");
    run_or_fail("compress '" + path("scene") + "' -o '" + path("scene.relume") +
                "' --clusters 2 --terms 2 --residual 3");
    std::ofstream lights(path("lights.txt"));
    for (int i = 0; i < 20; ++i) lights << "1 1 1\n";
  }
  static void TearDownTestSuite() { delete folder_; }

  static std::string path(const std::string& name) { return (*folder_ / name).string(); }
  static testing::CommandResult run_or_fail(const std::string& arguments) {
    const auto result = testing::run_relume(arguments);
    EXPECT_EQ(result.exit_code, 0) << arguments << "\n" << result.output;
    return result;
  }
  static std::string relight_to(const std::string& output) {
    return "relight '" + path("scene.relume") + "' --lights '" + path("lights.txt") + "' -o '" +
           path(output) + "'";
  }

  static testing::TempDir* folder_;
};

testing::TempDir* OutputOptions::folder_ = nullptr;

TEST_F(OutputOptions, AnExistingOutputIsReplacedOnlyWithOverwrite) {
  write_file_atomically(path("taken.exr"), "not an image");
  const auto refused = testing::run_relume(relight_to("taken.exr"));
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_NE(refused.output.find("taken.exr exists: pass -y/--overwrite"), std::string::npos)
      << refused.output;
  EXPECT_EQ(read_file(path("taken.exr")), "not an image");

  run_or_fail("-y " + relight_to("taken.exr"));
  EXPECT_EQ(read_image(path("taken.exr")).width, 16);
  run_or_fail(relight_to("taken.exr") + " --overwrite");  // after the command's name too

  // lights, sky and compare --json refuse the same way.
  for (const std::string& command :
       {"lights --dirs '" + path("scene") + "' --light-dir 0,0,1 -o '" + path("taken.exr") + "'",
        "sky -o '" + path("taken.exr") + "'",
        "compare '" + path("taken.exr") + "' '" + path("taken.exr") + "' --json '" +
            path("taken.exr") + "'"}) {
    const auto result = testing::run_relume(command);
    EXPECT_EQ(result.exit_code, 1) << command;
    EXPECT_NE(result.output.find("exists"), std::string::npos) << command << result.output;
  }
}

TEST_F(OutputOptions, DecompressRefusesANonEmptyFolder) {
  fs::create_directories(path("empty"));
  run_or_fail("decompress '" + path("scene.relume") + "' -o '" + path("empty") + "'");
  const auto refused =
      testing::run_relume("decompress '" + path("scene.relume") + "' -o '" + path("empty") + "'");
  EXPECT_EQ(refused.exit_code, 1);
  EXPECT_NE(refused.output.find("not empty"), std::string::npos) << refused.output;
  run_or_fail("decompress -y '" + path("scene.relume") + "' -o '" + path("empty") + "'");
  EXPECT_TRUE(fs::exists(path("empty/filenames.txt")));
  const auto synth =
      testing::run_relume("synth -o '" + path("empty") + "' --size 4x4 --lights 4 --samples 1");
  EXPECT_EQ(synth.exit_code, 1) << synth.output;
}

TEST_F(OutputOptions, OutputsAreCheckedBeforeAnyWork) {
  // compress: the existing container is refused before the field loads.
  const auto compress = testing::run_relume("compress '" + path("scene") + "' -o '" +
                                            path("scene.relume") + "' --clusters 2 --terms 2");
  EXPECT_EQ(compress.exit_code, 1);
  EXPECT_NE(compress.output.find("scene.relume exists"), std::string::npos) << compress.output;
  EXPECT_EQ(compress.output.find("loaded"), std::string::npos) << compress.output;
  // relight-sequence: one existing frame, and no frame is written.
  fs::create_directories(path("frames"));
  write_file_atomically(path("frames/0001.exr"), "taken");
  const auto sequence =
      testing::run_relume("relight-sequence '" + path("scene.relume") +
                          "' --light-orbit 30 --frames 3 -o '" + path("frames/%04d.exr") + "'");
  EXPECT_EQ(sequence.exit_code, 1);
  EXPECT_NE(sequence.output.find("0001.exr exists"), std::string::npos) << sequence.output;
  EXPECT_FALSE(fs::exists(path("frames/0000.exr")));
}

TEST_F(OutputOptions, ABatchCompressRefusesCollidingNames) {
  fs::create_directories(path("a"));
  fs::create_directories(path("b"));
  fs::copy(path("scene"), path("a/scene"));
  fs::copy(path("scene"), path("b/scene"));
  const auto result = testing::run_relume("compress '" + path("a/scene") + "' '" + path("b/scene") +
                                          "' -o '" + path("batch") + "'");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_NE(result.output.find("would both write"), std::string::npos) << result.output;
  EXPECT_FALSE(fs::exists(path("batch")));
}

}  // namespace
}  // namespace relume
