/* sts_return_map.cpp -- one step of the STS model (section 3.1, Figure 3).
 *
 * Cells of spring Kr in parallel with a friction element of threshold Ff,
 * chained exactly as the RT cells of eq. (2) (alpha = 0 limit, C0 = Ff).
 * The step is rate-independent; its backward-Euler form is the convex problem
 *   K y + f = b,  |f_k| <= Ff,  f_k = Ff sign(y_k - y_k_old) where y_k moves,
 * solved exactly by a primal-dual active-set method. K is a Stieltjes
 * (M-)matrix, for which the method terminates in finitely many iterations;
 * we cap them at RTB_STS_MAX_ITERS(N) = 2N + 5 solves and report
 * RTB_NOT_CONVERGED beyond, with the last solve's DOFs and their exact
 * tangent (that of the linear system of the last active set).
 */
#include <math.h>

#include "rtb_internal.h"
#include "tridiagonal.h"
#include "no_heap.h"

/* dy1/dxb of the solution of the system (lo, di, up) assembled for an active
 * set whose first DOF slides (slide0) or sticks: sliding DOFs follow b =
 * Kpa xb e1, stuck ones stay. Overwrites rhs. */
static rtb_real sts_tangent(int n, rtb_real Kpa, int slide0, const rtb_real *lo, const rtb_real *di,
                          const rtb_real *up, rtb_real *rhs, rtb_real *work) {
  for (int k = 0; k < n; ++k) rhs[k] = (k == 0 && slide0) ? Kpa : 0.0;
  rtb_tridiag_solve(n, lo, di, up, rhs, work);
  return rhs[0];
}

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
  const rtb_real Kpa = p->Kpa, Kr = p->Kr, Ff = p->Ff;
  rtb_real f[RTB_MAX_CELLS], lo[RTB_MAX_CELLS], di[RTB_MAX_CELLS], up[RTB_MAX_CELLS];
  rtb_real rhs[RTB_MAX_CELLS], work[RTB_MAX_CELLS];
  int act[RTB_MAX_CELLS]; /* -1 sliding down, 0 stuck, +1 sliding up */

  /* Elastic trial: nothing slides. */
  rtb_chain_apply(n, Kpa, Kr, y_old, f);
  for (int k = 0; k < n; ++k) {
    f[k] = (k == 0 ? Kpa * xb_new : 0.0) - f[k];
    act[k] = f[k] > Ff ? 1 : (f[k] < -Ff ? -1 : 0);
  }
  const rtb_real tie = RTB_STS_TIE_REL * Ff;
  int slide0 = 0; /* whether DOF 0 slid in the last solve (its tangent) */
  for (int it = 0; it < max_iters; ++it) {
    /* Solve with the current active set: stuck DOFs keep y_old, sliding DOFs
     * carry exactly +-Ff. */
    for (int k = 0; k < n; ++k) {
      if (act[k] == 0) {
        di[k] = 1.0; lo[k] = 0.0; up[k] = 0.0; rhs[k] = y_old[k];
      } else {
        di[k] = rtb_chain_diag(k, Kpa, Kr);
        lo[k] = k > 0 ? -Kr : 0.0;
        up[k] = k + 1 < n ? -Kr : 0.0;
        rhs[k] = (k == 0 ? Kpa * xb_new : 0.0) - act[k] * Ff;
      }
    }
    slide0 = act[0] != 0;
    if (rtb_tridiag_solve(n, lo, di, up, rhs, work) != 0) return RTB_ERR_OVERFLOW;
    rtb_chain_apply(n, Kpa, Kr, rhs, f);
    bool same = true;
    for (int k = 0; k < n; ++k) {
      f[k] = (k == 0 ? Kpa * xb_new : 0.0) - f[k];
      /* Complementarity function: friction force plus scaled slip. */
      const rtb_real g = (act[k] == 0 ? f[k] : act[k] * Ff) +
                       rtb_chain_diag(k, Kpa, Kr) * (rhs[k] - y_old[k]);
      const int a = g > Ff + tie ? 1 : (g < -Ff - tie ? -1 : 0);
      if (a != act[k]) { same = false; act[k] = a; }
    }
    if (same) {
      for (int k = 0; k < n; ++k) {
        y_new[k] = rhs[k];
        if (!isfinite(y_new[k])) return RTB_ERR_OVERFLOW;
      }
      *iterations = it + 1;
      if (dy1_dxb) *dy1_dxb = sts_tangent(n, Kpa, slide0, lo, di, up, rhs, work);
      return RTB_OK;
    }
  }
  /* Gave up: keep the last solve (rhs) and its own tangent, so that the
   * committed DOFs, the force and dF/dx describe the same iterate. */
  for (int k = 0; k < n; ++k) {
    y_new[k] = rhs[k];
    if (!isfinite(y_new[k])) return RTB_ERR_OVERFLOW;
  }
  *iterations = max_iters;
  if (dy1_dxb) *dy1_dxb = sts_tangent(n, Kpa, slide0, lo, di, up, rhs, work);
  return RTB_NOT_CONVERGED;
}
