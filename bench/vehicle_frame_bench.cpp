/* vehicle_frame_bench.cpp -- a full vehicle's bushings in one 1 kHz frame
 * (issue #11): 40 bushings x 6 axes = 240 independent elements, each stepped
 * once per 1 ms frame, on one core.
 *
 * Elements: the section 3.4 set (N = 15, SDIRK2) with parameters varied per
 * element (K0, Kpa, Kr x 0.5 .. 2, C0 x 0.5 .. 2, alpha 0.1 .. 0.5; fixed
 * seed) and, on every fourth element, one extension in turn (cubic spring,
 * asymmetry, Maxwell branch, viscous damper, Mullins, softening spring,
 * backlash 0.02 mm).
 * Input per element: road-like -- a 1.2 Hz body mode (amplitude 0.5 mm), a
 * 12 Hz wheel-hop mode (0.2 mm), each with a random phase, plus a
 * first-order filtered random road (corner 30 Hz, 0.05 mm rms), all scaled
 * per axis (rotational axes in rad-like units of the same magnitude).
 *
 * Counters: frame_us = median wall time of a frame (240 steps),
 * frame_p99_us, frame_max_us, step_mean_ns, not_converged, errors.
 * Frames: RTB_BENCH_FRAMES (default 5000) after 500 warm-up frames;
 * RTB_BENCH_TOL sets the Newton tolerance (bench_settings.h).
 */
#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <random>
#include <vector>

#include "bench/bench_settings.h"
#include "rt_bushing/rt_bushing.h"

namespace {

constexpr int kBushings = 40, kAxes = 6, kElements = kBushings * kAxes;
constexpr double kDt = 1e-3;
constexpr double kTwoPi = 6.283185307179586476925;

struct Element {
  rtb_params p;
  rtb_state s;
  double phase_body, phase_hop, road, scale;
};

rtb_params vary(std::mt19937_64 &g, int index) {
  std::uniform_real_distribution<double> f(std::log(0.5), std::log(2.0));
  std::uniform_real_distribution<double> a(0.1, 0.5);
  rtb_params p;
  rtb_params_default(&p, RTB_MODEL_RT);
  p.K0 *= std::exp(f(g));
  p.Kpa *= std::exp(f(g));
  p.Kr *= std::exp(f(g));
  p.C0 *= std::exp(f(g));
  p.alpha = a(g);
  if (index % 4 == 0) {
    switch ((index / 4) % 7) {
      case 0: p.k3 = 50.0; break;
      case 1: p.k_asym = 0.2 * p.K0; break;
      case 2: p.maxwell_k = 300.0; p.maxwell_tau = 0.05; break;
      case 3: p.viscous_c = 2.0; break;
      case 4: p.mullins = 0.3; break;
      case 5: p.sat_force = 300.0; p.sat_disp = 0.2; break;
      case 6: p.backlash = 0.02; break;
    }
  }
  return p;
}

long frames_measured() {
  const char *s = std::getenv("RTB_BENCH_FRAMES");
  const long v = s ? std::strtol(s, nullptr, 10) : 0;
  return v > 0 ? v : 5000;
}

void BM_VehicleFrame(benchmark::State &state) {
  std::mt19937_64 g(2026);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  std::normal_distribution<double> white(0.0, 1.0);
  std::vector<Element> el(kElements);
  for (int i = 0; i < kElements; ++i) {
    el[i].p = vary(g, i);
    rtb_state_init(&el[i].s, &el[i].p, 0.0);
    el[i].phase_body = kTwoPi * u01(g);
    el[i].phase_hop = kTwoPi * u01(g);
    el[i].road = 0.0;
    el[i].scale = 0.5 + u01(g);
  }
  /* Road: x' = -wc x + wc sqrt(2/(wc dt)) sigma w, discretised (forward). */
  const double wc = kTwoPi * 30.0, sigma = 0.05;
  const double road_gain = wc * kDt, road_noise = sigma * std::sqrt(2.0 * wc * kDt);
  std::vector<double> xs(kElements);
  auto inputs = [&](long k) { /* outside the timed region */
    const double t = k * kDt;
    for (int i = 0; i < kElements; ++i) {
      Element &e = el[i];
      e.road += -road_gain * e.road + road_noise * white(g);
      xs[i] = e.scale * (0.5 * std::sin(kTwoPi * 1.2 * t + e.phase_body) +
                         0.2 * std::sin(kTwoPi * 12.0 * t + e.phase_hop) + e.road);
    }
  };
  auto frame = [&](long *nc, long *errors) {
    for (int i = 0; i < kElements; ++i) {
      double F;
      const rtb_status st = rtb_step(&el[i].s, &el[i].p, bench_settings(), xs[i], kDt, &F);
      benchmark::DoNotOptimize(F);
      *nc += st == RTB_NOT_CONVERGED;
      *errors += st < 0;
    }
  };
  long nc = 0, errors = 0, k = 0;
  for (; k < 500; ++k) { inputs(k); frame(&nc, &errors); }
  const long n = frames_measured();
  std::vector<double> us;
  us.reserve(n);
  nc = errors = 0;
  for (auto _ : state) {
    for (long i = 0; i < n; ++i, ++k) {
      inputs(k);
      const auto a = std::chrono::steady_clock::now();
      frame(&nc, &errors);
      const auto b = std::chrono::steady_clock::now();
      us.push_back(std::chrono::duration<double, std::micro>(b - a).count());
    }
  }
  std::vector<double> sorted(us);
  std::sort(sorted.begin(), sorted.end());
  double sum = 0.0;
  for (double v : us) sum += v;
  state.counters["frame_us"] = sorted[sorted.size() / 2];
  state.counters["frame_p99_us"] = sorted[sorted.size() * 99 / 100];
  state.counters["frame_max_us"] = sorted.back();
  state.counters["step_mean_ns"] = 1e3 * sum / (static_cast<double>(us.size()) * kElements);
  state.counters["not_converged"] = static_cast<double>(nc);
  state.counters["errors"] = static_cast<double>(errors);
}

}  // namespace

BENCHMARK(BM_VehicleFrame)->Iterations(1)->Unit(benchmark::kMillisecond);
