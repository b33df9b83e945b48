// realtime_test.cpp -- real-time guarantees of the public API:
//   * no heap allocation in rtb_state_init, rtb_step, rtb_evaluate, rtb_commit
//     (RT with both integrators, STS; core model and every extension on);
//   * bounded work, checked against what the solver must achieve rather than
//     against its own loop guards: with the default settings every call
//     converges within a measured iteration count far below the caps, and an
//     imposed cap is reported (RTB_NOT_CONVERGED, exact iteration count).
//
// Allocation counting. The test binary replaces the global allocation
// functions and counts calls while a measured region is open:
//   * normal builds: malloc/calloc/realloc/free (forwarding to glibc's
//     __libc_malloc & co.) AND every global operator new/delete;
//   * AddressSanitizer builds: ASan intercepts malloc and friends, and a
//     malloc defined in the executable would bypass its allocator (and break
//     its free/realloc bookkeeping), so malloc is NOT replaced there. We count
//     operator new/delete (replaced here, forwarding to the intercepted malloc)
//     plus, as a second net, ASan's own allocation hooks
//     (__sanitizer_install_malloc_and_free_hooks), which see every malloc,
//     calloc, realloc and new made through the sanitizer allocator.
// A self-test checks that the counter really sees malloc and operator new, so
// a broken override cannot make the zero-allocation tests pass vacuously.
#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstddef>
#include <cstdlib>
#include <cstring>
#include <new>

#include "physics_helpers.h"
#include "rt_bushing/rt_bushing.h"
#include "test_numbers.h"

#if defined(__SANITIZE_ADDRESS__)
#define RTB_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define RTB_TEST_ASAN 1
#endif
#endif

namespace {

std::atomic<bool> g_counting{false};
std::atomic<long> g_allocs{0};
std::atomic<long> g_frees{0};

inline void note_alloc() {
  if (g_counting.load(std::memory_order_relaxed)) g_allocs.fetch_add(1, std::memory_order_relaxed);
}
inline void note_free(const void *p) {
  if (p && g_counting.load(std::memory_order_relaxed))
    g_frees.fetch_add(1, std::memory_order_relaxed);
}

}  // namespace

// ------------------------------------------------------------ C allocator
#if defined(RTB_TEST_ASAN)
extern "C" int __sanitizer_install_malloc_and_free_hooks(
    void (*malloc_hook)(const volatile void *, std::size_t),
    void (*free_hook)(const volatile void *));
namespace {
void asan_malloc_hook(const volatile void *, std::size_t) { note_alloc(); }
void asan_free_hook(const volatile void *p) { note_free(const_cast<const void *>(p)); }
[[maybe_unused]] const int g_hooks_installed =
    __sanitizer_install_malloc_and_free_hooks(asan_malloc_hook, asan_free_hook);
}  // namespace
#define RTB_TEST_COUNTS_MALLOC 1
#elif defined(__GLIBC__)
extern "C" {
void *__libc_malloc(std::size_t);
void *__libc_calloc(std::size_t, std::size_t);
void *__libc_realloc(void *, std::size_t);
void __libc_free(void *);

void *malloc(std::size_t n) {
  note_alloc();
  return __libc_malloc(n);
}
void *calloc(std::size_t n, std::size_t m) {
  note_alloc();
  return __libc_calloc(n, m);
}
void *realloc(void *p, std::size_t n) {
  note_alloc();
  return __libc_realloc(p, n);
}
void free(void *p) {
  note_free(p);
  __libc_free(p);
}
}  // extern "C"
#define RTB_TEST_COUNTS_MALLOC 1
#endif

// ------------------------------------------------------------ C++ allocator
// All replaceable global forms; they forward to malloc/aligned_alloc/free.
namespace {
void *counted_new(std::size_t n) {
  note_alloc();
  if (n == 0) n = 1;
  void *p = std::malloc(n);
  if (!p) throw std::bad_alloc();
  return p;
}
void *counted_new_aligned(std::size_t n, std::align_val_t al) {
  note_alloc();
  std::size_t a = static_cast<std::size_t>(al);
  if (a < sizeof(void *)) a = sizeof(void *);
  std::size_t sz = (n + a - 1) / a * a;
  if (sz == 0) sz = a;
  void *p = std::aligned_alloc(a, sz);
  if (!p) throw std::bad_alloc();
  return p;
}
void counted_delete(void *p) noexcept {
  note_free(p);
  std::free(p);
}
}  // namespace

void *operator new(std::size_t n) { return counted_new(n); }
void *operator new[](std::size_t n) { return counted_new(n); }
void *operator new(std::size_t n, const std::nothrow_t &) noexcept {
  try { return counted_new(n); } catch (...) { return nullptr; }
}
void *operator new[](std::size_t n, const std::nothrow_t &) noexcept {
  try { return counted_new(n); } catch (...) { return nullptr; }
}
void *operator new(std::size_t n, std::align_val_t a) { return counted_new_aligned(n, a); }
void *operator new[](std::size_t n, std::align_val_t a) { return counted_new_aligned(n, a); }
void *operator new(std::size_t n, std::align_val_t a, const std::nothrow_t &) noexcept {
  try { return counted_new_aligned(n, a); } catch (...) { return nullptr; }
}
void *operator new[](std::size_t n, std::align_val_t a, const std::nothrow_t &) noexcept {
  try { return counted_new_aligned(n, a); } catch (...) { return nullptr; }
}
void operator delete(void *p) noexcept { counted_delete(p); }
void operator delete[](void *p) noexcept { counted_delete(p); }
void operator delete(void *p, std::size_t) noexcept { counted_delete(p); }
void operator delete[](void *p, std::size_t) noexcept { counted_delete(p); }
void operator delete(void *p, const std::nothrow_t &) noexcept { counted_delete(p); }
void operator delete[](void *p, const std::nothrow_t &) noexcept { counted_delete(p); }
void operator delete(void *p, std::align_val_t) noexcept { counted_delete(p); }
void operator delete[](void *p, std::align_val_t) noexcept { counted_delete(p); }
void operator delete(void *p, std::size_t, std::align_val_t) noexcept { counted_delete(p); }
void operator delete[](void *p, std::size_t, std::align_val_t) noexcept { counted_delete(p); }
void operator delete(void *p, std::align_val_t, const std::nothrow_t &) noexcept {
  counted_delete(p);
}
void operator delete[](void *p, std::align_val_t, const std::nothrow_t &) noexcept {
  counted_delete(p);
}

namespace {

// RAII measured region. Nothing inside may use gtest assertions (a failing
// assertion allocates); results are checked after the region closes.
class AllocRegion {
 public:
  AllocRegion() {
    g_allocs.store(0);
    g_frees.store(0);
    g_counting.store(true);
  }
  ~AllocRegion() { stop(); }
  void stop() { g_counting.store(false); }
  long allocs() const { return g_allocs.load(); }
  long frees() const { return g_frees.load(); }
};

// Opaque to the optimiser, so allocation calls below cannot be elided.
void *(*volatile g_malloc_fn)(std::size_t) = std::malloc;
void (*volatile g_free_fn)(void *) = std::free;
void *(*volatile g_new_fn)(std::size_t) = ::operator new;
void (*volatile g_delete_fn)(void *) noexcept = ::operator delete;

TEST(RealtimeAllocCounter, SeesMallocAndOperatorNew) {
#if defined(RTB_TEST_COUNTS_MALLOC)
  {
    AllocRegion r;
    void *p = g_malloc_fn(64);
    g_free_fn(p);
    r.stop();
    EXPECT_GE(r.allocs(), 1) << "malloc is not counted: the allocation tests would be vacuous";
    EXPECT_GE(r.frees(), 1);
  }
#endif
  {
    AllocRegion r;
    void *p = g_new_fn(64);
    g_delete_fn(p);
    r.stop();
    EXPECT_GE(r.allocs(), 1) << "operator new is not counted";
    EXPECT_GE(r.frees(), 1);
  }
  {
    AllocRegion r;
    r.stop();
    EXPECT_EQ(r.allocs(), 0);
  }
}

// ------------------------------------------------------------ scenarios
struct InputScenario {
  const char *name;
  int model;
  int integrator;
  int cells;
  bool extensions;
};

rtb_params make_params(const InputScenario &sc) {
  rtb_params p;
  rtb_params_default(&p, sc.model);
  p.integrator = sc.integrator;
  p.cells = sc.cells;
  if (sc.extensions) rtbtest::add_extensions(&p);
  return p;
}

int stages(const rtb_params &p) {
  return p.model == RTB_MODEL_RT && p.integrator == RTB_INTEGRATOR_SDIRK2 ? 2 : 1;
}

// Iterations of the committed response (rtb_state::last_iterations) and of
// the whole call including clearance trials (rtb_step_info::iterations) that
// this input needs at most with the default settings, measured with
// rtb_step_ex (RT_SDIRK2: 7 / 45 with a clearance; RT_BE: 4 / 29; STS: 12 /
// 37), with about 30 % margin. The loop caps are 40 per stage for RT and
// 2N + 5 for STS: a solver that degrades towards them fails here first.
int expected_max_last(const rtb_params &p) { return p.model == RTB_MODEL_STS ? 16 : 5 * stages(p); }
int expected_max_total(const rtb_params &p) {
  if (p.backlash == 0.0) return expected_max_last(p);
  return p.model == RTB_MODEL_STS ? 48 : 30 * stages(p);
}


// Displacement history: a multi-frequency sine with amplitude sweeps, so the
// RT dashpots go through slow and fast phases and the backlash opens/closes.
double scenario_input(long i, double dt) {
  const double t = static_cast<double>(i) * dt;
  return 1.5 * std::sin(kTwoPi * 3.0 * t) * (0.5 + 0.5 * std::sin(kTwoPi * 0.1 * t)) +
         0.02 * std::sin(kTwoPi * 47.0 * t);
}

struct RunResult {
  long calls = 0;
  long allocs = 0, frees = 0;
  long errors = 0, not_converged = 0, nonfinite = 0;
  int max_iterations = 0;        // rtb_state::last_iterations
  int min_iterations = 1 << 30;
  int max_total_iterations = 0;  // rtb_step_info::iterations
  // Converged calls that iterated within one response: with a cap of one
  // Newton iteration only a clearance search, whose responses each start
  // from the last, can accumulate enough iterations to converge.
  long converged_in_one_response = 0;
  int first_error = 0;
  long first_error_step = -1;
};

// 10^5 API calls: alternating rtb_step and rtb_evaluate (+ rtb_commit), with
// state init inside the measured region.
RunResult run(const rtb_params &p, const rtb_settings *set, long calls) {
  static rtb_state s, trial;  // static: no large stack frame, no heap
  RunResult res;
  const double dt = 1e-3;
  AllocRegion region;
  rtb_status st = rtb_state_init(&s, &p, 0.0);
  if (st != RTB_OK) {
    res.errors = 1;
    res.first_error = st;
    res.first_error_step = 0;
  }
  for (long i = 1; i <= calls && st == RTB_OK; ++i) {
    double f = 0.0, df = 0.0;
    const double x = scenario_input(i, dt);
    rtb_status r;
    rtb_step_info info;
    info.iterations = 0;
    ++res.calls;
    if (i % 2 == 0) {
      r = rtb_step_ex(&s, &p, set, x, dt, &f, &info);
    } else {
      // A host's implicit loop: a few trial evaluations, then commit.
      r = rtb_evaluate(&s, &p, set, x + 1e-4, dt, &trial, &f, &df);
      if (r >= 0) r = rtb_evaluate_ex(&s, &p, set, x, dt, &trial, &f, &df, &info);
      if (r >= 0 && rtb_commit(&s, &trial) != RTB_OK) r = RTB_ERR_STATE;
    }
    if (r < 0) {
      if (res.errors++ == 0) {
        res.first_error = r;
        res.first_error_step = i;
      }
      continue;
    }
    if (r == RTB_NOT_CONVERGED) ++res.not_converged;
    if (r == RTB_OK && info.iterations > 0 && info.clearance_iterations <= 1)
      ++res.converged_in_one_response;
    if (!std::isfinite(f) || !std::isfinite(df)) ++res.nonfinite;
    if (s.last_iterations > res.max_iterations) res.max_iterations = s.last_iterations;
    if (s.last_iterations < res.min_iterations) res.min_iterations = s.last_iterations;
    if (info.iterations > res.max_total_iterations) res.max_total_iterations = info.iterations;
  }
  region.stop();
  res.allocs = region.allocs();
  res.frees = region.frees();
  return res;
}

class RealtimeScenario : public ::testing::TestWithParam<InputScenario> {};

constexpr long kCalls = 100000;

TEST_P(RealtimeScenario, NoHeapAndBoundedWork) {
  const InputScenario sc = GetParam();
  const rtb_params p = make_params(sc);
  ASSERT_EQ(rtb_params_validate(&p), RTB_OK);

  const RunResult res = run(p, nullptr, kCalls);
  EXPECT_EQ(res.allocs, 0) << sc.name << ": heap allocations during init + " << kCalls << " calls";
  EXPECT_EQ(res.frees, 0) << sc.name << ": heap frees during the measured region";
  EXPECT_EQ(res.errors, 0) << sc.name << ": first error " << res.first_error << " ("
                           << rtb_status_message(static_cast<rtb_status>(res.first_error))
                           << ") at call " << res.first_error_step;
  EXPECT_EQ(res.nonfinite, 0) << sc.name;
  EXPECT_EQ(res.not_converged, 0) << sc.name << ": the default settings must converge here";
  EXPECT_LE(res.max_iterations, expected_max_last(p)) << sc.name;
  EXPECT_LE(res.max_total_iterations, expected_max_total(p)) << sc.name;
  EXPECT_GT(res.max_iterations, 0) << sc.name << ": last_iterations never set";
}

// Forcing the iteration cap: with max_iter = 1 and an unreachable tolerance
// the RT solve must stop at the cap and say so: (almost) every call returns
// RTB_NOT_CONVERGED with a finite force, and the committed response reports
// exactly one iteration per stage (fewer would mean it did not iterate, more
// that the cap was ignored). STS does not use max_iter: its active set still
// terminates as with the defaults.
TEST_P(RealtimeScenario, IterationCapRespected) {
  const InputScenario sc = GetParam();
  const rtb_params p = make_params(sc);
  rtb_settings set;
  rtb_settings_default(&set);
  set.max_iter = 1;
  set.tol = 1e-16;
  set.max_backtrack = 2;

  const RunResult res = run(p, &set, 2000);
  EXPECT_EQ(res.allocs, 0) << sc.name;
  EXPECT_EQ(res.errors, 0) << sc.name << ": first error " << res.first_error << " at call "
                           << res.first_error_step;
  EXPECT_EQ(res.nonfinite, 0) << sc.name;
  if (p.model == RTB_MODEL_RT) {
    // Measured: every call but the one at rest with a clearance (0 iterations)
    // and a few clearance searches (the warm-started responses converge: 16 of
    // 2000 calls on RT_BE_ext with the Chebyshev step, 6 without).
    EXPECT_EQ(res.converged_in_one_response, 0) << sc.name;
    EXPECT_GE(res.not_converged, res.calls - 25) << sc.name;
    EXPECT_EQ(res.max_iterations, stages(p)) << sc.name;
  } else {
    EXPECT_LE(res.max_iterations, expected_max_last(p)) << sc.name;
  }
}

const InputScenario kScenarios[] = {
    {"RT_SDIRK2", RTB_MODEL_RT, RTB_INTEGRATOR_SDIRK2, RTB_DEFAULT_CELLS, false},
    {"RT_BE", RTB_MODEL_RT, RTB_INTEGRATOR_BE, RTB_DEFAULT_CELLS, false},
    {"STS", RTB_MODEL_STS, RTB_INTEGRATOR_SDIRK2, RTB_DEFAULT_CELLS, false},
    {"RT_SDIRK2_ext", RTB_MODEL_RT, RTB_INTEGRATOR_SDIRK2, RTB_DEFAULT_CELLS, true},
    {"RT_BE_ext", RTB_MODEL_RT, RTB_INTEGRATOR_BE, RTB_DEFAULT_CELLS, true},
    {"STS_ext", RTB_MODEL_STS, RTB_INTEGRATOR_SDIRK2, RTB_DEFAULT_CELLS, true},
    {"RT_SDIRK2_N32_ext", RTB_MODEL_RT, RTB_INTEGRATOR_SDIRK2, RTB_MAX_CELLS, true},
    {"STS_N32", RTB_MODEL_STS, RTB_INTEGRATOR_SDIRK2, RTB_MAX_CELLS, false},
};

INSTANTIATE_TEST_SUITE_P(All, RealtimeScenario, ::testing::ValuesIn(kScenarios),
                         [](const ::testing::TestParamInfo<InputScenario> &info) {
                           return std::string(info.param.name);
                         });

// Error paths must not allocate either (a host may hit them every step).
TEST(RealtimeErrors, ErrorPathsDoNotAllocate) {
  rtb_params p;
  rtb_params_default(&p, RTB_MODEL_RT);
  rtb_state s, trial;
  ASSERT_EQ(rtb_state_init(&s, &p, 0.0), RTB_OK);
  rtb_params bad = p;
  bad.alpha = 1.5;
  long errors = 0;
  double f = 0.0, df = 0.0;
  const char *msg = nullptr;
  AllocRegion region;
  for (int i = 0; i < 1000; ++i) {
    errors += rtb_step(&s, &p, nullptr, NAN, 1e-3, &f) < 0;
    errors += rtb_step(&s, &p, nullptr, 0.1, -1.0, &f) < 0;
    errors += rtb_step(&s, &bad, nullptr, 0.1, 1e-3, &f) < 0;
    errors += rtb_evaluate(&s, &p, nullptr, INFINITY, 1e-3, &trial, &f, &df) < 0;
    errors += rtb_state_init(&trial, &bad, 0.0) < 0;
    msg = rtb_status_message(RTB_ERR_ALPHA);
  }
  region.stop();
  EXPECT_EQ(region.allocs(), 0);
  EXPECT_EQ(errors, 5000);
  EXPECT_NE(msg, nullptr);
}

// The six-axis calls, success and error paths alike.
TEST(RealtimeSixAxis, NoHeap) {
  rtb_bushing6_params p;
  ASSERT_EQ(rtb_bushing6_params_default(&p, RTB_MODEL_RT), RTB_OK);
  rtb_params_default(&p.axis[RTB_AXIS_Z], RTB_MODEL_STS);
  p.active[RTB_AXIS_RZ] = 0;
  rtb_bushing6_state s, trial;
  double x[RTB_AXES] = {0}, F[RTB_AXES], K[RTB_AXES];
  long ok = 0, errors = 0;
  AllocRegion region;
  ok += rtb_bushing6_init(&s, &p, nullptr, nullptr) == RTB_OK;
  for (int i = 1; i <= 200; ++i) {
    for (int a = 0; a < RTB_AXES; ++a) x[a] = 0.3 * std::sin(0.05 * i * (a + 1));
    ok += rtb_bushing6_evaluate(&s, &p, nullptr, x, 1e-3, &trial, F, K, nullptr) >= 0;
    ok += rtb_bushing6_step(&s, &p, nullptr, x, 1e-3, F, nullptr) >= 0;
    x[RTB_AXIS_Y] = NAN;
    errors += rtb_bushing6_step(&s, &p, nullptr, x, 1e-3, F, nullptr) < 0;
  }
  region.stop();
  EXPECT_EQ(region.allocs(), 0);
  EXPECT_EQ(ok, 401);
  EXPECT_EQ(errors, 200);
}

}  // namespace
