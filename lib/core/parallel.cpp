// Implementation of the dynamic parallel loop declared in parallel.hpp.
#include "core/parallel.hpp"

#include <sched.h>

#include <algorithm>
#include <atomic>
#include <exception>
#include <mutex>
#include <relume/error.hpp>
#include <string>
#include <system_error>
#include <thread>
#include <vector>

namespace relume {

unsigned resolve_thread_count(unsigned requested) {
  if (requested > max_worker_threads)
    throw Error("--threads " + std::to_string(requested) + " is more than the " +
                std::to_string(max_worker_threads) + " worker threads relume runs at most");
  if (requested > 0) return requested;
  return std::max(1u, std::thread::hardware_concurrency());
}

unsigned cores_of_this_thread() {
  cpu_set_t cores;
  if (sched_getaffinity(0, sizeof cores, &cores) != 0)
    return std::max(1u, std::thread::hardware_concurrency());
  return unsigned(CPU_COUNT(&cores));
}

void parallel_for(std::size_t count, unsigned threads,
                  const std::function<void(std::size_t, unsigned)>& body) {
  threads = static_cast<unsigned>(std::min<std::size_t>(resolve_thread_count(threads), count));
  if (threads <= 1) {
    for (std::size_t i = 0; i < count; ++i) body(i, 0);
    return;
  }
  std::atomic<std::size_t> next{0};
  std::atomic<bool> failed{false};
  std::exception_ptr first_error;
  std::mutex error_mutex;
  // Indices are taken in runs of `chunk`: one at a time while there are few (uneven work balances
  // itself), about 64 runs per worker when there are many (per-pixel bodies, where taking each
  // index from the shared counter would cost more than the body).
  const std::size_t chunk = std::max<std::size_t>(1, count / (std::size_t(threads) * 64));
  auto work = [&](unsigned worker) {
    for (std::size_t first = next.fetch_add(chunk); first < count && !failed;
         first = next.fetch_add(chunk)) {
      const std::size_t last = std::min(count, first + chunk);
      try {
        for (std::size_t i = first; i < last && !failed; ++i) body(i, worker);
      } catch (...) {
        std::lock_guard lock(error_mutex);
        if (!first_error) first_error = std::current_exception();
        failed = true;
      }
    }
  };
  std::vector<std::thread> pool;
  pool.reserve(threads - 1);
  for (unsigned w = 1; w < threads; ++w) {
    try {
      pool.emplace_back(work, w);
    } catch (const std::system_error&) {
      break;  // no more threads to be had: the ones started (and this one) do the work
    }
  }
  work(0);
  for (auto& t : pool) t.join();
  if (first_error) std::rethrow_exception(first_error);
}

}  // namespace relume
