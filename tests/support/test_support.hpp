// Helpers shared by the tests: the real-data folder (RELUME_DATA or ../shared/data), a fresh
// temporary folder per test, running commands and the built `relume` binary, a fixture for
// suites of commands that share one folder, the relative difference of two images, a noisy
// original for a compressed field, and dark pixels for one.
#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <optional>
#include <relume/compressed_field.hpp>
#include <relume/image.hpp>
#include <string>

namespace relume::testing {

// The shared data folder, or nullopt when it is missing.
std::optional<std::filesystem::path> shared_data_dir();

// Skips the current test, saying which folder was missing and how to point at it.
#define RELUME_REQUIRE_SHARED_DATA(var)                                                  \
  const auto var##_opt = ::relume::testing::shared_data_dir();                           \
  if (!var##_opt)                                                                        \
    GTEST_SKIP() << "shared data not found at " << ::relume::testing::shared_data_hint() \
                 << " (set RELUME_DATA to the folder that holds olat/ and envmaps/)";    \
  const std::filesystem::path var = *var##_opt

std::string shared_data_hint();

// A new empty folder under the system temp dir, removed when the object goes away.
class TempDir {
 public:
  TempDir();
  ~TempDir();
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

 private:
  std::filesystem::path path_;
};

struct CommandResult {
  int exit_code = 0;
  std::string output;  // stdout and stderr together
};

// The message of the relume::Error that `action` throws, or "(no relume::Error thrown)".
std::string error_message(const std::function<void()>& action);

// Runs a shell command line.
CommandResult run_command(const std::string& command);

// Runs the built relume binary with the given arguments (shell-quoted here).
CommandResult run_relume(const std::string& arguments);

// A suite of command tests that share one temporary folder, made before its first test and
// removed after its last. A suite's own SetUpTestSuite calls CommandSuite::SetUpTestSuite()
// first, then prepares its inputs with run_or_fail.
class CommandSuite : public ::testing::Test {
 protected:
  static void SetUpTestSuite();
  static void TearDownTestSuite();
  // `name` inside the suite's folder.
  static std::string path(const std::string& name);
  // run_relume(arguments), expecting exit status 0 (a failure names the arguments and output).
  static CommandResult run_or_fail(const std::string& arguments);
  // The small synthetic field of the command suites, "scene" (24 x 20, 40 lights), and its
  // container "scene.relume" (4 clusters, 2 terms, 6 residual entries).
  static void make_small_scene();

 private:
  static TempDir* folder_;
};

// sum (a - b)^2 / sum b^2 over every pixel and channel (a failure when the sizes differ).
double relative_squared_difference(const Image& a, const Image& b);

// A field that `compressed` approximates: its reconstruction plus uniform noise of amplitude
// `noise` on the stored functions (the others stay zero and have no Eq. 16 error), so the
// compressed field has a known, non-zero error over exactly its stored rows. Seeded: the same
// arguments give the same field.
ReflectanceField noisy_original(const CompressedField& compressed, double noise);

// The repository's root folder (for its scripts).
inline std::filesystem::path source_dir() { return RELUME_SOURCE_DIR; }

// Every other pixel of `field` without stored rows joins the mask as a dark pixel, and the field
// gets a dark model (small values, channels x lights).
void add_dark_pixels(CompressedField& field);

// Gains for `field`'s dark pixels: one per block and channel, multiples of a step, as the
// container stores them.
void add_dark_gains(CompressedField& field);

}  // namespace relume::testing
