// Helpers shared by the tests: the real-data folder (RELUME_DATA or ../shared/data), a fresh
// temporary folder per test, and running commands and the built `relume` binary.
#pragma once

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <functional>
#include <optional>
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

// The repository's root folder (for its scripts).
inline std::filesystem::path source_dir() { return RELUME_SOURCE_DIR; }

}  // namespace relume::testing
