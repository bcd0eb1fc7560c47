// Progress reporting for long work: a counter that threads advance, and a reporter thread that
// prints a bar with rate and ETA on a terminal (stderr), or a plain line every few seconds
// otherwise.
#pragma once

#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <string>
#include <thread>

namespace relume {

class ProgressReporter {
 public:
  // total: number of work units; quiet: print nothing (also when the verbosity is quiet or
  // RELUME_QUIET is set to anything but "" or "0").
  ProgressReporter(std::string title, std::uint64_t total, bool quiet = false);
  ~ProgressReporter();
  ProgressReporter(const ProgressReporter&) = delete;
  ProgressReporter& operator=(const ProgressReporter&) = delete;

  void advance(std::uint64_t units = 1) { done_ += units; }
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
};

}  // namespace relume
