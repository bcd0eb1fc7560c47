// The request rate cap of `relume view`: one token bucket for the whole server, refilled at
// `per_second` tokens a second and holding at most one second's worth, so a page dragging at 60
// frames/s is never refused under the default cap while a runaway script gets HTTP 429.
#pragma once

#include <mutex>

#include "core/elapsed_time.hpp"

namespace relume {

class RequestRateLimit {
 public:
  // per_second > 0.
  explicit RequestRateLimit(double per_second);

  // Takes a token; false when none is left (the request is to be refused). Thread-safe.
  bool admit();

  double per_second() const { return per_second_; }

 private:
  std::mutex mutex_;
  double per_second_;
  double tokens_;
  Clock::time_point last_;
};

}  // namespace relume
