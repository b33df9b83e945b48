// freq_bench.cpp -- the frequency domain (issue #13), N = 15, the paper's
// section 3.4 parameter set:
//   BM_DynStiffPoint     one converged (frequency, amplitude) point, 10 Hz, 0.3 mm
//   BM_DynStiffTableFit  `rtb identify --dynstiff` on a 12-row table (4
//                        frequencies x 3 amplitudes, stiffness to 3 significant
//                        digits, loss angle to 0.1 deg) from the table start;
//                        target < 30 s
#ifdef RTB_HAVE_OFFLINE
#include <benchmark/benchmark.h>

#include <cmath>

#include "offline/freq/periodic_drive.h"
#include "offline/freq/table_fit.h"

namespace {

using namespace rtb;

rtb_params truth() {
  rtb_params p;
  rtb_params_default(&p, RTB_MODEL_RT);
  return p;
}

const DynStiffTable &table() {
  static const DynStiffTable t = [] {
    DynStiffTable t;
    t.path = "bench";
    for (double f : {1.0, 3.0, 10.0, 30.0})
      for (double A : {0.03, 0.3, 3.0}) {
        const DynStiffPoint d = dynamic_stiffness(truth(), SineTest{f, A}, DynStiffOptions());
        const double e = std::pow(10.0, std::floor(std::log10(d.k.stiffness)) - 2);
        t.rows.push_back(DynStiffRow{f, A, std::round(d.k.stiffness / e) * e,
                                     std::round(d.k.loss_angle_deg * 10) / 10, 1.0});
      }
    return t;
  }();
  return t;
}

void BM_DynStiffPoint(benchmark::State &state) {
  for (auto _ : state)
    benchmark::DoNotOptimize(dynamic_stiffness(truth(), SineTest{10.0, 0.3}, DynStiffOptions()).k);
}
BENCHMARK(BM_DynStiffPoint)->Unit(benchmark::kMillisecond);

void BM_DynStiffTableFit(benchmark::State &state) {
  const DynStiffTable &t = table();
  TableFitResult r;
  for (auto _ : state) r = fit_dynstiff_table(t, table_initial_guess(t, 15), TableFitOptions());
  const rtb_params p = truth();
  state.counters["iterations"] = r.fit.iterations;
  state.counters["rms_stiffness_pct"] = 100 * r.rms_stiffness_rel;
  state.counters["rms_loss_deg"] = r.rms_loss_deg;
  state.counters["K0_ratio"] = r.fit.params.K0 / p.K0;
  state.counters["alpha_ratio"] = r.fit.params.alpha / p.alpha;
}
BENCHMARK(BM_DynStiffTableFit)->Unit(benchmark::kSecond)->Iterations(1);

}  // namespace

#endif
