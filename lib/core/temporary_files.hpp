// Temporary files and folders of atomic writes (core/atomic_file.hpp), named
// `.tmp-<pid>-<target name>` beside their target:
//  - a registry of the ones in progress that a signal handler may empty (async-signal-safe: fixed
//    slots, no allocation, no locks), so that a second Ctrl-C unlinks them before the process
//    exits (core/signals.hpp);
//  - the removal of stale ones that an earlier, killed process left beside a target.
#pragma once

#include <filesystem>

namespace relume {

// The temporary path for `target` in this process: `<folder>/.tmp-<pid>-<name>`.
std::filesystem::path temporary_path_for(const std::filesystem::path& target);

// Registers a temporary file or folder while it lives. A path that does not fit a slot (the
// registry holds a fixed number of long paths) is simply not registered: RAII and the next run's
// stale cleanup still remove it.
class TemporaryPathRegistration {
 public:
  enum class Kind { file, folder };
  TemporaryPathRegistration(const std::filesystem::path& path, Kind kind);
  ~TemporaryPathRegistration();
  TemporaryPathRegistration(const TemporaryPathRegistration&) = delete;
  TemporaryPathRegistration& operator=(const TemporaryPathRegistration&) = delete;

 private:
  int slot_ = -1;
};

// Unlinks every registered file, then removes every registered folder that is empty by then.
// Async-signal-safe (unlink, rmdir and atomics only).
void remove_registered_temporaries() noexcept;

// Removes `.tmp-<pid>-<target name>` files and folders beside `target` whose process no longer
// runs: what a killed earlier run left behind. Never fails (what cannot be removed stays).
void remove_stale_temporaries(const std::filesystem::path& target) noexcept;

}  // namespace relume
