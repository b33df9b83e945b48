// diagnose_bench.cpp -- cost of `rtb diagnose` on the issue #4 set-up: five
// 10 s records at 1 kHz (three fit records, two held out), N = 15, 0.5%
// noise, one hidden effect; all nine candidates screened, four fitted
// jointly, 2 threads. Target: under 30 s per diagnosis on this machine.
//   BM_Diagnose/<effect>   one full diagnosis; counter named_ok = 1 when the
//                          hidden effect was named
#ifdef RTB_HAVE_OFFLINE
#include <benchmark/benchmark.h>

#include "offline/diagnose/diagnose.h"
#include "offline/synth/synthetic_records.h"

namespace {

using namespace rtb;

const char *const kEffects[] = {"none", "backlash", "delay", "maxwell"};

void BM_Diagnose(benchmark::State &state) {
  const std::string effect = kEffects[state.range(0)];
  const Scenario sc = hidden_effect_scenario(effect, 5, 0.005, 10.0);
  DiagnoseOptions o;
  o.threads = 2;
  double ok = 0;
  for (auto _ : state) {
    const DiagnoseResult r = diagnose(sc.fit, sc.holdout, o);
    ok = r.cause == effect ? 1.0 : 0.0;
    benchmark::DoNotOptimize(r.gain);
  }
  state.SetLabel(effect + ", " + std::to_string(sc.fit.size() + sc.holdout.size()) + " records");
  state.counters["named_ok"] = ok;
}
BENCHMARK(BM_Diagnose)->DenseRange(0, 3)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

}  // namespace
#endif
