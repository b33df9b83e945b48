/* cell_row_solve.h -- one cell's row of the stage equation solved alone,
 * with its neighbours held: the stage solver's repair of a Newton step that
 * blew up (stage_newton.cpp, gauss_seidel_trial).
 *
 * Row k of H(f) = f + h K phi(f) - r = 0 (rtb_internal.h), with the
 * neighbours' velocities moved to the right-hand side:
 *   f + a v = b,   v = phi(f),   a = h K_kk > 0,
 *   b = r_k + h Kr (v_k-1 + v_k+1),
 * i.e. backward Euler of a single dashpot on a spring. The left side is
 * strictly increasing in f (and in v), so the root is unique, has b's sign,
 * and lies in |f| <= |b|, |v| <= |b| / a: a bracket known a priori.
 *
 * Why (issue #11): where the dashpots are near-friction (alpha ~ 0.01, or
 * eq. (14)-smoothed with a small level C0) and the load r is thousands of
 * times C0, Newton's linear step in f takes a shallow (force-updated) DOF
 * far past its friction level, and phi there is ~(f/C0)^(1/alpha): the
 * trial residual overflows and the line search halves t a dozen times per
 * iteration, gaining ~|H| t each time. Every cell's own row, solved exactly,
 * puts every force back near its level in one pass.
 *
 * Method: Newton on the row in the variable the per-DOF switch of
 * stage_newton.cpp would use (v where a phi'(f) > 1, else f), safeguarded by
 * both brackets: a step in v that leaves its bracket is taken in f instead,
 * and one in f that leaves its bracket becomes a bisection of the force
 * bracket (geometric when it spans decades). Start: the upper end v = |b| / a,
 * where the row's residual is psi(|b|/a) >= 0; in the friction regime this
 * is already within psi's level of the root. Every eq. (1) row of the test's
 * 20 000 random draws is solved within 8 evaluations; a smoothed one in 85%
 * (its inverse takes several psi_s evaluations per step in f).
 */
#ifndef RTB_CELL_ROW_SOLVE_H
#define RTB_CELL_ROW_SOLVE_H

#include <math.h>

#include "dashpot_law.h"
#include "rtb_scalar.h"

/* Law evaluations one row may take (a psi_s evaluation of the smoothed
 * inverse counts as one). Measured on BM_RandomConfigs' 90 000 steps at the
 * default budget, before stage_newton.cpp's gain rule: 8, 12 and 16 leave
 * 1.40%, 1.47% and 1.94% of them unconverged (a longer row solve spends
 * what the Newton steps need). With the gain rule, at 8: 1.53%. */
#define RTB_ROW_SOLVE_EVALS 8
/* The row is solved to this relative residual: a repair, which Newton's
 * iteration then finishes. */
#define RTB_ROW_SOLVE_TOL 1e-3

/* Solves f + a phi(f) = b (a > 0, b finite). Returns v = phi(f); *f the
 * force, *D = phi'(f) at the pair, *evals the law evaluations taken (<=
 * max_evals, >= 1 when b != 0; max_evals >= 2). The pair is on the dashpot
 * curve; when the evaluations run out it is the last iterate, its velocity
 * inside the bracket. */
static inline rtb_real rtb_cell_row_solve(const rtb_law *L, rtb_real a, rtb_real b, int max_evals,
                                          rtb_real *f, rtb_real *D, int *evals) {
  *evals = 0;
  if (b == 0.0) { *f = 0.0; *D = 0.0; return 0.0; }
  const rtb_real m = fabs(b), sg = b < 0.0 ? -1.0 : 1.0;
  /* Magnitudes along b's sign: |f| in [flo, fhi], |v| in [vlo, vhi]. */
  rtb_real vlo = 0.0, flo = 0.0, fhi = m, vhi = m / a;
  if (!(vhi <= RTB_REAL_MAX)) vhi = RTB_REAL_MAX;
  rtb_real v = vhi, fm = sg * rtb_law_eval_v(L, sg * v, D);
  *evals = 1;
  /* A smoothed inverse stopped by the cap leaves v off the curve: a last
   * step in f is then closed by f = psi_s(v), one evaluation kept for it. */
  const bool close = L->s > 0.0;
  bool last_in_f = false;
  while (*evals < max_evals - close) {
    /* phi overflows far past the level: then only the force bracket moves. */
    const bool finite = v <= RTB_REAL_MAX;
    const rtb_real G = finite ? fm + a * v - m : INFINITY; /* the row's residual, increasing */
    if (G > 0.0) { if (finite) vhi = v; fhi = fm; }
    else if (G < 0.0) { vlo = v; flo = fm; }
    if (!(fabs(G) > RTB_ROW_SOLVE_TOL * m)) break;
    if (finite && a * *D > 1.0) { /* steep: Newton in v, dG/dv = 1/D + a */
      const rtb_real vn = v - G / (1.0 / *D + a);
      if (vn > vlo && vn < vhi) {
        v = vn;
        fm = sg * rtb_law_eval_v(L, sg * v, D);
        ++*evals;
        last_in_f = false;
        continue;
      }
    }
    /* Shallow, or the step in v left its bracket: Newton in f, dG/df =
     * 1 + a D, else bisection of the force bracket (geometric when it spans
     * decades; also taken when v overflowed). */
    rtb_real fn = finite ? fm - G / (1.0 + a * *D) : fm;
    if (!(fn > flo && fn < fhi))
      fn = (flo > 0.0 && fhi > 4.0 * flo) ? sqrt(flo) * sqrt(fhi) : flo + 0.5 * (fhi - flo);
    fm = fn;
    int cap = max_evals - close - *evals; /* the smoothed inverse's evaluations */
    v = sg * rtb_law_eval_f(L, sg * fm, sg * v, 0.0, D, &cap, 0);
    *evals += cap;
    last_in_f = true;
  }
  if (close && last_in_f) {
    fm = sg * rtb_law_eval_v(L, sg * v, D);
    ++*evals;
  }
  *f = sg * fm;
  return sg * v;
}

/* One Gauss-Seidel pass along an n-cell chain (stage_newton.cpp's repair):
 * row k solved with a = h K_kk (hK0 for k = 0, 2 hKr after) and b = r_k +
 * hKr (v_k-1 + v_k+1), the velocity before it already updated, the one after
 * it from v0. Fills f, v, D; returns the law evaluations taken (at most
 * n RTB_ROW_SOLVE_EVALS). Out of line (cell_row_solve.cpp): inlined into the
 * stage solver, this rarely taken code made every ordinary step ~5% slower
 * (BM_Latency/variant:0/N:15 921 -> 972-991 ns; the same instructions). */
#ifdef __cplusplus
extern "C" {
#endif
int rtb_cell_gauss_seidel(const rtb_law *L, int n, rtb_real hK0, rtb_real hKr, const rtb_real *r,
                          const rtb_real *v0, rtb_real *f, rtb_real *v, rtb_real *D);
#ifdef __cplusplus
}
#endif

#endif
