// Implementation of ProgressReporter: bar with ETA on a terminal, periodic plain lines otherwise;
// the listener of its thread told at the start, every 0.1 s of advances and at the finish.
#include "core/progress.hpp"

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "core/console.hpp"
#include "core/interruption.hpp"

namespace relume {
namespace {

thread_local const ProgressListener* current_listener = nullptr;

constexpr auto listener_period = std::chrono::milliseconds(100);

// RELUME_QUIET set to anything but "" or "0" (test runs, logs) silences every progress bar.
bool quiet_by_environment() {
  const char* value = std::getenv("RELUME_QUIET");
  return value && std::string(value) != "0" && std::string(value) != "";
}

}  // namespace

ProgressListenerScope::ProgressListenerScope(ProgressListener listener)
    : listener_(std::move(listener)), previous_(current_listener) {
  if (listener_) current_listener = &listener_;
}

ProgressListenerScope::~ProgressListenerScope() { current_listener = previous_; }

ProgressReporter::ProgressReporter(std::string title, std::uint64_t total, bool quiet)
    : title_(std::move(title)),
      total_(total),
      quiet_(quiet || verbosity() == Verbosity::quiet || quiet_by_environment()),
      terminal_(isatty(STDERR_FILENO) != 0),
      start_(std::chrono::steady_clock::now()),
      owner_(std::this_thread::get_id()),
      last_told_(start_) {
  // Told before the printing thread starts: a listener that throws leaves nothing running.
  if (current_listener) {
    listener_ = *current_listener;
    listener_(title_, 0.0);
  }
  if (!quiet_) thread_ = std::thread([this] { run(); });
}

// Without finish() the work did not complete (an exception unwound past it): stop quietly.
ProgressReporter::~ProgressReporter() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  wake_.notify_all();
  thread_.join();
  if (terminal_) std::fputc('\n', stderr);
}

double ProgressReporter::elapsed_seconds() const {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void ProgressReporter::advance(std::uint64_t units) {
  done_ += units;
  if (listener_ && std::this_thread::get_id() == owner_) {
    const auto now = std::chrono::steady_clock::now();
    if (now - last_told_ >= listener_period) {
      last_told_ = now;
      listener_(title_, total_ ? std::min(1.0, double(done_.load()) / double(total_)) : 1.0);
    }
  }
  throw_if_interrupted();
}

void ProgressReporter::finish() {
  if (thread_.joinable()) {
    {
      std::lock_guard lock(mutex_);
      stop_ = true;
    }
    wake_.notify_all();
    thread_.join();
    print(true);
  }
  if (listener_) listener_(title_, 1.0);
}

void ProgressReporter::run() {
  const auto period = terminal_ ? std::chrono::milliseconds(200) : std::chrono::seconds(5);
  std::unique_lock lock(mutex_);
  while (!wake_.wait_for(lock, period, [this] { return stop_; })) print(false);
}

void ProgressReporter::print(bool final_line) {
  const std::uint64_t done = final_line ? total_ : done_.load();
  const double seconds = elapsed_seconds();
  const double fraction = total_ ? double(done) / double(total_) : 1.0;
  char eta[32] = "";
  if (!final_line && done > 0 && fraction < 1.0)
    std::snprintf(eta, sizeof eta, " ETA %.0fs", seconds / fraction - seconds);
  if (terminal_) {
    const int width = 30;
    std::string bar(static_cast<std::size_t>(fraction * width), '#');
    bar.resize(width, '.');
    std::fprintf(stderr, "\r%s [%s] %5.1f%% %.1fs%s   %s", title_.c_str(), bar.c_str(),
                 100 * fraction, seconds, eta, final_line ? "\n" : "");
  } else {
    std::fprintf(stderr, "%s: %llu/%llu (%.1f%%) %.1fs%s\n", title_.c_str(),
                 static_cast<unsigned long long>(done), static_cast<unsigned long long>(total_),
                 100 * fraction, seconds, eta);
  }
  std::fflush(stderr);
}

}  // namespace relume
