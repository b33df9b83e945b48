// diagnose_bench.cpp -- cost of `rtb diagnose` on the issue #4 set-up: five
// 10 s records at 1 kHz (three fit records, two held out), N = 15, 0.5%
// noise, one hidden effect; every candidate screened, five fitted jointly,
// further rounds while the residual is above the noise floor, 2 threads.
// Target (issue #10): under 60 s per diagnosis on this machine.
//   BM_Diagnose/<k>   one full diagnosis of kEffects[k] hidden (none and the
//                     whole vocabulary); counter named_ok = 1 when it was named
#ifdef RTB_HAVE_OFFLINE
#include <benchmark/benchmark.h>

#include <iterator>

#include "offline/diagnose/diagnose.h"
#include "offline/synth/synthetic_records.h"

namespace {

using namespace rtb;

const char *const kEffects[] = {"none",     "cubic_stiffness", "asymmetry", "maxwell",
                                "viscous",  "backlash",        "mullins",   "delay",
                                "inertia",  "offset",          "softening", "backlash_held",
                                "slack",    "relaxation_spectrum", "friction_asymmetry"};

void BM_Diagnose(benchmark::State &state) {
  const std::string effect = kEffects[state.range(0)];
  const Scenario sc = hidden_effect_scenario(effect, 5, 0.005, 10.0);
  DiagnoseOptions o;
  o.threads = 2;
  double ok = 0;
  DiagnoseResult r;
  for (auto _ : state) {
    r = diagnose(sc.fit, sc.holdout, o);
    const std::string want = effect == "backlash_held" ? "backlash" : effect;
    ok = r.cause == want ? 1.0 : 0.0;
    benchmark::DoNotOptimize(r.gain);
  }
  // Where the time went (seconds): baseline fit, screening, joint fits.
  state.counters["baseline_s"] = r.seconds_baseline;
  state.counters["screen_s"] = r.seconds_screen;
  state.counters["joint_s"] = r.seconds_joint;
  state.SetLabel(effect + ", " + std::to_string(sc.fit.size() + sc.holdout.size()) + " records");
  state.counters["named_ok"] = ok;
  state.counters["causes"] = (double)r.causes.size();
}
BENCHMARK(BM_Diagnose)->DenseRange(0, (int)std::size(kEffects) - 1)->Unit(benchmark::kSecond)->Iterations(1)->UseRealTime();

}  // namespace
#endif
