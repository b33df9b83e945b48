/* friction_limit.h -- the rate-independent limit of an RT stage, the start
 * of near-friction stages (stage_newton.cpp).
 *
 * Stage residual (rtb_internal.h): H = f + h K v - r, v = phi(f). As alpha
 * -> 0, eq. (1) tends to a friction element: |f_k| <= L_k where the cell
 * is still (v_k = 0), f_k = L_k sign(v_k) where it slides, with the level
 * L_k = C0 |v_k|^alpha nearly constant (at alpha = 0.001 it changes by 0.5%
 * per decade of velocity). That limit is the STS step of section 3.1 in
 * velocities, and the primal-dual active-set method of the STS return map
 * (sts_return_map.cpp) solves it exactly in a few tridiagonal solves. Why:
 * near friction, Newton's iteration on the smooth stage starts from the
 * last step's pair, and where a cell must go from sticking to slipping
 * (or back) its force update overshoots the level, v = (f / C0)^(1/alpha)
 * explodes and the line search halves a dozen times (BM_RandomConfigs'
 * near-friction elements; a fitted element at alpha 0.001 took ~30 law
 * sweeps per step, docs/benchmarks.md session 35). The limit's active set
 * is the right one to within the boundary layer, so Newton starts on the
 * right side of every cell's level. */
#ifndef RTB_FRICTION_LIMIT_H
#define RTB_FRICTION_LIMIT_H

#include "rtb_scalar.h"

#ifdef __cplusplus
extern "C" {
#endif

/* Solve the limit stage f + h K v = r, -Lm <= f_k <= Lp, f_k = Lp where
 * v_k > 0 and -Lm where v_k < 0, for the first n cells of the chain
 * (hK0 = h (Kpa + Kr), hKr = h Kr; v beyond n is 0). Phase 0, up to
 * trial_solves solves: the plain method from the elastic trial's active set
 * (the cells whose r_k is past a level), right in one solve when
 * little slides (the STS return map's common case, which passes its whole
 * cap), left as soon as it cycles (a set seen two solves ago, or a cell
 * reversing for the second time). Phase 1: from the set of the level-free
 * solve h K v = r, with sliding cells stopping before they reverse; right
 * to within the boundary cells when a pulled cell drags the chain (the
 * near-friction stage's case, which passes trial_solves = 0). act receives
 * the active set of the last solve, -1 / 0 / +1 (sliding down / still /
 * up); v and f that solve's velocities and forces (f = Lp or -Lm exactly where
 * a cell slides). At most max_solves tridiagonal solves (>= 2, or >= 1 with
 * a trial; the level-free phase needs two, and is skipped without). Returns the
 * solves used (> 0) when the active set settled, minus that number when it
 * did not, 0 on a singular system (v, f then unset). */
int rtb_friction_limit(int n, rtb_real hK0, rtb_real hKr, const rtb_real *r, rtb_real Lp,
                       rtb_real Lm, int trial_solves, int max_solves, int *act, rtb_real *v,
                       rtb_real *f);

/* dv_0 / d r_0 times b0 for the active set act: the first cell's response
 * to a load b0 on it, still cells held (the STS step's tangent dy1/dxb with
 * b0 = Kpa). 0 on a singular system. */
rtb_real rtb_friction_limit_tangent(int n, rtb_real hK0, rtb_real hKr, const int *act,
                                    rtb_real b0);

#ifdef __cplusplus
}
#endif

#endif
