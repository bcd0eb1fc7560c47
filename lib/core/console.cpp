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

void say(const char* format, ...) {
  if (verbosity() == Verbosity::quiet) return;
  std::va_list arguments;
  va_start(arguments, format);
  print_line(stdout, format, arguments);
  va_end(arguments);
}

void note(const char* format, ...) {
  if (verbosity() == Verbosity::quiet) return;
  std::va_list arguments;
  va_start(arguments, format);
  print_line(stderr, format, arguments);
  va_end(arguments);
}

void detail(const char* format, ...) {
  if (verbosity() != Verbosity::verbose) return;
  std::va_list arguments;
  va_start(arguments, format);
  print_line(stderr, format, arguments);
  va_end(arguments);
}

}  // namespace relume
