// Property test of the numeric options of `relume relight` and `relume relight-sequence`: each
// case gives one option a random number (an edge such as 0, 1e400, inf or nan, or a random
// magnitude of either sign; support/number_samples.hpp, fixed seed), and every run either
// succeeds and writes its output or is refused with a message and exit status 1 or 2. None
// crashes (--exposure 128 once segfaulted) or runs on (--frames 2147483647 once tried to make
// that many lights first). A few dozen cases per command keep it within a minute or two.
#include <gtest/gtest.h>

#include "support/number_samples.hpp"
#include "support/test_support.hpp"

namespace relume {
namespace {

namespace fs = std::filesystem;

// An option and how many numbers it takes (1, or 3 for x,y,z and r,g,b), with the arguments it
// needs beside it.
struct NumericOption {
  std::string name;
  int numbers = 1;
  std::string needs;
};

class NumericOptionsProperty : public testing::CommandSuite {
 protected:
  static void SetUpTestSuite() {
    CommandSuite::SetUpTestSuite();
    run_or_fail("synth -o '" + path("scene") + "' --size 16x12 --lights 20 --samples 1");
    run_or_fail("compress '" + path("scene") + "' -o '" + path("scene.relume") +
                "' --clusters 2 --terms 2 --residual 3");
    run_or_fail("sky -o '" + path("sky.exr") + "' --width 32");
  }

  // Runs `relume -y ARGUMENTS` and checks the property; `output` is what a success writes.
  static void expect_success_or_refusal(const std::string& arguments, const fs::path& output) {
    fs::remove_all(output);
    const auto result = testing::run_relume("-y " + arguments);
    ASSERT_TRUE(result.exit_code == 0 || result.exit_code == 1 || result.exit_code == 2)
        << "exit " << result.exit_code << ": relume " << arguments << "\n" << result.output;
    if (result.exit_code == 0)
      EXPECT_TRUE(fs::exists(output)) << arguments << "\n" << result.output;
    else
      EXPECT_NE(result.output.find_first_not_of(" \n"), std::string::npos)
          << "refused without a message: " << arguments;
  }

  static std::string value_for(testing::NumberSamples& samples, const NumericOption& option) {
    return option.numbers == 3 ? samples.next_triple() : samples.next();
  }
};

TEST_F(NumericOptionsProperty, RelightSucceedsOrRefusesEveryNumber) {
  const std::string env = "--env '" + path("sky.exr") + "'";
  const std::vector<NumericOption> options = {
      {"--light-dir", 3, ""},          {"--light-color", 3, "--light-dir 0,0.3,1"},
      {"--spread", 1, "--light-dir 0,0.3,1"}, {"--rotate", 1, env},
      {"--exposure", 1, "--light-dir 0,0,1"}, {"--residual", 1, "--light-dir 0,0,1"},
      {"--threads", 1, "--light-dir 0,0,1"},
  };
  testing::NumberSamples samples(35);
  for (int run = 0; run < 35; ++run) {
    const NumericOption& option = options[std::size_t(run) % options.size()];
    const std::string output = path(run % 3 == 2 ? "relit.exr" : "relit.png");
    expect_success_or_refusal("relight '" + path("scene.relume") + "' " + option.needs + " " +
                                  option.name + " " + value_for(samples, option) +
                                  (run % 2 ? " --cpu" : "") + " -o '" + output + "'",
                              output);
  }
}

TEST_F(NumericOptionsProperty, RelightSequenceSucceedsOrRefusesEveryNumber) {
  const std::vector<NumericOption> options = {
      {"--light-orbit", 1, "--frames 2"},
      {"--light-color", 3, "--light-orbit 30 --frames 2"},
      {"--spread", 1, "--light-orbit 30 --frames 2"},
      {"--frames", 1, "--light-orbit 30"},
      {"--rotate", 1, "--light-orbit 30 --frames 2"},
      {"--rotate-step", 1, "--light-orbit 30 --frames 2"},
      {"--batch", 1, "--light-orbit 30 --frames 3"},
      {"--start-number", 1, "--light-orbit 30 --frames 2"},
      {"--exposure", 1, "--light-orbit 30 --frames 2"},
      {"--residual", 1, "--light-orbit 30 --frames 2"},
  };
  testing::NumberSamples samples(36);
  for (int run = 0; run < 30; ++run) {
    const NumericOption& option = options[std::size_t(run) % options.size()];
    fs::remove_all(path("frames"));
    const std::string report = path("sequence.json");
    expect_success_or_refusal("relight-sequence '" + path("scene.relume") + "' " + option.needs +
                                  " " + option.name + " " + value_for(samples, option) +
                                  " -o '" + path("frames/%d.png") + "' --report '" + report + "'",
                              report);
  }
}

}  // namespace
}  // namespace relume
