// parallel_for_test.cpp -- the offline tool's loop over independent jobs
// (offline/model/parallel_for.h): every index runs once; a loop nested in
// one that runs on several threads runs serially on its caller's thread
// (the diagnosis's candidate fits hold the cores, each fit's records then
// run in turn), while one nested in a serial loop may use its threads; an
// exception reaches the caller and leaves no nesting count behind.
#include <gtest/gtest.h>

#include <atomic>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>
#include <vector>

#include "model/parallel_for.h"

namespace {

using rtb::parallel_depth;
using rtb::parallel_for;

TEST(ParallelFor, EveryIndexRunsOnce) {
  std::vector<std::atomic<int>> hits(1000);
  parallel_for(hits.size(), 4, [&](size_t k) { hits[k].fetch_add(1); });
  for (const auto &h : hits) EXPECT_EQ(h.load(), 1);
  EXPECT_EQ(parallel_depth(), 0);
}

TEST(ParallelFor, NestedInAParallelLoopRunsOnTheCallersThread) {
  std::mutex mu;
  int mismatched = 0, inner_runs = 0, max_inner_depth = 0;
  parallel_for(4, 2, [&](size_t) {
    const std::thread::id outer = std::this_thread::get_id();
    EXPECT_EQ(parallel_depth(), 1);
    parallel_for(8, 4, [&](size_t) {
      std::lock_guard<std::mutex> lock(mu);
      ++inner_runs;
      if (std::this_thread::get_id() != outer) ++mismatched;
      max_inner_depth = std::max(max_inner_depth, parallel_depth());
    });
  });
  EXPECT_EQ(inner_runs, 32);
  EXPECT_EQ(mismatched, 0);
  EXPECT_EQ(max_inner_depth, 1);  // the serial inner loop counts no level of its own
  EXPECT_EQ(parallel_depth(), 0);
}

TEST(ParallelFor, NestedInASerialLoopKeepsItsThreads) {
  // One thread outside (threads = 1, or a single job): nothing is held, the
  // inner loop's bodies see no enclosing parallel level and it may spread.
  for (int outer_threads : {1, 4}) {
    parallel_for(1, outer_threads, [&](size_t) {
      EXPECT_EQ(parallel_depth(), 0);
      parallel_for(4, 2, [&](size_t) { EXPECT_EQ(parallel_depth(), 1); });
    });
  }
  EXPECT_EQ(parallel_depth(), 0);
}

TEST(ParallelFor, AnExceptionReachesTheCallerAndTheCountIsRestored) {
  EXPECT_THROW(parallel_for(10, 2,
                            [&](size_t k) {
                              if (k == 3) throw std::runtime_error("job 3");
                            }),
               std::runtime_error);
  EXPECT_EQ(parallel_depth(), 0);
  std::set<size_t> seen;
  std::mutex mu;
  parallel_for(6, 2, [&](size_t k) {
    std::lock_guard<std::mutex> lock(mu);
    seen.insert(k);
  });
  EXPECT_EQ(seen.size(), 6u);
}

}  // namespace
