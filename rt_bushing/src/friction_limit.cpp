/* friction_limit.cpp -- the active-set solve of friction_limit.h. */
#include "friction_limit.h"

#include <math.h>

#include "tridiagonal.h"
#include "no_heap.h"

namespace {

/* Row k of h K v = rhs where cell k slides, v_k = 0 where it is still
 * (act[k] == 0; all slide when act is NULL). */
void limit_rows(int n, rtb_real hK0, rtb_real hKr, const int *act, rtb_real *lo, rtb_real *di,
                rtb_real *up) {
  for (int k = 0; k < n; ++k) {
    const bool still = act && act[k] == 0;
    di[k] = still ? 1.0 : (k == 0 ? hK0 : 2.0 * hKr);
    lo[k] = still || k == 0 ? 0.0 : -hKr;
    up[k] = still || k + 1 == n ? 0.0 : -hKr;
  }
}

/* One solve with the active set act: v, f, and the set the complementarity
 * function asks for next (*next). Returns -1 on a singular system, else
 * whether the set is unchanged. */
int limit_solve(int n, rtb_real hK0, rtb_real hKr, const rtb_real *r, const rtb_real *Lp,
                const rtb_real *Lm, const int *act, bool stop_first, rtb_real *v, rtb_real *f,
                int *next) {
  rtb_real lo[RTB_MAX_CELLS], di[RTB_MAX_CELLS], up[RTB_MAX_CELLS], work[RTB_MAX_CELLS];
  limit_rows(n, hK0, hKr, act, lo, di, up);
  for (int k = 0; k < n; ++k) v[k] = act[k] == 0 ? 0.0 : r[k] - (act[k] > 0 ? Lp[k] : -Lm[k]);
  if (rtb_tridiag_solve(n, lo, di, up, v, work) != 0) return -1;
  int same = 1;
  for (int k = 0; k < n; ++k) {
    const rtb_real a = k == 0 ? hK0 : 2.0 * hKr;
    const rtb_real Kv = a * v[k] - hKr * ((k > 0 ? v[k - 1] : 0.0) + (k + 1 < n ? v[k + 1] : 0.0));
    f[k] = act[k] == 0 ? r[k] - Kv : (act[k] > 0 ? Lp[k] : -Lm[k]);
    /* Complementarity function: the friction force plus the scaled slip;
     * past a level by more than the tie band, the cell slides that way.
     * stop_first: a sliding cell that would reverse stops first. */
    const rtb_real g = f[k] + a * v[k];
    const rtb_real tie = RTB_STS_TIE_REL * (Lp[k] > Lm[k] ? Lp[k] : Lm[k]);
    int s = g > Lp[k] + tie ? 1 : (g < -Lm[k] - tie ? -1 : 0);
    if (stop_first && s == -act[k]) s = 0;
    next[k] = s;
    same &= s == act[k];
  }
  return same;
}

/* The set of the level-free solve h K v = r: each cell slides the way the
 * chain alone would move it. Returns -1 on a singular system. */
int level_free_set(int n, rtb_real hK0, rtb_real hKr, const rtb_real *r, rtb_real *v, int *act) {
  rtb_real lo[RTB_MAX_CELLS], di[RTB_MAX_CELLS], up[RTB_MAX_CELLS], work[RTB_MAX_CELLS];
  limit_rows(n, hK0, hKr, NULL, lo, di, up);
  for (int k = 0; k < n; ++k) v[k] = r[k];
  if (rtb_tridiag_solve(n, lo, di, up, v, work) != 0) return -1;
  for (int k = 0; k < n; ++k) act[k] = v[k] > 0.0 ? 1 : (v[k] < 0.0 ? -1 : 0);
  return 0;
}

}  // namespace

extern "C" int rtb_friction_limit(int n, rtb_real hK0, rtb_real hKr, const rtb_real *r,
                                  const rtb_real *Lp, const rtb_real *Lm, int trial_solves,
                                  int max_solves, int *act, rtb_real *v, rtb_real *f) {
  int next[RTB_MAX_CELLS], prev[RTB_MAX_CELLS], flipped[RTB_MAX_CELLS] = {0};
  if (n < 1 || n > RTB_MAX_CELLS || max_solves < (trial_solves > 0 ? 1 : 2)) return 0;
  int solves = 0;
  /* The phases of friction_limit.h. Why phase 1 starts from the level-free
   * set: the elastic trial ignores the chain, and where a cell pulled hard
   * drags its neighbours against their own load, stops from that set move
   * the front one cell per two solves (49 solves at N = 25 under random
   * 10 mm jumps; from the level-free set, mostly 1). Why phase 0 at all: on
   * smooth input the plain method's fronts need fewer solves (up to 12 at
   * N = 15 on tests/realtime_test.cpp's input, 17 from the level-free set). */
  for (int k = 0; k < n; ++k) act[k] = prev[k] = r[k] > Lp[k] ? 1 : (r[k] < -Lm[k] ? -1 : 0);
  for (int phase = trial_solves > 0 ? 0 : 1; phase < 2; ++phase) {
    int cap = max_solves;
    if (phase == 0) { /* leave phase 1 two solves, if there are three */
      const int room = max_solves >= 3 ? max_solves - 2 : max_solves;
      cap = trial_solves < room ? trial_solves : room;
    } else {
      if (max_solves - solves < 2) break;
      if (level_free_set(n, hK0, hKr, r, v, act) != 0) return 0;
      ++solves;
    }
    while (solves < cap) {
      ++solves;
      const int same = limit_solve(n, hK0, hKr, r, Lp, Lm, act, phase == 1, v, f, next);
      if (same < 0) return 0;
      if (same) return solves;
      if (solves == max_solves) break; /* act stays the last solve's set */
      bool cycle = phase == 0, again = false;
      for (int k = 0; k < n; ++k) {
        cycle = cycle && next[k] == prev[k];
        if (next[k] == -act[k] && next[k] != 0) again |= flipped[k]++ > 0;
      }
      if (cycle || (phase == 0 && again)) break; /* act stays the last solve's set */
      for (int k = 0; k < n; ++k) prev[k] = act[k], act[k] = next[k];
    }
  }
  return -solves;
}

extern "C" rtb_real rtb_friction_limit_tangent(int n, rtb_real hK0, rtb_real hKr, const int *act,
                                               rtb_real b0) {
  rtb_real lo[RTB_MAX_CELLS], di[RTB_MAX_CELLS], up[RTB_MAX_CELLS], work[RTB_MAX_CELLS];
  rtb_real x[RTB_MAX_CELLS];
  if (n < 1 || n > RTB_MAX_CELLS) return 0.0;
  limit_rows(n, hK0, hKr, act, lo, di, up);
  for (int k = 0; k < n; ++k) x[k] = k == 0 && act[0] != 0 ? b0 : 0.0;
  if (rtb_tridiag_solve(n, lo, di, up, x, work) != 0) return 0.0;
  return x[0];
}
