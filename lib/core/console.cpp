// Implementation of the process-wide verbosity and its message lines.
#include "core/console.hpp"

#include <atomic>
#include <cstdarg>
#include <cstdio>

namespace relume {
namespace {

std::atomic<Verbosity>& level() {
  static std::atomic<Verbosity> current{Verbosity::normal};
  return current;
}

void print_line(std::FILE* stream, const char* format, std::va_list arguments) {
  std::vfprintf(stream, format, arguments);
  std::fputc('\n', stream);
  std::fflush(stream);
}

}  // namespace

Verbosity verbosity() { return level().load(); }

void set_verbosity(Verbosity value) { level().store(value); }

// The three message kinds differ only in their stream and the least verbosity that shows them.
#define RELUME_PRINT_LINE(stream, shown)   \
  do {                                     \
    if (!(shown)) return;                  \
    std::va_list arguments;                \
    va_start(arguments, format);           \
    print_line(stream, format, arguments); \
    va_end(arguments);                     \
  } while (false)

void say(const char* format, ...) { RELUME_PRINT_LINE(stdout, verbosity() != Verbosity::quiet); }

void note(const char* format, ...) { RELUME_PRINT_LINE(stderr, verbosity() != Verbosity::quiet); }

void detail(const char* format, ...) {
  RELUME_PRINT_LINE(stderr, verbosity() == Verbosity::verbose);
}

#undef RELUME_PRINT_LINE

}  // namespace relume
