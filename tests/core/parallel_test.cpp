// Tests of parallel_for's limits: --threads has an upper bound, and a thread the system refuses
// (here: an address-space limit too small for the stacks) makes the loop run on fewer workers
// instead of aborting.
#include "core/parallel.hpp"

#include <sys/resource.h>

#include <atomic>
#include <fstream>
#include <relume/error.hpp>
#include <vector>

#include "support/test_support.hpp"

namespace relume {
namespace {

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
