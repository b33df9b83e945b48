/* friction_limit.cpp -- the active-set solve of friction_limit.h. */
#include "friction_limit.h"

#include <math.h>

#include "tridiagonal.h"
#include "no_heap.h"

namespace {

/* One workspace for every solve: this sits at the bottom of the deepest
 * call chain of a step (make embedded's stack depth). */
struct LimitWork {
  rtb_real lo[RTB_MAX_CELLS], di[RTB_MAX_CELLS], up[RTB_MAX_CELLS];
  rtb_real piv[RTB_MAX_CELLS], w[RTB_MAX_CELLS];
};

/* Solve h K v = rhs (v holds rhs on entry) over the cells that slide, with
 * v_k = 0 where cell k is still (act[k] == 0; all slide when act is NULL).
 * Returns -1 on a singular system. */
int solve_rows(int n, rtb_real hK0, rtb_real hKr, const int *act, LimitWork *W, rtb_real *v) {
  for (int k = 0; k < n; ++k) {
    const bool still = act && act[k] == 0;
    W->di[k] = still ? 1.0 : (k == 0 ? hK0 : 2.0 * hKr);
    W->lo[k] = still || k == 0 ? 0.0 : -hKr;
    W->up[k] = still || k + 1 == n ? 0.0 : -hKr;
  }
  if (rtb_tridiag_factor(n, W->lo, W->di, W->up, W->piv, W->w) != 0) return -1;
  rtb_tridiag_subst(n, W->lo, W->piv, W->w, v);
  return 0;
}

/* One solve with the active set act: v, f, and the set the complementarity
 * function asks for next (*next). Returns -1 on a singular system, else
 * whether the set is unchanged. */
int limit_solve(int n, rtb_real hK0, rtb_real hKr, const rtb_real *r, rtb_real Lp, rtb_real Lm,
                const int *act, bool stop_first, LimitWork *W, rtb_real *v, rtb_real *f,
                signed char *next) {
  for (int k = 0; k < n; ++k) v[k] = act[k] == 0 ? 0.0 : r[k] - (act[k] > 0 ? Lp : -Lm);
  if (solve_rows(n, hK0, hKr, act, W, v) != 0) return -1;
  const rtb_real tie = RTB_STS_TIE_REL * (Lp > Lm ? Lp : Lm);
  int same = 1;
  for (int k = 0; k < n; ++k) {
    const rtb_real a = k == 0 ? hK0 : 2.0 * hKr;
    const rtb_real Kv = a * v[k] - hKr * ((k > 0 ? v[k - 1] : 0.0) + (k + 1 < n ? v[k + 1] : 0.0));
    f[k] = act[k] == 0 ? r[k] - Kv : (act[k] > 0 ? Lp : -Lm);
    /* Complementarity function: the friction force plus the scaled slip;
     * past a level by more than the tie band, the cell slides that way.
     * stop_first: a sliding cell that would reverse stops first. */
    const rtb_real g = f[k] + a * v[k];
    int s = g > Lp + tie ? 1 : (g < -Lm - tie ? -1 : 0);
    if (stop_first && s == -act[k]) s = 0;
    next[k] = (signed char)s;
    same &= s == act[k];
  }
  return same;
}

}  // namespace

extern "C" int rtb_friction_limit(int n, rtb_real hK0, rtb_real hKr, const rtb_real *r,
                                  rtb_real Lp, rtb_real Lm, int trial_solves, int max_solves,
                                  int *act, rtb_real *v, rtb_real *f) {
  LimitWork W;
  signed char next[RTB_MAX_CELLS], prev[RTB_MAX_CELLS], flipped[RTB_MAX_CELLS];
  if (n < 1 || n > RTB_MAX_CELLS || max_solves < (trial_solves > 0 ? 1 : 2)) return 0;
  int solves = 0;
  /* The phases of friction_limit.h. Why phase 1 starts from the level-free
   * set: the elastic trial ignores the chain, and where a cell pulled hard
   * drags its neighbours against their own load, stops from that set move
   * the front one cell per two solves (49 solves at N = 25 under random
   * 10 mm jumps; from the level-free set, mostly 1). Why phase 0 at all: on
   * smooth input the plain method's fronts need fewer solves (up to 12 at
   * N = 15 on tests/realtime_test.cpp's input, 17 from the level-free set). */
  for (int k = 0; k < n; ++k) {
    act[k] = r[k] > Lp ? 1 : (r[k] < -Lm ? -1 : 0);
    prev[k] = (signed char)act[k];
    flipped[k] = 0;
  }
  for (int phase = trial_solves > 0 ? 0 : 1; phase < 2; ++phase) {
    int cap = max_solves;
    if (phase == 0) { /* leave phase 1 two solves, if there are three */
      const int room = max_solves >= 3 ? max_solves - 2 : max_solves;
      cap = trial_solves < room ? trial_solves : room;
    } else { /* the level-free solve's set */
      if (max_solves - solves < 2) break;
      for (int k = 0; k < n; ++k) v[k] = r[k];
      if (solve_rows(n, hK0, hKr, NULL, &W, v) != 0) return 0;
      ++solves;
      for (int k = 0; k < n; ++k) act[k] = v[k] > 0.0 ? 1 : (v[k] < 0.0 ? -1 : 0);
    }
    while (solves < cap) {
      ++solves;
      const int same = limit_solve(n, hK0, hKr, r, Lp, Lm, act, phase == 1, &W, v, f, next);
      if (same < 0) return 0;
      if (same) return solves;
      if (solves == max_solves) break; /* act stays the last solve's set */
      bool cycle = phase == 0, again = false;
      for (int k = 0; k < n; ++k) {
        cycle = cycle && next[k] == prev[k];
        if (next[k] != 0 && next[k] == -act[k]) again |= flipped[k]++ > 0;
      }
      if (cycle || (phase == 0 && again)) break; /* act stays the last solve's set */
      for (int k = 0; k < n; ++k) prev[k] = (signed char)act[k], act[k] = next[k];
    }
  }
  return -solves;
}

extern "C" rtb_real rtb_friction_limit_tangent(int n, rtb_real hK0, rtb_real hKr, const int *act,
                                               rtb_real b0) {
  LimitWork W;
  rtb_real x[RTB_MAX_CELLS];
  if (n < 1 || n > RTB_MAX_CELLS) return 0.0;
  for (int k = 0; k < n; ++k) x[k] = k == 0 && act[0] != 0 ? b0 : 0.0;
  if (solve_rows(n, hK0, hKr, act, &W, x) != 0) return 0.0;
  return x[0];
}
