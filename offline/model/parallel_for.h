// parallel_for.h -- run body(k) for k in [0, n) on up to `threads` threads.
// Records and candidates are independent; the stepper has no shared state.
#ifndef RTB_OFFLINE_PARALLEL_FOR_H
#define RTB_OFFLINE_PARALLEL_FOR_H

#include <algorithm>
#include <atomic>
#include <exception>
#include <thread>
#include <vector>

namespace rtb {

// How many parallel_for loops that run on several threads this thread is
// inside (its own thread-local count).
inline int &parallel_depth() {
  static thread_local int depth = 0;
  return depth;
}

// The first exception thrown by a body is rethrown after all threads join.
// Nested in a loop that already runs on several threads, the inner loop runs
// serially on its caller's thread: the outer loop holds the cores (a
// diagnosis fits its candidates in parallel, and each fit's records are
// simulated in parallel only where the diagnosis runs one fit at a time).
template <class F>
void parallel_for(size_t n, int threads, F &&body) {
  std::atomic<size_t> next{0};
  std::exception_ptr err;
  std::atomic<bool> failed{false};
  const int used = parallel_depth() > 0 ? 1 : std::max(1, std::min<int>(threads, (int)n));
  auto worker = [&]() {
    if (used > 1) ++parallel_depth();
    for (size_t k; (k = next.fetch_add(1)) < n;) {
      try {
        body(k);
      } catch (...) {
        if (!failed.exchange(true)) err = std::current_exception();
      }
    }
    if (used > 1) --parallel_depth();
  };
  std::vector<std::thread> pool;
  for (int i = 1; i < used; ++i) pool.emplace_back(worker);
  worker();
  for (std::thread &t : pool) t.join();
  if (err) std::rethrow_exception(err);
}

// Threads for the offline tool: the machine's cores, at most 8.
int default_threads();

}  // namespace rtb

#endif
