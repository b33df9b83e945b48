// stage_residual.h -- the residual of eq. (2) that a returned implicit stage
// leaves with the exact law of eq. (1), recomputed from the stage's forces
// (shared by stuck_cells_test.cpp and sweep_free_update_test.cpp).
#ifndef RTB_TESTS_STAGE_RESIDUAL_H
#define RTB_TESTS_STAGE_RESIDUAL_H

#include <cmath>

#include "dashpot_law.h"
#include "rt_bushing/rt_bushing.h"
#include "rtb_internal.h"
#include "tridiagonal.h"

namespace rtbtest {

// max |H| / scale of a returned stage with v = phi(f) (eq. (1)) for every
// cell: H = f + h K phi(f) - (b - K c), scale = max(|f|, |b - K c|) as the
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
    v[k] = rtb_law_velocity(st.f[k], p.C0, p.alpha);
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

}  // namespace rtbtest

#endif
