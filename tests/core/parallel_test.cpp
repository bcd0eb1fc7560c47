// Tests of parallel_for: every index is visited once whatever the count and threads (indices are
// taken in runs when there are many), few indices are taken one at a time, a body's exception
// is rethrown; --threads has an upper bound, and a thread the system refuses (here: an
// address-space limit too small for the stacks) makes the loop run on fewer workers instead of
// aborting.
#include "core/parallel.hpp"

#include <sys/resource.h>

#include <atomic>
#include <chrono>
#include <fstream>
#include <relume/error.hpp>
#include <thread>
#include <vector>

#include "support/test_support.hpp"

namespace relume {
namespace {

TEST(ParallelFor, VisitsEveryIndexOnceForAnyCountAndThreads) {
  for (const std::size_t count : {0u, 1u, 127u, 128u, 129u, 1000u, 100003u})
    for (const unsigned threads : {1u, 2u, 3u, 8u}) {
      std::vector<std::atomic<int>> visits(count);
      parallel_for(count, threads, [&](std::size_t i, unsigned worker) {
        EXPECT_LT(worker, threads);
        ++visits[i];
      });
      for (std::size_t i = 0; i < count; ++i)
        ASSERT_EQ(visits[i].load(), 1)
            << "index " << i << " of " << count << ", " << threads << " threads";
    }
}

// Four indices on four threads: each worker takes one, so all four bodies run at the same time
// (a worker that took two would leave the others waiting for a fourth that never starts).
TEST(ParallelFor, FewIndicesAreTakenOneAtATime) {
  std::atomic<int> running{0}, met{0};
  parallel_for(4, 4, [&](std::size_t, unsigned) {
    ++running;
    const auto until = std::chrono::steady_clock::now() + std::chrono::seconds(20);
    while (running.load() < 4 && std::chrono::steady_clock::now() < until)
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
    if (running.load() == 4) ++met;
  });
  EXPECT_EQ(met.load(), 4);
}

TEST(ParallelFor, RethrowsTheFirstErrorAndStops) {
  std::atomic<std::size_t> visited{0};
  EXPECT_THAT(testing::error_message([&] {
                parallel_for(1000000, 2, [&](std::size_t i, unsigned) {
                  ++visited;
                  if (i == 10) throw Error("index 10 failed");
                });
              }),
              ::testing::HasSubstr("index 10 failed"));
  EXPECT_LT(visited.load(), 1000000u);
}

TEST(ParallelFor, ThreadCountHasAnUpperBound) {
  EXPECT_EQ(resolve_thread_count(max_worker_threads), max_worker_threads);
  EXPECT_THAT(testing::error_message([] { resolve_thread_count(max_worker_threads + 1); }),
              ::testing::HasSubstr("--threads 1025 is more than the 1024"));
}

TEST(ParallelFor, RefusedThreadsMeanFewerWorkersNotACrash) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer reserves terabytes of address space: no RLIMIT_AS test";
#endif
  EXPECT_EXIT(
      {
        // 1024 threads need 8 GB of stack address space; allow 512 MB more than in use.
        rlimit limit{};
        std::ifstream statm("/proc/self/statm");
        std::size_t pages = 0;
        statm >> pages;
        limit.rlim_cur = limit.rlim_max = pages * 4096 + (512u << 20);
        ::setrlimit(RLIMIT_AS, &limit);
        std::vector<std::atomic<int>> visits(20000);
        std::atomic<unsigned> highest_worker{0};
        parallel_for(visits.size(), max_worker_threads, [&](std::size_t i, unsigned worker) {
          ++visits[i];
          unsigned seen = highest_worker.load();
          while (worker > seen && !highest_worker.compare_exchange_weak(seen, worker)) {
          }
        });
        for (const auto& v : visits)
          if (v != 1) std::exit(1);
        // Fewer workers than asked ran: some thread starts were refused.
        std::exit(highest_worker.load() < max_worker_threads - 1 ? 42 : 2);
      },
      ::testing::ExitedWithCode(42), "");
}

}  // namespace
}  // namespace relume
