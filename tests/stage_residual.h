// stage_residual.h -- the residual of eq. (2) that a returned implicit stage
// leaves with the exact law of eq. (1) (or eq. (14) when smoothed),
// recomputed from the stage's forces, and the benchmark input those tests
// drive it with (shared by stuck_cells_test.cpp, sweep_free_update_test.cpp
// and smoothed_chebyshev_test.cpp).
#ifndef RTB_TESTS_STAGE_RESIDUAL_H
#define RTB_TESTS_STAGE_RESIDUAL_H

#include <gtest/gtest.h>

#include <cmath>

#include "dashpot_law.h"
#include "rt_bushing/rt_bushing.h"
#include "rtb_internal.h"
#include "tridiagonal.h"

namespace rtbtest {

// max |H| / scale of a returned stage with v = phi(f) (eq. (1), or the
// closed-form inverse of eq. (14) to rounding when p.smoothing > 0; no
// friction asymmetry) for every cell: H = f + h K phi(f) - (b - K c), scale = max(|f|, |b - K c|) as the
// solver's own test. *locked: the cells returned at v = 0, D = 0; *loaded:
// those of them that carry a force (f != 0: the law gives v != 0 there).
inline double full_residual(const rtb_params &p, const rtb_stage &st, int *locked, int *loaded) {
  const int n = p.cells;
  double r[RTB_MAX_CELLS], v[RTB_MAX_CELLS], Kv[RTB_MAX_CELLS];
  rtb_chain_apply(n, p.Kpa, p.Kr, st.c, r);
  double scale = 0.0;
  *locked = *loaded = 0;
  for (int k = 0; k < n; ++k) {
    r[k] = (k == 0 ? st.b1 : 0.0) - r[k];
    v[k] = p.smoothing > 0.0 ? rtb_slaw_velocity(st.f[k], p.C0, p.alpha, p.smoothing, st.v[k])
                             : rtb_law_velocity(st.f[k], p.C0, p.alpha);
    if (st.v[k] == 0.0 && st.D[k] == 0.0) {
      ++*locked;
      *loaded += st.f[k] != 0.0;
    }
    scale = std::fmax(scale, std::fmax(std::fabs(st.f[k]), std::fabs(r[k])));
  }
  rtb_chain_apply(n, p.Kpa, p.Kr, v, Kv);
  double h = 0.0;
  for (int k = 0; k < n; ++k) h = std::fmax(h, std::fabs(st.f[k] + st.h * Kv[k] - r[k]));
  return scale > 0.0 ? h / scale : h;
}

// Sample i of the benchmark input: a 10 Hz, 1 mm sine at 1 kHz plus
// uniform noise of 35 um peak to peak (10 um rms) from a 64-bit LCG in
// *seed (advanced), so the tests need no <random> distribution whose
// output could differ between standard libraries. [mm]
inline double noisy_sine_mm(int i, unsigned long long *seed) {
  *seed = *seed * 6364136223846793005ULL + 1442695040888963407ULL;
  const double u = (double)(*seed >> 11) * (1.0 / 9007199254740992.0) - 0.5;
  return std::sin(6.283185307179586476925 * 10.0 * i * 1e-3) + 0.0346 * u;
}

// Steps p on `steps` samples of noisy_sine_mm (from seed) with the
// tolerance tol, calling on_step(i, status, info, stages) after each step
// (stages: the step's implicit stages); stops after a step that fails.
template <class OnStep>
void drive_noisy_sine(const rtb_params &p, double tol, int steps, unsigned long long seed,
                      OnStep on_step) {
  rtb_settings set;
  rtb_settings_default(&set);
  set.tol = tol;
  rtb_state s;
  if (rtb_state_init(&s, &p, 0.0) != RTB_OK) {
    ADD_FAILURE() << "rtb_state_init rejected the parameters";
    return;
  }
  for (int i = 1; i <= steps; ++i) {
    rtb_state out;
    rtb_stage st[2];
    double F, dF;
    rtb_step_info info;
    const rtb_status q = rtb_step_core(&s, &p, &set, noisy_sine_mm(i, &seed), 1e-3, &out, &F,
                                       &dF, st, &info, RTB_BACKLASH_ITERS);
    on_step(i, q, info, st);
    if (q < 0) return;
    s = out;
  }
}

}  // namespace rtbtest

#endif
