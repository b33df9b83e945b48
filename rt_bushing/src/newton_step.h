/* newton_step.h -- the linear algebra of one Newton step of an RT stage
 * (stage_newton.cpp): the LU of the Newton matrix, kept for a second
 * right-hand side, and the second-order term of the update, which gives the
 * Chebyshev correction and a direct estimate of what a linearised update
 * leaves.
 *
 * Stage residual (rtb_internal.h): H = f + h K v - r with v = phi(f).
 * Newton matrix J = I + h K D, D = diag(phi'(f)); K is the chain stiffness of
 * eq. (2): Kpa + Kr on the first diagonal entry, 2 Kr on the others, -Kr off
 * the diagonal (the last cell's spring ties to ground).
 */
#ifndef RTB_NEWTON_STEP_H
#define RTB_NEWTON_STEP_H

#include <math.h>
#include <stdbool.h>

#include "rtb_scalar.h"

/* LU of J (Thomas algorithm) with reciprocal pivots and the forward
 * substitution's multipliers premultiplied, so that a solve's two
 * recurrences are one multiply and one subtract per row and a second solve
 * with the same matrix costs no division. Column k of h K D carries D[k]. */
typedef struct rtb_newton_lu {
  int n;
  rtb_real inv[RTB_MAX_CELLS];  /* 1 / pivot k */
  rtb_real g[RTB_MAX_CELLS];    /* J[k][k-1] / pivot k */
  rtb_real w[RTB_MAX_CELLS];    /* J[k-1][k] / pivot k-1 */
} rtb_newton_lu;

/* Continuant bounds (rtb_newton_factor): matrix entries up to ENTRY_MAX
 * (so a product of two, c_k, is at most its square) and continuants
 * rescaled by 1/RESCALE once above RESCALE keep every product of a row below
 * the scalar's overflow (double: ~1e251, float: ~2e31). */
#ifdef RTB_SINGLE
#define RTB_NEWTON_ENTRY_MAX 1e6f
#define RTB_NEWTON_RESCALE 18446744073709551616.0f   /* 2^64: rescaling is exact */
#else
#define RTB_NEWTON_ENTRY_MAX 1e50
#define RTB_NEWTON_RESCALE 0x1p500                   /* 2^500 ~ 3e150 */
#endif

/* hK0 = h (Kpa + Kr), hKr = h Kr. Returns 0, or -1 on a zero pivot.
 * Why the continuant (session 10, 8-10% of a default step, docs/benchmarks.md):
 * the pivots obey piv_k = a_k - c_k / piv_k-1, a chain of dependent
 * divisions. Their
 * products, the leading principal minors p_k = a_k p_k-1 - c_k p_k-2, need
 * only a multiply and a subtract in the chain; each pivot is then the ratio
 * p_k / p_k-1, and those divisions are independent of one another. J is a
 * column diagonally dominant M-matrix (column sums 1, 1 + h Kpa D_0, 1 + h Kr
 * D_n-1), so in exact arithmetic every pivot is >= 1 and |p_k| only grows:
 * it is rescaled before it can overflow. (Next to steep cells the subtraction
 * cancels in either form; as before, only a zero pivot is rejected and the
 * line search judges the step: measured on BM_RandomConfigs, 4.36% of steps
 * end unconverged against 4.26% with the division chain, within the spread
 * of rounding-level changes on those configurations.) Entries beyond RTB_NEWTON_ENTRY_MAX (a near-rigid
 * dashpot) take the division chain, whose products stay bounded. */
static inline int rtb_newton_factor(int n, rtb_real hK0, rtb_real hKr, const rtb_real *D,
                                    rtb_newton_lu *F) {
  F->n = n;
  rtb_real dmax = 0.0;
  for (int k = 0; k < n; ++k) dmax = D[k] > dmax ? D[k] : dmax;
  const rtb_real kmax = hK0 > 2.0 * hKr ? hK0 : 2.0 * hKr;
  rtb_real piv = 1.0 + hK0 * D[0];
  if (!(piv != 0.0)) return -1;
  F->inv[0] = 1.0 / piv;
  if (kmax * dmax <= RTB_NEWTON_ENTRY_MAX) {
    rtb_real pm2 = 1.0, pm1 = piv;
    for (int k = 1; k < n; ++k) {
      const rtb_real lo = -hKr * D[k - 1], up = -hKr * D[k];
      rtb_real p = (1.0 + 2.0 * hKr * D[k]) * pm1 - (lo * up) * pm2;
      if (!(p != 0.0)) return -1;
      F->inv[k] = pm1 / p;
      if (fabs(p) > RTB_NEWTON_RESCALE) { p /= RTB_NEWTON_RESCALE; pm1 /= RTB_NEWTON_RESCALE; }
      pm2 = pm1;
      pm1 = p;
    }
    for (int k = 1; k < n; ++k) {
      F->g[k] = -hKr * D[k - 1] * F->inv[k];
      F->w[k] = -hKr * D[k] * F->inv[k - 1];
    }
    return 0;
  }
  for (int k = 1; k < n; ++k) {
    const rtb_real lo = -hKr * D[k - 1];
    F->w[k] = -hKr * D[k] * F->inv[k - 1];
    piv = 1.0 + 2.0 * hKr * D[k] - lo * F->w[k];
    if (!(piv != 0.0)) return -1;
    F->inv[k] = 1.0 / piv;
    F->g[k] = lo * F->inv[k];
  }
  return 0;
}

/* x = J^-1 (sign b); x may not alias b. */
static inline void rtb_newton_substitute(const rtb_newton_lu *F, rtb_real sign, const rtb_real *b,
                                         rtb_real *x) {
  const int n = F->n;
  /* sign b_k / pivot_k is off the chain: one multiply-subtract per row in it */
  x[0] = sign * b[0] * F->inv[0];
  for (int k = 1; k < n; ++k) x[k] = sign * b[k] * F->inv[k] - F->g[k] * x[k - 1];
  for (int k = n - 2; k >= 0; --k) x[k] -= F->w[k + 1] * x[k + 1];
}

/* out = h K u (the chain stiffness of eq. (2) times h); returns nothing. The
 * first and last rows are peeled so the interior loop has no branch. */
static inline void rtb_newton_hK_apply(int n, rtb_real hK0, rtb_real hKr, const rtb_real *u,
                                       rtb_real *out) {
  if (n < 1) return; /* u[0] would be read unwritten (make embedded's GCC says so) */
  out[0] = hK0 * u[0];
  if (n > 1) out[0] -= hKr * u[1];
  for (int k = 1; k < n - 1; ++k) out[k] = 2.0 * hKr * u[k] - hKr * (u[k - 1] + u[k + 1]);
  if (n > 1) out[n - 1] = 2.0 * hKr * u[n - 1] - hKr * u[n - 2];
}

/* Q = 1/2 H''[dl, dl], the residual's second-order term along the Newton
 * update dl (f-space), for the exact law eq. (1) only. Steep DOFs move v by
 * D dl and recompute f = psi(v), which gains 1/2 psi'' (D dl)^2 with
 * psi'' = (alpha - 1) / (D v); the others move f by dl and recompute
 * v = phi(f), which gains 1/2 phi'' dl^2 with phi'' = (1/alpha - 1) D / f
 * and enters H through h K. (Both from eq. (1): psi' = alpha f / v = 1 / D.)
 * *move: the largest relative move, |D dl / v| on steep DOFs, |dl / f| on
 * the others (+inf where a DOF at the origin moves; such a DOF adds nothing
 * to Q, the expansion does not hold there). Q is the leading term only where
 * *move is small against alpha: the third-order term is ~ (1/alpha) *move
 * times the second. One division per DOF. Returns max |Q|. */
static inline rtb_real rtb_newton_second_order(int n, rtb_real hK0, rtb_real hKr, rtb_real alpha,
                                               const bool *steep, const rtb_real *f,
                                               const rtb_real *v, const rtb_real *D,
                                               const rtb_real *dl, rtb_real *Q, rtb_real *move) {
  rtb_real df[RTB_MAX_CELLS], dv[RTB_MAX_CELLS];
  const rtb_real cs = 0.5 * (alpha - 1.0), cf = 0.5 * (1.0 / alpha - 1.0);
  rtb_real mv = 0.0;
  for (int k = 0; k < n; ++k) {
    const rtb_real du = steep[k] ? D[k] * dl[k] : dl[k];   /* move of the update variable */
    const rtb_real u = steep[k] ? v[k] : f[k];
    if (du == 0.0) { df[k] = dv[k] = 0.0; continue; }
    if (u == 0.0) { df[k] = dv[k] = 0.0; mv = INFINITY; continue; }
    const rtb_real rel = du / u;
    const rtb_real a = fabs(rel);
    mv = a > mv ? a : mv;
    /* steep: 1/2 psi'' (D dl)^2 = cs (du / v) dl; else 1/2 phi'' dl^2 = cf D (dl / f) dl */
    df[k] = steep[k] ? cs * rel * dl[k] : 0.0;
    dv[k] = steep[k] ? 0.0 : cf * D[k] * rel * dl[k];
  }
  rtb_newton_hK_apply(n, hK0, hKr, dv, Q);
  rtb_real m = 0.0;
  for (int k = 0; k < n; ++k) {
    Q[k] += df[k];
    m = fabs(Q[k]) > m ? fabs(Q[k]) : m;
  }
  *move = mv;
  return m;
}

#endif
