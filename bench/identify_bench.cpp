// identify_bench.cpp -- cost of the offline half on the issue #3 set-up:
// three 10 s records at 1 kHz (triangle, 1 Hz and 10 Hz sines), N = 15.
//   BM_ForwardSolve      one forward solve of all three records
//   BM_MisfitGradient    misfit + exact adjoint gradient; counter
//                        gradient_over_forward = its cost / a forward solve
//   BM_Identify          a full identification from the paper's near start
#ifdef RTB_HAVE_OFFLINE
#include <benchmark/benchmark.h>

#include <chrono>

#include "offline/identify/identify.h"
#include "offline/synth/synthetic_records.h"

namespace {

using namespace rtb;

const std::vector<Record> &records() {
  static const std::vector<Record> recs = [] {
    rtb_params truth;
    rtb_params_default(&truth, RTB_MODEL_RT);
    TruthSpec ts;
    ts.p = truth;
    ts.oversample = 1;
    std::vector<Record> v;
    for (const InputSpec &in : {InputSpec{InputKind::Triangle, 1.0, 0.5, 10.0, 1e-3},
                                InputSpec{InputKind::Sine, 0.5, 1.0, 10.0, 1e-3},
                                InputSpec{InputKind::Sine, 0.2, 10.0, 10.0, 1e-3}})
      v.push_back(synthesize(in, ts, "bench"));
    return v;
  }();
  return recs;
}

rtb_params near_start() {
  rtb_params p;
  rtb_params_default(&p, RTB_MODEL_RT);
  p.Kpa *= 4.0 / 3.0;
  p.Kr *= 2.0 / 3.0;
  p.C0 *= 2.0;
  p.alpha *= 2.0;
  return p;
}

double seconds_of(const std::function<void()> &f) {
  const auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

void BM_ForwardSolve(benchmark::State &state) {
  const rtb_params p = near_start();
  for (auto _ : state) benchmark::DoNotOptimize(misfit(p, records(), MisfitOptions(), false).J);
}
BENCHMARK(BM_ForwardSolve)->Unit(benchmark::kMillisecond);

void BM_MisfitGradient(benchmark::State &state) {
  const rtb_params p = near_start();
  double fwd = 0, grad = 0;
  int n = 0;
  for (auto _ : state) {
    fwd += seconds_of([&] { benchmark::DoNotOptimize(misfit(p, records(), MisfitOptions(), false).J); });
    grad += seconds_of([&] { benchmark::DoNotOptimize(misfit(p, records(), MisfitOptions(), true).grad[0]); });
    ++n;
  }
  state.counters["gradient_over_forward"] = grad / fwd;
  state.counters["forward_ms"] = 1e3 * fwd / n;
  state.counters["gradient_ms"] = 1e3 * grad / n;
}
BENCHMARK(BM_MisfitGradient)->Unit(benchmark::kMillisecond)->Iterations(5);

void BM_Identify(benchmark::State &state) {
  IdentifyOptions o;
  o.method = state.range(0) == 0 ? Method::TrustRegion : Method::Bfgs;
  double err = 0;
  int iters = 0;
  for (auto _ : state) {
    const IdentifyResult r = identify(records(), near_start(), o);
    err = r.error;
    iters = r.iterations;
  }
  state.counters["final_error"] = err;
  state.counters["iterations"] = iters;
  state.SetLabel(o.method == Method::Bfgs ? "bfgs" : "trust-region");
}
BENCHMARK(BM_Identify)->Arg(0)->Arg(1)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace
#endif
