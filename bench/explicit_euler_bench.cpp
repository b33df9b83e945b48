/* explicit_euler_bench.cpp -- rt_bushing against the seed paper's real-time
 * integrator (section 3.5: explicit Euler with the host step divided by a
 * substep factor m), at equal accuracy. See reference_explicit_euler.h for the
 * scheme and its stability limit, docs/benchmarks.md for the results.
 *
 * Test case: x(t) = 1 mm sin(2 pi 10 t), host samples every 1 ms, N = 15,
 * rtb_params_default (alpha = 0.2), virgin start, 5 cycles (500 host steps).
 * Error = max |F - F_ref| over the last cycle (host samples) / max |F_ref|
 * over that cycle. Reference: rt_bushing SDIRK2 at dt = 1e-6 s fed the exact
 * sine; its own error is estimated by Richardson against dt = 2e-6 s
 * (order 2: err(1e-6) ~ |F(1e-6) - F(2e-6)| / 3). The host-rate methods only
 * see the 1 kHz samples and interpolate linearly between them; the error
 * that sampling alone causes (reference fed the interpolated samples, same
 * fine dt) is reported as sampling_floor_pct.
 *
 * BM_EE_Accuracy    (one run) the accuracy study, as counters:
 *   ref_conv_pct, sampling_floor_pct, ref_peak_N,
 *   ee_m_min          smallest m that is stable (finite AND linearly stable,
 *                     max over all substeps of h rho(D K) <= 2) and within
 *                     0.5 %; ee_m_bounded: smallest m whose run stays finite
 *   ee_err_pct, ee_h_rho_max   at ee_m_min
 *   rtb_sdirk2_err_pct, rtb_be_err_pct   one rt_bushing step per host step
 *   rtb_sdirk2_substeps, rtb_be_substeps smallest number of rt_bushing steps
 *                     per host step within 0.5 % (1 = a single step suffices)
 *   ee_err_pct_m<k>   the error for a few m around ee_m_min
 * BM_EE_HostStep      explicit Euler, m = ee_m_min, one 1 ms host step
 * BM_RTB_HostStep/<integrator>   rt_bushing, its substeps, one host step
 * BM_EE_vs_RTB_Ratio  the same host steps, both integrators interleaved step
 *                     by step in one run, each host step timed individually
 *                     (std::chrono::steady_clock); counters ratio_*_mean =
 *                     mean EE time / mean rt_bushing time (> 1: rt_bushing
 *                     is faster), ratio_*_median likewise with medians.
 */
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include "bench/reference_explicit_euler.h"
#include "rt_bushing/rt_bushing.h"

namespace {

constexpr double kHostDt = 1e-3;
constexpr double kAmp = 1.0;
constexpr double kFreq = 10.0;
constexpr int kHostSteps = 500;  /* 5 cycles */
constexpr int kPerCycle = 100;   /* host samples per cycle */
constexpr double kTarget = 0.005;

double input(double t) { return kAmp * std::sin(2.0 * M_PI * kFreq * t); }

rtb_params params(int integrator) {
  rtb_params p;
  rtb_params_default(&p, RTB_MODEL_RT);
  p.integrator = integrator;
  return p;
}

using Series = std::vector<double>; /* force at host samples 0..kHostSteps */

/* rt_bushing with `sub` steps per host step. exact_input: evaluate the sine
 * at every fine step; otherwise interpolate the host samples linearly. */
Series run_rtb(int integrator, int sub, bool exact_input) {
  const rtb_params p = params(integrator);
  rtb_state s;
  rtb_state_init(&s, &p, 0.0);
  Series F(kHostSteps + 1, 0.0);
  const double h = kHostDt / sub;
  for (int i = 1; i <= kHostSteps; ++i) {
    const double x0 = input((i - 1) * kHostDt), x1 = input(i * kHostDt);
    double f = 0.0;
    for (int j = 1; j <= sub; ++j) {
      const double x = exact_input ? input((i - 1) * kHostDt + j * h)
                                   : x0 + (x1 - x0) * j / sub;
      if (rtb_step(&s, &p, nullptr, x, h, &f) < 0) return Series();
    }
    F[i] = f;
  }
  return F;
}

Series run_ee(int m, bool *stable_finite, double *h_rho_max) {
  rtb_ref::ExplicitEuler e;
  e.init(params(RTB_INTEGRATOR_SDIRK2));
  Series F(kHostSteps + 1, 0.0);
  for (int i = 1; i <= kHostSteps && e.finite; ++i) F[i] = e.step<true>(input(i * kHostDt), kHostDt, m);
  *stable_finite = e.finite;
  *h_rho_max = e.max_stiffness;
  return F;
}

/* Max abs error on the last cycle relative to the reference's peak there. */
double rel_err(const Series &a, const Series &ref) {
  if (a.size() != ref.size()) return INFINITY;
  double e = 0.0, peak = 0.0;
  for (int i = kHostSteps - kPerCycle; i <= kHostSteps; ++i) {
    const double d = std::fabs(a[i] - ref[i]);
    e = std::isfinite(d) ? std::max(e, d) : INFINITY;
    peak = std::max(peak, std::fabs(ref[i]));
  }
  return e / peak;
}

struct Study {
  double ref_conv = 0, floor = 0, ref_peak = 0;
  int m_min = -1, m_bounded = -1;
  double ee_err = 0, ee_h_rho = 0;
  std::vector<std::pair<int, double>> ee_scan; /* (m, err) near m_min */
  double rtb_err[2] = {0, 0};
  int rtb_sub[2] = {-1, -1};
};

const Study &study() {
  static Study S;
  static bool done = false;
  if (done) return S;
  done = true;
  const Series ref = run_rtb(RTB_INTEGRATOR_SDIRK2, 1000, true);   /* dt = 1e-6 */
  const Series ref2 = run_rtb(RTB_INTEGRATOR_SDIRK2, 500, true);   /* dt = 2e-6 */
  const Series refs = run_rtb(RTB_INTEGRATOR_SDIRK2, 1000, false); /* sampled input */
  S.ref_conv = rel_err(ref2, ref) / 3.0;
  S.floor = rel_err(refs, ref);
  for (int i = kHostSteps - kPerCycle; i <= kHostSteps; ++i) S.ref_peak = std::max(S.ref_peak, std::fabs(ref[i]));

  for (int m = 1; m <= 100000 && S.m_min < 0; m = m < 64 ? m + 1 : m + m / 16) {
    bool fin;
    double hr;
    const Series F = run_ee(m, &fin, &hr);
    if (fin && S.m_bounded < 0) S.m_bounded = m;
    if (fin && hr <= 2.0) {
      const double e = rel_err(F, ref);
      if (e <= kTarget) { S.m_min = m; S.ee_err = e; S.ee_h_rho = hr; }
    }
  }
  if (S.m_min > 0)
    for (int m : {S.m_min - 1, S.m_min + 1, 2 * S.m_min, 10 * S.m_min}) {
      if (m < 1) continue;
      bool fin;
      double hr;
      const Series F = run_ee(m, &fin, &hr);
      S.ee_scan.push_back({m, fin ? rel_err(F, ref) : INFINITY});
    }

  for (int integ : {RTB_INTEGRATOR_SDIRK2, RTB_INTEGRATOR_BE}) {
    S.rtb_err[integ] = rel_err(run_rtb(integ, 1, false), ref);
    for (int sub = 1; sub <= 1000; ++sub)
      if (rel_err(run_rtb(integ, sub, false), ref) <= kTarget) { S.rtb_sub[integ] = sub; break; }
  }
  return S;
}

void BM_EE_Accuracy(benchmark::State &state) {
  for (auto _ : state) benchmark::DoNotOptimize(study());
  const Study &S = study();
  state.counters["ref_conv_pct"] = 100 * S.ref_conv;
  state.counters["sampling_floor_pct"] = 100 * S.floor;
  state.counters["ref_peak_N"] = S.ref_peak;
  state.counters["ee_m_min"] = S.m_min;
  state.counters["ee_m_bounded"] = S.m_bounded;
  state.counters["ee_err_pct"] = 100 * S.ee_err;
  state.counters["ee_h_rho_max"] = S.ee_h_rho;
  for (const auto &me : S.ee_scan)
    state.counters["ee_err_pct_m" + std::to_string(me.first)] =
        std::isfinite(me.second) ? 100 * me.second : -1.0; /* -1: blew up */
  state.counters["rtb_sdirk2_err_pct"] = 100 * S.rtb_err[RTB_INTEGRATOR_SDIRK2];
  state.counters["rtb_be_err_pct"] = 100 * S.rtb_err[RTB_INTEGRATOR_BE];
  state.counters["rtb_sdirk2_substeps"] = S.rtb_sub[RTB_INTEGRATOR_SDIRK2];
  state.counters["rtb_be_substeps"] = S.rtb_sub[RTB_INTEGRATOR_BE];
  if (S.m_min < 0) state.SkipWithError("no substep factor reached the target");
}

/* Host samples over whole cycles, replayed cyclically (periodic input). */
const std::vector<double> &host_input() {
  static std::vector<double> xs = [] {
    std::vector<double> v(100 * kPerCycle);
    for (size_t i = 0; i < v.size(); ++i) v[i] = input((i + 1) * kHostDt);
    return v;
  }();
  return xs;
}

struct RtbHost {
  rtb_params p;
  rtb_state s;
  int sub = 1;
  long bad = 0; /* steps that did not return RTB_OK */
  double x_prev = 0.0;
  void init(int integrator, int substeps) {
    p = params(integrator);
    rtb_state_init(&s, &p, 0.0);
    sub = substeps;
    x_prev = 0.0;
  }
  double step(double x) {
    double f = 0.0;
    const double h = kHostDt / sub;
    for (int j = 1; j <= sub; ++j)
      if (rtb_step(&s, &p, nullptr, x_prev + (x - x_prev) * j / sub, h, &f) != RTB_OK) ++bad;
    x_prev = x;
    return f;
  }
};

void BM_EE_HostStep(benchmark::State &state) {
  const int m = study().m_min;
  if (m < 1) { state.SkipWithError("no substep factor"); return; }
  rtb_ref::ExplicitEuler e;
  e.init(params(RTB_INTEGRATOR_SDIRK2));
  const auto &xs = host_input();
  for (double x : xs) e.step(x, kHostDt, m); /* warm-up: 100 cycles */
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(e.step(xs[i], kHostDt, m));
    if (++i == xs.size()) i = 0;
  }
  if (!e.finite) state.SkipWithError("explicit Euler blew up");
  state.SetItemsProcessed(state.iterations());
  state.counters["m"] = m;
}

void BM_RTB_HostStep(benchmark::State &state) {
  const int integ = static_cast<int>(state.range(0));
  const int sub = std::max(1, study().rtb_sub[integ]);
  RtbHost r;
  r.init(integ, sub);
  const auto &xs = host_input();
  for (double x : xs) r.step(x);
  size_t i = 0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(r.step(xs[i]));
    if (++i == xs.size()) i = 0;
  }
  state.SetItemsProcessed(state.iterations());
  state.counters["substeps"] = sub;
  state.counters["not_ok"] = static_cast<double>(r.bad);
  state.SetLabel(integ == RTB_INTEGRATOR_BE ? "BE" : "SDIRK2");
}

void BM_EE_vs_RTB_Ratio(benchmark::State &state) {
  using Clock = std::chrono::steady_clock;
  const Study &S = study();
  if (S.m_min < 1) { state.SkipWithError("no substep factor"); return; }
  rtb_ref::ExplicitEuler e;
  e.init(params(RTB_INTEGRATOR_SDIRK2));
  RtbHost r2, rb;
  r2.init(RTB_INTEGRATOR_SDIRK2, std::max(1, S.rtb_sub[RTB_INTEGRATOR_SDIRK2]));
  rb.init(RTB_INTEGRATOR_BE, std::max(1, S.rtb_sub[RTB_INTEGRATOR_BE]));
  const auto &xs = host_input();
  for (double x : xs) { e.step(x, kHostDt, S.m_min); r2.step(x); rb.step(x); }
  const long n = state.max_iterations;
  std::vector<double> te, t2, tb;
  te.reserve(n); t2.reserve(n); tb.reserve(n);
  size_t i = 0;
  double max_dF = 0.0;
  for (auto _ : state) {
    const double x = xs[i];
    const auto a = Clock::now();
    const double fe = e.step(x, kHostDt, S.m_min);
    const auto b = Clock::now();
    const double f2 = r2.step(x);
    const auto c = Clock::now();
    const double fb = rb.step(x);
    const auto d = Clock::now();
    benchmark::DoNotOptimize(fb);
    max_dF = std::max(max_dF, std::fabs(fe - f2));
    te.push_back(std::chrono::duration<double, std::nano>(b - a).count());
    t2.push_back(std::chrono::duration<double, std::nano>(c - b).count());
    tb.push_back(std::chrono::duration<double, std::nano>(d - c).count());
    if (++i == xs.size()) i = 0;
  }
  auto mean = [](const std::vector<double> &v) {
    double s = 0.0;
    for (double x : v) s += x;
    return s / v.size();
  };
  auto median = [](std::vector<double> v) {
    std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
    return v[v.size() / 2];
  };
  const double me = mean(te), m2 = mean(t2), mb = mean(tb);
  const double de = median(te), d2 = median(t2), db = median(tb);
  state.counters["m"] = S.m_min;
  state.counters["ee_mean_ns"] = me;
  state.counters["sdirk2_mean_ns"] = m2;
  state.counters["be_mean_ns"] = mb;
  state.counters["ee_median_ns"] = de;
  state.counters["sdirk2_median_ns"] = d2;
  state.counters["be_median_ns"] = db;
  state.counters["ratio_sdirk2_mean"] = me / m2;
  state.counters["ratio_be_mean"] = me / mb;
  state.counters["ratio_sdirk2_median"] = de / d2;
  state.counters["ratio_be_median"] = de / db;
  state.counters["ee_vs_sdirk2_max_dF_N"] = max_dF; /* sanity: same answer */
  state.counters["rtb_not_ok"] = static_cast<double>(r2.bad + rb.bad);
}

}  // namespace

BENCHMARK(BM_EE_Accuracy)->Iterations(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_EE_HostStep)->Unit(benchmark::kNanosecond);
BENCHMARK(BM_RTB_HostStep)->Arg(RTB_INTEGRATOR_SDIRK2)->Arg(RTB_INTEGRATOR_BE)->ArgName("integrator")
    ->Unit(benchmark::kNanosecond);
BENCHMARK(BM_EE_vs_RTB_Ratio)->Iterations(200000)->Unit(benchmark::kNanosecond);
