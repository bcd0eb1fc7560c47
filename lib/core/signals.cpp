// Implementation of the SIGINT / SIGTERM handler (see signals.hpp).
#include "core/signals.hpp"

#include <signal.h>
#include <unistd.h>

#include <atomic>
#include <relume/error.hpp>

#include "core/interruption.hpp"
#include "core/temporary_files.hpp"

namespace relume {
namespace {

std::atomic<int> first_signal{0};
static_assert(std::atomic<int>::is_always_lock_free);

void write_stderr(const char* text) noexcept {
  std::size_t length = 0;
  while (text[length] != '\0') ++length;
  [[maybe_unused]] const ssize_t written = ::write(STDERR_FILENO, text, length);
}

extern "C" void on_interruption_signal(int signal_number) {
  int expected = 0;
  if (first_signal.compare_exchange_strong(expected, signal_number)) {
    request_interruption();
    write_stderr(
        "\nrelume: stopping at the next safe point (signal again to stop at once, leaving no "
        "temporary files)\n");
    return;
  }
  remove_registered_temporaries();
  write_stderr("\nrelume: stopped at once\n");
  ::_exit(128 + first_signal.load());
}

}  // namespace

void install_interruption_handlers() {
  struct sigaction action {};
  action.sa_handler = on_interruption_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;
  for (int signal_number : {SIGINT, SIGTERM})
    if (::sigaction(signal_number, &action, nullptr) != 0)
      throw Error("cannot install the handler of signal " + std::to_string(signal_number));
}

int interrupting_signal() noexcept { return first_signal.load(); }

}  // namespace relume
