// Tests of ProgressReporter's listener and interruption: a listener installed on a thread hears
// the start (0), the finish (1) and fractions in between, only from reporters made on its thread
// and only on that thread; advance() throws Interrupted once an interruption is requested, also
// from the worker threads of a parallel loop, and the flag stays set until cleared.
#include "core/progress.hpp"

#include <gtest/gtest.h>

#include <relume/error.hpp>
#include <thread>
#include <utility>
#include <vector>

#include "core/interruption.hpp"
#include "core/parallel.hpp"

namespace relume {
namespace {

struct Heard {
  std::vector<std::pair<std::string, double>> calls;
  std::vector<std::thread::id> threads;
};

ProgressListener recorder(Heard& heard) {
  return [&heard](const std::string& title, double fraction) {
    heard.calls.emplace_back(title, fraction);
    heard.threads.push_back(std::this_thread::get_id());
  };
}

TEST(ProgressListener, HearsStartFractionsAndFinishOnItsThread) {
  Heard heard;
  {
    const ProgressListenerScope scope(recorder(heard));
    ProgressReporter progress("work", 40, true);
    parallel_for(40, 2, [&](std::size_t, unsigned) {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
      progress.advance();
    });
    progress.finish();
  }
  ASSERT_GE(heard.calls.size(), 3u) << "start, at least one fraction in 0.2 s, finish";
  EXPECT_EQ(heard.calls.front(), std::make_pair(std::string("work"), 0.0));
  EXPECT_EQ(heard.calls.back(), std::make_pair(std::string("work"), 1.0));
  for (std::size_t i = 1; i < heard.calls.size(); ++i) {
    EXPECT_GE(heard.calls[i].second, heard.calls[i - 1].second);
    EXPECT_LE(heard.calls[i].second, 1.0);
  }
  for (const auto id : heard.threads) EXPECT_EQ(id, std::this_thread::get_id());
}

TEST(ProgressListener, ScopesNestAndEndAndOtherThreadsHaveNone) {
  Heard outer, inner;
  {
    const ProgressListenerScope outer_scope(recorder(outer));
    {
      const ProgressListenerScope inner_scope(recorder(inner));
      ProgressReporter("inner", 1, true).finish();
    }
    ProgressReporter("outer", 1, true).finish();
    std::thread([] { ProgressReporter("elsewhere", 1, true).finish(); }).join();
  }
  ProgressReporter("after", 1, true).finish();
  ASSERT_EQ(inner.calls.size(), 2u);
  EXPECT_EQ(inner.calls[0].first, "inner");
  ASSERT_EQ(outer.calls.size(), 2u);
  EXPECT_EQ(outer.calls[0].first, "outer");
}

TEST(Interruption, AdvanceThrowsOnceRequestedUntilCleared) {
  clear_interruption();
  ProgressReporter progress("work", 10, true);
  EXPECT_NO_THROW(progress.advance());
  request_interruption();
  EXPECT_TRUE(interruption_requested());
  EXPECT_THROW(progress.advance(), Interrupted);
  EXPECT_THROW(throw_if_interrupted(), Interrupted);
  clear_interruption();
  EXPECT_FALSE(interruption_requested());
  EXPECT_NO_THROW(progress.advance());
}

TEST(Interruption, StopsAParallelLoopFromAWorker) {
  clear_interruption();
  ProgressReporter progress("work", 100000, true);
  std::atomic<int> done{0};
  EXPECT_THROW(parallel_for(100000, 2,
                            [&](std::size_t i, unsigned) {
                              if (i == 10) request_interruption();
                              ++done;
                              progress.advance();
                            }),
               Interrupted);
  EXPECT_LT(done.load(), 100000) << "the loop went on after the request";
  clear_interruption();
}

TEST(Interruption, IsAnError) {
  try {
    throw Interrupted();
  } catch (const Error& error) {
    EXPECT_STREQ(error.what(), "interrupted");
  }
}

}  // namespace
}  // namespace relume
