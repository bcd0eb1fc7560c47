// Tests of the `relume` command's front door: --version and the version stamp in reports,
// containers and images; `relume help CMD`; unknown commands with a suggestion; usage errors with
// exit status 2 and input errors with 1; the global -q and -v on any command.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <relume/container.hpp>
#include <relume/version.hpp>

#include "support/test_support.hpp"

namespace relume {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;
using testing::run_relume;

TEST(FrontDoor, VersionPrintsTheVersionAndTheCommit) {
  const auto result = run_relume("--version");
  EXPECT_EQ(result.exit_code, 0);
  EXPECT_EQ(result.output, version_line() + "\n");
  EXPECT_THAT(version_line(), HasSubstr("relume " + version() + " (commit "));
  const auto head = testing::run_command("git -C '" + testing::source_dir().string() +
                                         "' rev-parse --short=10 HEAD");
  if (head.exit_code != 0) GTEST_SKIP() << "not a git checkout: " << head.output;
  EXPECT_EQ(git_commit().substr(0, 10), head.output.substr(0, 10));
}

TEST(FrontDoor, UnknownCommandsAreNamedWithTheNearestCommand) {
  auto result = run_relume("compres scene -o x.relume");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_THAT(result.output,
              HasSubstr("relume: unknown command 'compres'; did you mean 'compress'?"));
  result = run_relume("frobnicate");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_THAT(result.output, HasSubstr("unknown command 'frobnicate'"));
  EXPECT_THAT(result.output, Not(HasSubstr("did you mean")));
  result = run_relume("relihgt");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_THAT(result.output, HasSubstr("did you mean 'relight'?"));
}

TEST(FrontDoor, HelpNamesTheCommandAsRelume) {
  auto result = run_relume("help info");
  EXPECT_EQ(result.exit_code, 0);
  EXPECT_THAT(result.output, HasSubstr("Usage: relume info"));
  result = run_relume("info --help");
  EXPECT_EQ(result.exit_code, 0);
  EXPECT_THAT(result.output, HasSubstr("Usage: relume info"));
  result = run_relume("help");
  EXPECT_EQ(result.exit_code, 0);
  EXPECT_THAT(result.output, HasSubstr("relight-sequence"));
  EXPECT_THAT(result.output, HasSubstr("Exit status: 0 success, 1 error"));
  result = run_relume("help nosuch");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_THAT(result.output, HasSubstr("unknown command 'nosuch'"));
  result = run_relume("");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_THAT(result.output, HasSubstr("Usage: relume"));
}

TEST(FrontDoor, UsageErrorsExitWithTwoAndInputErrorsWithOne) {
  testing::TempDir folder;
  auto result = run_relume("info --no-such-option '" + (folder / "x.relume").string() + "'");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_EQ(result.output.rfind("relume: ", 0), 0u) << result.output;
  EXPECT_THAT(result.output, HasSubstr("--no-such-option"));
  result = run_relume("synth -o '" + (folder / "s").string() + "' --lights many");
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_THAT(result.output, HasSubstr("many"));
  result = run_relume("info '" + (folder / "missing.relume").string() + "'");
  EXPECT_EQ(result.exit_code, 1);
  EXPECT_THAT(result.output, HasSubstr("relume: error:"));
  EXPECT_THAT(result.output, HasSubstr("missing.relume"));
  result = run_relume("-q -v info x.relume");
  EXPECT_EQ(result.exit_code, 2);
}

// A small scene compressed once: the stamps in its container, report and images, and the
// global verbosity flags on the same commands.
class StampedOutputs : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    folder_ = new testing::TempDir;
    synth_ = run_relume("synth -o '" + path("scene") + "' --size 20x16 --lights 30 --samples 1");
    compress_ = run_relume("compress -q '" + path("scene") + "' -o '" + path("scene.relume") +
                           "' --clusters 3 --terms 2 --residual 3 --assign cpu --report '" +
                           path("report.json") + "'");
  }
  static void TearDownTestSuite() { delete folder_; }
  static std::string path(const std::string& name) { return (*folder_ / name).string(); }

  static testing::TempDir* folder_;
  static testing::CommandResult synth_, compress_;
};
testing::TempDir* StampedOutputs::folder_ = nullptr;
testing::CommandResult StampedOutputs::synth_, StampedOutputs::compress_;

TEST_F(StampedOutputs, QuietPrintsNothingAndVerbosePrintsMore) {
  ASSERT_EQ(synth_.exit_code, 0) << synth_.output;
  EXPECT_THAT(synth_.output, HasSubstr("synth: 20x16, 30 lights"));
  ASSERT_EQ(compress_.exit_code, 0) << compress_.output;
  EXPECT_EQ(compress_.output, "") << "-q after the command's name";
  const std::string decompress = "decompress '" + path("scene.relume") + "' -o '" + path("d");
  auto result = run_relume("-q " + decompress + "'");
  EXPECT_EQ(result.exit_code, 0);
  EXPECT_EQ(result.output, "");
  result = run_relume("-y " + decompress + "'");
  EXPECT_THAT(result.output, HasSubstr("wrote "));
  result = run_relume("-v -y " + decompress + "'");
  EXPECT_THAT(result.output, HasSubstr(version_line()));
  EXPECT_THAT(result.output, HasSubstr("relume: decompress done in"));
  // A command's results are not messages: info prints its description even when quiet.
  result = run_relume("info -q '" + path("scene.relume") + "'");
  EXPECT_EQ(result.exit_code, 0);
  EXPECT_THAT(result.output, HasSubstr("written by: " + version_line()));
}

TEST_F(StampedOutputs, ContainerAndReportRecordTheVersion) {
  ASSERT_EQ(compress_.exit_code, 0) << compress_.output;
  ContainerOptions stored;
  read_container(path("scene.relume"), &stored);
  EXPECT_EQ(stored.written_by, version_line());
  std::ifstream report_file(path("report.json"));
  const auto report = nlohmann::json::parse(report_file);
  EXPECT_EQ(report.at("software"), version_line());
  EXPECT_TRUE(report.contains("error_masked")) << "the report itself follows the stamp";
}

TEST_F(StampedOutputs, ImagesCarryTheVersionAsSoftware) {
  ASSERT_EQ(compress_.exit_code, 0) << compress_.output;
  ASSERT_EQ(run_relume("sky -o '" + path("sky.exr") + "' --width 64").exit_code, 0);
  for (const std::string name : {"sky.exr", "relit.exr", "relit.png"}) {
    if (name != "sky.exr") {
      const auto result = run_relume("relight '" + path("scene.relume") + "' --cpu --env '" +
                                     path("sky.exr") + "' -o '" + path(name) + "'");
      ASSERT_EQ(result.exit_code, 0) << result.output;
    }
    auto input = OIIO::ImageInput::open(path(name));
    ASSERT_TRUE(input) << name;
    EXPECT_EQ(input->spec().get_string_attribute("Software"), version_line()) << name;
  }
}

}  // namespace
}  // namespace relume
