// Wall-clock timing of phases (compression phases, benchmark runs): a steady clock and the
// seconds elapsed since a time point taken from it.
#pragma once

#include <chrono>

namespace relume {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace relume
