/* friction_limit.cpp -- the active-set solve of friction_limit.h. */
#include "friction_limit.h"

#include <math.h>

#include "no_heap.h"

namespace {

/* The limit's matrix h K restricted to the sliding cells splits, at every
 * still cell, into independent segments of the chain (a still row is the
 * identity and its v is 0). Thomas's pivots of a segment follow from the
 * linear sequence a_j = 1 + q j of the recurrence p_j = 2 hKr - hKr^2 /
 * p_{j-1}: p_j = hKr a_{j+1} / a_j, with q = hK0 / hKr - 1 = Kpa / Kr for
 * the segment that starts at k = 0 (p_0 = hK0) and q = 1 for one that
 * starts after a still cell (p_0 = 2 hKr). So the ratios rho_j = a_j /
 * a_{j+1} are set once per call, and a solve is two passes of
 * multiply-adds with no division: the divisions were a dependent chain of
 * 2N per solve, and the diagnosis's near-friction fits run 3.7 solves per
 * stage on average (slack records of BM_Diagnose: 110 M solves, a quarter
 * of the diagnosis's time before). Kpa, Kr > 0 (rtb_params_check), so every
 * a_j >= 1. One workspace for every solve: this sits at the bottom of the
 * deepest call chain of a step (make embedded's stack depth). */
struct LimitWork {
  rtb_real rho_first[RTB_MAX_CELLS]; /* rho of row k of the segment from k = 0 */
  rtb_real rho_inner[RTB_MAX_CELLS]; /* rho of the j-th row of a segment after a still cell */
  rtb_real rho[RTB_MAX_CELLS];       /* the ratios one solve used, row by row (0: still) */
  rtb_real ihKr;                     /* 1 / hKr (1 / hK0 when n = 1) */
};

/* The ratios of h K's segments; -1 on a singular matrix. */
int limit_factor(int n, rtb_real hK0, rtb_real hKr, LimitWork *W) {
  if (!(hK0 > 0.0) || !(hKr > 0.0 || n == 1)) return -1;
  if (n == 1) {
    W->ihKr = 1.0 / hK0;
    W->rho_first[0] = W->rho_inner[0] = 1.0;
    return 0;
  }
  const rtb_real q = (hK0 - hKr) / hKr;
  W->ihKr = 1.0 / hKr;
  for (int j = 0; j < n; ++j) {
    W->rho_first[j] = (1.0 + q * j) / (1.0 + q * (j + 1));
    W->rho_inner[j] = (j + 1.0) / (j + 2.0);
  }
  return 0;
}

/* Solve h K v = rhs (v holds rhs on entry) over the cells that slide, with
 * v_k = rhs_k where cell k is still (act[k] == 0, its row the identity; all
 * slide when act is NULL): Thomas's forward and back substitution with
 * the pivots hKr / rho. */
void solve_rows(int n, const int *act, LimitWork *W, rtb_real *v) {
  const rtb_real ihKr = W->ihKr;
  const rtb_real *rho = W->rho_first;
  rtb_real prev = 0.0;
  for (int k = 0, j = 0; k < n; ++k, ++j) {
    if (act && act[k] == 0) {
      W->rho[k] = 0.0;
      rho = W->rho_inner, j = -1;
    } else {
      W->rho[k] = rho[j];
      v[k] = (v[k] * ihKr + prev) * rho[j];
    }
    prev = v[k];
  }
  for (int k = n - 2; k >= 0; --k) v[k] += W->rho[k] * v[k + 1];
}

/* One solve with the active set act: v, f, and the set the complementarity
 * function asks for next (*next). Returns whether the set is unchanged. */
bool limit_solve(int n, rtb_real hK0, rtb_real hKr, const rtb_real *r, rtb_real Lp, rtb_real Lm,
                const int *act, bool stop_first, LimitWork *W, rtb_real *v, rtb_real *f,
                signed char *next) {
  for (int k = 0; k < n; ++k) v[k] = act[k] == 0 ? 0.0 : r[k] - (act[k] > 0 ? Lp : -Lm);
  solve_rows(n, act, W, v);
  const rtb_real tie = RTB_STS_TIE_REL * (Lp > Lm ? Lp : Lm);
  bool same = true;
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
    same = same && s == act[k];
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
  if (limit_factor(n, hK0, hKr, &W) != 0) return 0;
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
      solve_rows(n, NULL, &W, v);
      ++solves;
      for (int k = 0; k < n; ++k) act[k] = v[k] > 0.0 ? 1 : (v[k] < 0.0 ? -1 : 0);
    }
    while (solves < cap) {
      ++solves;
      if (limit_solve(n, hK0, hKr, r, Lp, Lm, act, phase == 1, &W, v, f, next)) return solves;
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
  if (n < 1 || n > RTB_MAX_CELLS || limit_factor(n, hK0, hKr, &W) != 0) return 0.0;
  for (int k = 0; k < n; ++k) x[k] = k == 0 && act[0] != 0 ? b0 : 0.0;
  solve_rows(n, act, &W, x);
  return x[0];
}
