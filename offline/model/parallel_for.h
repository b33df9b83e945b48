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

// The first exception thrown by a body is rethrown after all threads join.
template <class F>
void parallel_for(size_t n, int threads, F &&body) {
  std::atomic<size_t> next{0};
  std::exception_ptr err;
  std::atomic<bool> failed{false};
  auto worker = [&]() {
    for (size_t k; (k = next.fetch_add(1)) < n;) {
      try {
        body(k);
      } catch (...) {
        if (!failed.exchange(true)) err = std::current_exception();
      }
    }
  };
  std::vector<std::thread> pool;
  for (int i = 1; i < std::min<int>(threads, (int)n); ++i) pool.emplace_back(worker);
  worker();
  for (std::thread &t : pool) t.join();
  if (err) std::rethrow_exception(err);
}

// Threads for the offline tool: the machine's cores, at most 8.
int default_threads();

}  // namespace rtb

#endif
