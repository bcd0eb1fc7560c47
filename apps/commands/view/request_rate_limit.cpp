// Implementation of the token bucket (request_rate_limit.hpp).
#include "commands/view/request_rate_limit.hpp"

#include <algorithm>
#include <chrono>

namespace relume {

RequestRateLimit::RequestRateLimit(double per_second)
    : per_second_(per_second), tokens_(per_second), last_(Clock::now()) {}

bool RequestRateLimit::admit() {
  const std::lock_guard<std::mutex> lock(mutex_);
  const Clock::time_point now = Clock::now();
  tokens_ = std::min(per_second_,
                     tokens_ + per_second_ * std::chrono::duration<double>(now - last_).count());
  last_ = now;
  if (tokens_ < 1) return false;
  tokens_ -= 1;
  return true;
}

}  // namespace relume
