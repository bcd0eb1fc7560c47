// Progress reporting for long work: a counter that threads advance, and a reporter thread that
// prints a bar with rate and ETA on a terminal (stderr), or a plain line every few seconds
// otherwise.
//
// Listeners and interruption. A ProgressListenerScope installs a listener on its thread (the
// public CompressOptions::progress callback is one): every ProgressReporter constructed on that
// thread while the scope lives tells it (title, fraction done) at the start (0), about every
// 0.1 s while the constructing thread advances it, and at finish() (1), always on the
// constructing thread, quiet or not. advance() also checks for a requested interruption
// (lib/core/interruption.hpp) and throws relume::Interrupted: long loops become interruptible
// where they already report progress.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

namespace relume {

// (title of the work, fraction done in [0, 1]). An exception it throws ends the work.
using ProgressListener = std::function<void(const std::string& title, double fraction)>;

// Installs `listener` for the ProgressReporters made on this thread while it lives; scopes nest
// (the previous listener is back when this one ends). An empty listener installs none.
class ProgressListenerScope {
 public:
  explicit ProgressListenerScope(ProgressListener listener);
  ~ProgressListenerScope();
  ProgressListenerScope(const ProgressListenerScope&) = delete;
  ProgressListenerScope& operator=(const ProgressListenerScope&) = delete;

 private:
  ProgressListener listener_;
  const ProgressListener* previous_;
};

class ProgressReporter {
 public:
  // total: number of work units; quiet: print nothing (also when the verbosity is quiet or
  // RELUME_QUIET is set to anything but "" or "0"). A listener installed on this thread hears
  // from it either way.
  ProgressReporter(std::string title, std::uint64_t total, bool quiet = false);
  ~ProgressReporter();
  ProgressReporter(const ProgressReporter&) = delete;
  ProgressReporter& operator=(const ProgressReporter&) = delete;

  // Thread-safe. Throws Interrupted when an interruption was requested, and whatever the
  // listener throws (called from the constructing thread only).
  void advance(std::uint64_t units = 1);
  // Stops the reporter thread and prints the final line with the elapsed time.
  void finish();
  double elapsed_seconds() const;

 private:
  void print(bool final_line);
  void run();

  std::string title_;
  std::uint64_t total_;
  bool quiet_;
  bool terminal_;
  std::atomic<std::uint64_t> done_{0};
  std::chrono::steady_clock::time_point start_;
  std::mutex mutex_;
  std::condition_variable wake_;
  bool stop_ = false;
  std::thread thread_;
  ProgressListener listener_;
  std::thread::id owner_;
  std::chrono::steady_clock::time_point last_told_;
};

}  // namespace relume
