/* step_bench.cpp -- per-step latency and throughput of rtb_step / rtb_evaluate.
 *
 * Input: the realistic host signal of docs/benchmarks.md, a 10 Hz, 1 mm sine
 * sampled at dt = 1e-3 s plus a small Gaussian random component (sigma 10 um,
 * fixed seed), parameters from rtb_params_default (the paper's section 3.4
 * set) with N overridden.
 *
 * Latency benchmarks (BM_Latency/<variant>/<N>): after a warm-up of
 * RTB_BENCH_WARMUP steps (default 100000) every one of RTB_BENCH_STEPS steps
 * (default 1000000) is timed individually with std::chrono::steady_clock
 * (clock_gettime(CLOCK_MONOTONIC) through the vDSO on Linux). The raw
 * timings include one clock read (reported as clock_overhead_ns, not
 * subtracted). Exported user counters:
 *   median_ns, p99_ns, p999_ns, worst_ns, mean_ns   per-step wall time
 *   worst_replay_ns   median of 1001 replays of the step that was worst
 *                     (same state, same input): tells an algorithmic worst
 *                     case from an OS interruption
 *   iter_max, iter_mean   Newton iterations per step (stages summed), or
 *                     active-set iterations for STS
 *   maxiter_replay_ns median of 1001 replays of the step with most iterations
 *   not_converged     steps that returned RTB_NOT_CONVERGED (committed anyway)
 *   errors            steps that returned an error (< 0; state not advanced):
 *                     the label then says INVALID
 *   median_filtered_ns, p99_filtered_ns, worst_filtered_ns
 *                     the same statistics of min over RTB_BENCH_REPEAT
 *                     (default 3) timings of each step (the step is re-run
 *                     from the saved state with the same input): an estimate
 *                     of the algorithmic cost with OS interruptions filtered
 * Variants: 0 RT/SDIRK2 rtb_step, 1 RT/BE rtb_step, 2 STS rtb_step,
 *           3 RT/SDIRK2 rtb_evaluate with dF/dx + rtb_commit (host Jacobian
 *           path; one evaluate per step).
 *
 * Throughput benchmarks (BM_Throughput/<variant>/<N>): plain loop, items per
 * second = steps per second.
 */
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <random>
#include <string>
#include <vector>

#include "bench/bench_settings.h"
#include "rt_bushing/rt_bushing.h"

namespace {

constexpr double kDt = 1e-3;
constexpr double kAmp = 1.0;     /* mm */
constexpr double kFreq = 10.0;   /* Hz */
constexpr double kNoise = 0.01;  /* mm, standard deviation */

long env_long(const char *name, long def) {
  const char *s = std::getenv(name);
  if (!s || !*s) return def;
  const long v = std::strtol(s, nullptr, 10);
  return v > 0 ? v : def;
}

long steps_measured() { return env_long("RTB_BENCH_STEPS", 1000000); }
long steps_warmup() { return env_long("RTB_BENCH_WARMUP", 100000); }

/* x_i = A sin(2 pi f i dt) + N(0, sigma), i = 1..n. */
std::vector<double> make_input(long n, uint64_t seed = 12345) {
  std::mt19937_64 gen(seed);
  std::normal_distribution<double> noise(0.0, kNoise);
  std::vector<double> x(n);
  for (long i = 0; i < n; ++i)
    x[i] = kAmp * std::sin(2.0 * M_PI * kFreq * (i + 1) * kDt) + noise(gen);
  return x;
}

enum Variant { kSdirk2 = 0, kBE = 1, kSTS = 2, kEvalSdirk2 = 3 };

const char *variant_name(int v) {
  switch (v) {
    case kSdirk2: return "RT-SDIRK2";
    case kBE: return "RT-BE";
    case kSTS: return "STS";
    case kEvalSdirk2: return "RT-SDIRK2-evaluate+dFdx";
  }
  return "?";
}

rtb_params make_params(int variant, int cells) {
  rtb_params p;
  rtb_params_default(&p, variant == kSTS ? RTB_MODEL_STS : RTB_MODEL_RT);
  p.cells = cells;
  p.integrator = variant == kBE ? RTB_INTEGRATOR_BE : RTB_INTEGRATOR_SDIRK2;
  return p;
}

/* One host step of the given variant. */
inline rtb_status do_step(int variant, rtb_state *s, const rtb_params *p, double x,
                          double *F) {
  if (variant == kEvalSdirk2) {
    rtb_state trial;
    double dF;
    rtb_status st = rtb_evaluate(s, p, bench_settings(), x, kDt, &trial, F, &dF);
    benchmark::DoNotOptimize(dF);
    if (st >= 0) rtb_commit(s, &trial);
    return st;
  }
  return rtb_step(s, p, bench_settings(), x, kDt, F);
}

using Clock = std::chrono::steady_clock;

inline double ns_between(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::nano>(b - a).count();
}

double clock_overhead_ns() {
  static double cached = -1.0;
  if (cached >= 0.0) return cached;
  std::vector<double> t(200000);
  for (double &v : t) {
    const auto a = Clock::now();
    const auto b = Clock::now();
    v = ns_between(a, b);
  }
  std::nth_element(t.begin(), t.begin() + t.size() / 2, t.end());
  cached = t[t.size() / 2];
  return cached;
}

/* Median wall time of replaying one step (from a saved state) 1001 times. */
double replay_ns(int variant, const rtb_state &before, const rtb_params &p, double x) {
  std::vector<double> t(1001);
  for (double &v : t) {
    rtb_state s = before;
    double F;
    const auto a = Clock::now();
    rtb_status st = do_step(variant, &s, &p, x, &F);
    const auto b = Clock::now();
    benchmark::DoNotOptimize(st);
    benchmark::DoNotOptimize(F);
    v = ns_between(a, b);
  }
  std::nth_element(t.begin(), t.begin() + t.size() / 2, t.end());
  return t[t.size() / 2];
}

double quantile(std::vector<double> sorted, double q) {
  const size_t i = std::min(sorted.size() - 1, static_cast<size_t>(q * (sorted.size() - 1) + 0.5));
  return sorted[i];
}

void BM_Latency(benchmark::State &state) {
  const int variant = static_cast<int>(state.range(0));
  const int cells = static_cast<int>(state.range(1));
  const rtb_params p = make_params(variant, cells);
  const long warm = steps_warmup(), meas = steps_measured();
  const std::vector<double> xs = make_input(warm + meas);
  rtb_state s;
  if (rtb_state_init(&s, &p, 0.0) != RTB_OK) {
    state.SkipWithError("rtb_state_init failed");
    return;
  }
  double F = 0.0;
  for (long i = 0; i < warm; ++i) do_step(variant, &s, &p, xs[i], &F);

  const long repeat = env_long("RTB_BENCH_REPEAT", 3);
  std::vector<double> lat(meas), lat_min(meas);
  std::vector<int> iters(meas);
  long i = 0, not_conv = 0, errors = 0;
  double worst = -1.0;
  long worst_i = 0, maxit_i = 0;
  int maxit = -1;
  rtb_state worst_before = s, maxit_before = s;
  for (auto _ : state) {
    const double x = xs[warm + i];
    const rtb_state before = s; /* for the replays, outside the timed region */
    const auto t0 = Clock::now();
    const rtb_status st = do_step(variant, &s, &p, x, &F);
    const auto t1 = Clock::now();
    benchmark::DoNotOptimize(F);
    const double ns = ns_between(t0, t1);
    lat[i] = ns;
    iters[i] = s.last_iterations;
    if (st == RTB_NOT_CONVERGED) ++not_conv;
    if (st < 0) ++errors;
    if (ns > worst) { worst = ns; worst_i = i; worst_before = before; }
    if (s.last_iterations > maxit) { maxit = s.last_iterations; maxit_i = i; maxit_before = before; }
    /* Re-time the same step (same state, same input) repeat-1 more times;
     * the minimum filters out interrupts and preemption. */
    double best = ns;
    for (long r = 1; r < repeat; ++r) {
      rtb_state again = before;
      double Fr;
      const auto a = Clock::now();
      const rtb_status sr = do_step(variant, &again, &p, x, &Fr);
      const auto b = Clock::now();
      benchmark::DoNotOptimize(sr);
      benchmark::DoNotOptimize(Fr);
      best = std::min(best, ns_between(a, b));
    }
    lat_min[i] = best;
    ++i;
  }
  if (i != meas) {
    state.SkipWithError("iteration count mismatch");
    return;
  }
  double sum = 0.0, isum = 0.0;
  for (long k = 0; k < meas; ++k) { sum += lat[k]; isum += iters[k]; }
  std::vector<double> sorted(lat);
  std::sort(sorted.begin(), sorted.end());

  state.counters["median_ns"] = quantile(sorted, 0.5);
  state.counters["p99_ns"] = quantile(sorted, 0.99);
  state.counters["p999_ns"] = quantile(sorted, 0.999);
  state.counters["worst_ns"] = sorted.back();
  state.counters["mean_ns"] = sum / meas;
  std::vector<double> sorted_min(lat_min);
  std::sort(sorted_min.begin(), sorted_min.end());
  state.counters["median_filtered_ns"] = quantile(sorted_min, 0.5);
  state.counters["p99_filtered_ns"] = quantile(sorted_min, 0.99);
  state.counters["worst_filtered_ns"] = sorted_min.back();
  state.counters["repeat"] = static_cast<double>(repeat);
  state.counters["worst_replay_ns"] = replay_ns(variant, worst_before, p, xs[warm + worst_i]);
  state.counters["iter_max"] = maxit;
  state.counters["iter_mean"] = isum / meas;
  state.counters["maxiter_replay_ns"] = replay_ns(variant, maxit_before, p, xs[warm + maxit_i]);
  state.counters["not_converged"] = static_cast<double>(not_conv);
  state.counters["errors"] = static_cast<double>(errors);
  state.counters["clock_overhead_ns"] = clock_overhead_ns();
  state.counters["steps"] = static_cast<double>(meas);
  /* A failed step (< 0) leaves the state unchanged, so later steps time a
   * different computation: flag the run rather than report it silently. */
  state.SetLabel(errors ? std::string(variant_name(variant)) + " INVALID: " +
                              std::to_string(errors) + " failed steps"
                        : std::string(variant_name(variant)));
}

void BM_Throughput(benchmark::State &state) {
  const int variant = static_cast<int>(state.range(0));
  const int cells = static_cast<int>(state.range(1));
  const rtb_params p = make_params(variant, cells);
  /* 100 whole periods of the sine, replayed cyclically. */
  const std::vector<double> xs = make_input(100000);
  rtb_state s;
  if (rtb_state_init(&s, &p, 0.0) != RTB_OK) {
    state.SkipWithError("rtb_state_init failed");
    return;
  }
  double F = 0.0;
  for (size_t i = 0; i < xs.size(); ++i) do_step(variant, &s, &p, xs[i], &F); /* warm-up */
  size_t i = 0;
  long errors = 0;
  for (auto _ : state) {
    if (do_step(variant, &s, &p, xs[i], &F) < 0) ++errors;
    benchmark::DoNotOptimize(F);
    if (++i == xs.size()) i = 0;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["errors"] = static_cast<double>(errors);
  state.SetLabel(errors ? std::string(variant_name(variant)) + " INVALID: " +
                              std::to_string(errors) + " failed steps"
                        : std::string(variant_name(variant)));
}

void latency_args(benchmark::internal::Benchmark *b) {
  for (int v : {kSdirk2, kBE, kSTS, kEvalSdirk2})
    for (int n : {1, 5, 15, 32}) b->Args({v, n});
  b->ArgNames({"variant", "N"});
  b->Iterations(steps_measured());
  b->Unit(benchmark::kNanosecond);
}

void throughput_args(benchmark::internal::Benchmark *b) {
  for (int v : {kSdirk2, kBE, kSTS, kEvalSdirk2})
    for (int n : {1, 5, 15, 32}) b->Args({v, n});
  b->ArgNames({"variant", "N"});
  b->Unit(benchmark::kNanosecond);
}

}  // namespace

BENCHMARK(BM_Latency)->Apply(latency_args);
BENCHMARK(BM_Throughput)->Apply(throughput_args);
