// Implementation of the interruption flag declared in interruption.hpp.
#include "core/interruption.hpp"

#include <atomic>
#include <relume/error.hpp>

namespace relume {
namespace {

// Lock-free, hence safe to store from a signal handler.
std::atomic<bool> requested{false};
static_assert(std::atomic<bool>::is_always_lock_free);

}  // namespace

void request_interruption() noexcept { requested.store(true, std::memory_order_relaxed); }

void clear_interruption() noexcept { requested.store(false, std::memory_order_relaxed); }

bool interruption_requested() noexcept { return requested.load(std::memory_order_relaxed); }

void throw_if_interrupted() {
  if (interruption_requested()) throw Interrupted();
}

}  // namespace relume
