/* sts_return_map.cpp -- one step of the STS model (section 3.1, Figure 3).
 *
 * Cells of spring Kr in parallel with a friction element of threshold Ff,
 * chained exactly as the RT cells of eq. (2) (alpha = 0 limit, C0 = Ff).
 * The step is rate-independent; its backward-Euler form is the convex problem
 *   K y + f = b,  |f_k| <= Ff,  f_k = Ff sign(y_k - y_k_old) where y_k moves,
 * solved exactly by a primal-dual active-set method, in the increments
 * v = y - y_old: it is the alpha -> 0 limit of an RT stage with h = 1, and
 * friction_limit.h holds the one solver of both. From the elastic trial's
 * set (one solve when little slides), and if that cycles, from the
 * level-free solve's: the elastic trial alone cycled on 5.6% of random
 * harsh steps (tests/friction_limit_test.cpp: a cell dragged by its
 * neighbour against its own load flips side at every solve), which ended
 * unconverged at the cap; now none does, and the smooth steps of
 * tests/realtime_test.cpp take the same solves as before. Capped at
 * RTB_STS_MAX_ITERS(N) = 2N + 5 solves, RTB_NOT_CONVERGED beyond, with the
 * last solve's DOFs and their exact tangent (that of the linear system of
 * the last active set).
 */
#include <math.h>

#include "friction_limit.h"
#include "rtb_internal.h"
#include "tridiagonal.h"
#include "no_heap.h"


extern "C" rtb_status rtb_sts_solve(const rtb_params *p, const rtb_real *y_old,
                                    rtb_real xb_new, rtb_real *y_new, int *iterations,
                                    rtb_real *dy1_dxb) {
  return rtb_sts_solve_capped(p, y_old, xb_new, y_new, iterations, dy1_dxb,
                              RTB_STS_MAX_ITERS(p->cells));
}

extern "C" rtb_status rtb_sts_solve_capped(const rtb_params *p, const rtb_real *y_old,
                                           rtb_real xb_new, rtb_real *y_new, int *iterations,
                                           rtb_real *dy1_dxb, int max_iters) {
  const int n = p->cells;
  if (n < 1 || n > RTB_MAX_CELLS) return RTB_ERR_STATE;
  if (max_iters < 1) max_iters = 1;
  const rtb_real Kpa = p->Kpa, Kr = p->Kr;
  /* r zeroed: rtb_chain_apply writes its first n entries, which GCC 12 at
   * -O3 -march=x86-64-v4 (or native on an AVX-512 host) cannot see, and the
   * library builds with -Werror. */
  rtb_real r[RTB_MAX_CELLS] = {0}, dy[RTB_MAX_CELLS], f[RTB_MAX_CELLS];
  int act[RTB_MAX_CELLS]; /* -1 sliding down, 0 stuck, +1 sliding up */
  /* r = b - K y_old: the friction forces if nothing slid (the elastic trial). */
  rtb_chain_apply(n, Kpa, Kr, y_old, r);
  for (int k = 0; k < n; ++k) r[k] = (k == 0 ? Kpa * xb_new : 0.0) - r[k];
  const int solves = rtb_friction_limit(n, Kpa + Kr, Kr, r, p->Ff, p->Ff, max_iters, max_iters,
                                        act, dy, f);
  if (solves == 0) return RTB_ERR_OVERFLOW;
  /* Settled or not, the last solve's DOFs and their own tangent, so that the
   * committed DOFs, the force and dF/dx describe the same iterate. */
  for (int k = 0; k < n; ++k) {
    y_new[k] = y_old[k] + dy[k];
    if (!isfinite(y_new[k])) return RTB_ERR_OVERFLOW;
  }
  *iterations = solves > 0 ? solves : -solves;
  if (dy1_dxb) *dy1_dxb = rtb_friction_limit_tangent(n, Kpa + Kr, Kr, act, Kpa);
  return solves > 0 ? RTB_OK : RTB_NOT_CONVERGED;
}
