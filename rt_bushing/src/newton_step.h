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

/* Twisted LU of J: the Thomas algorithm run from both ends at once, rows
 * above m = n/2 eliminated downwards, rows below upwards, meeting at row m.
 * A Newton iteration is a chain of dependent steps (factor, solve, sweep,
 * solve again), and each recurrence of a solve is a chain through its rows:
 * from both ends that chain is n/2 rows long instead of n, two independent
 * chains that the core runs side by side (measured on one dependent solve of
 * 15 rows: 58 -> 36 ns; docs/benchmarks.md, session 10). The multipliers are
 * premultiplied by the reciprocal pivots, so every row of a solve is one
 * multiply and one subtract in its chain, and a second solve with the same
 * factors costs no division. Column k of h K D carries D[k]. */
typedef struct rtb_newton_lu {
  int n, m;                     /* size; the meeting row, n / 2 */
  rtb_real inv[RTB_MAX_CELLS];  /* 1 / pivot k of its own end (m: the meeting row's) */
  rtb_real g[RTB_MAX_CELLS];    /* elimination multiplier towards m: J[k][k-1] /
                                   pivot k-1 for k <= m, J[k][k+1] / pivot k+1 for k > m */
  rtb_real w[RTB_MAX_CELLS];    /* back substitution away from m: J[k][k+1] / pivot k
                                   for k < m, J[k][k-1] / pivot k for k > m */
  rtb_real gm;                  /* row m's other multiplier, J[m][m+1] / pivot m+1 */
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

/* One row of an end's elimination: the continuant p = a p1 - c p2 of the
 * pivots so far (p1 the last, p2 the one before), the new reciprocal pivot
 * p1 / p into *inv, and (p1, p2) advanced. Returns -1 on a zero pivot. */
static inline int rtb_newton_continuant_row(rtb_real a, rtb_real c, rtb_real *p1, rtb_real *p2,
                                            rtb_real *inv) {
  rtb_real p = a * *p1 - c * *p2;
  if (!(p != 0.0)) return -1;
  *inv = *p1 / p;
  if (fabs(p) > RTB_NEWTON_RESCALE) { p /= RTB_NEWTON_RESCALE; *p1 /= RTB_NEWTON_RESCALE; }
  *p2 = *p1;
  *p1 = p;
  return 0;
}

/* hK0 = h (Kpa + Kr), hKr = h Kr. Returns 0, or -1 on a zero pivot.
 * Row k: diagonal a_k = 1 + h K_kk D_k, off-diagonals J[k][k-1] = -e_k-1 and
 * J[k][k+1] = -e_k+1 with e_k = h Kr D_k, so eliminating the pair (k, k+1)
 * from either end subtracts c = e_k e_k+1 / (the neighbour's pivot).
 * Why continuants (session 10): the pivots obey piv = a - c / piv_prev, a
 * chain of dependent divisions; their products p = a p_prev - c p_prevprev
 * (the minors) need a multiply and a subtract in the chain, and each
 * reciprocal pivot p_prev / p is a division off it. J is a column diagonally
 * dominant M-matrix (column sums 1, 1 + h Kpa D_0, 1 + h Kr D_n-1), so in
 * exact arithmetic every pivot is >= 1 from either end and |p| only grows:
 * it is rescaled before it can overflow. Next to steep cells the
 * subtraction cancels in either form; as with the division chain, only a
 * zero pivot is rejected and the line search judges the step (requiring
 * positive pivots doubled BM_RandomConfigs' unconverged steps). Entries
 * beyond RTB_NEWTON_ENTRY_MAX (a near-rigid dashpot) take the division
 * chain, whose products stay bounded. */
static inline int rtb_newton_factor(int n, rtb_real hK0, rtb_real hKr, const rtb_real *D,
                                    rtb_newton_lu *F) {
  const int m = n / 2;
  F->n = n;
  F->m = m;
  rtb_real dmax = 0.0;
  for (int k = 0; k < n; ++k) dmax = D[k] > dmax ? D[k] : dmax;
  const rtb_real kmax = hK0 > 2.0 * hKr ? hK0 : 2.0 * hKr;
#define RTB_NEWTON_A(k) (1.0 + ((k) == 0 ? hK0 : 2.0 * hKr) * D[k])
#define RTB_NEWTON_E(k) (hKr * D[k])
  if (m > 0) F->inv[0] = 1.0 / RTB_NEWTON_A(0);
  if (n - 1 > m) F->inv[n - 1] = 1.0 / RTB_NEWTON_A(n - 1);
  if (kmax * dmax <= RTB_NEWTON_ENTRY_MAX) {
    rtb_real t1 = m > 0 ? RTB_NEWTON_A(0) : 1.0, t2 = 1.0;
    rtb_real b1 = RTB_NEWTON_A(n - 1), b2 = 1.0;
    for (int kt = 1, kb = n - 2; kt < m || kb > m; ++kt, --kb) { /* both ends side by side */
      if (kt < m && rtb_newton_continuant_row(RTB_NEWTON_A(kt), RTB_NEWTON_E(kt - 1) * RTB_NEWTON_E(kt),
                                              &t1, &t2, &F->inv[kt]) != 0)
        return -1;
      if (kb > m && rtb_newton_continuant_row(RTB_NEWTON_A(kb), RTB_NEWTON_E(kb) * RTB_NEWTON_E(kb + 1),
                                              &b1, &b2, &F->inv[kb]) != 0)
        return -1;
    }
  } else {
    for (int k = 1; k < m; ++k) {
      const rtb_real piv = RTB_NEWTON_A(k) - RTB_NEWTON_E(k - 1) * (RTB_NEWTON_E(k) * F->inv[k - 1]);
      if (!(piv != 0.0)) return -1;
      F->inv[k] = 1.0 / piv;
    }
    for (int k = n - 2; k > m; --k) {
      const rtb_real piv = RTB_NEWTON_A(k) - RTB_NEWTON_E(k + 1) * (RTB_NEWTON_E(k) * F->inv[k + 1]);
      if (!(piv != 0.0)) return -1;
      F->inv[k] = 1.0 / piv;
    }
  }
  /* The meeting row: both neighbours eliminated into it. */
  rtb_real piv = RTB_NEWTON_A(m);
  F->g[m] = 0.0;
  F->gm = 0.0;
  if (m > 0) {
    F->g[m] = -RTB_NEWTON_E(m - 1) * F->inv[m - 1];
    piv += F->g[m] * RTB_NEWTON_E(m);
  }
  if (n - 1 > m) {
    F->gm = -RTB_NEWTON_E(m + 1) * F->inv[m + 1];
    piv += F->gm * RTB_NEWTON_E(m);
  }
  if (!(piv != 0.0)) return -1;
  F->inv[m] = 1.0 / piv;
  for (int k = 1; k < m; ++k) F->g[k] = -RTB_NEWTON_E(k - 1) * F->inv[k - 1];
  for (int k = 0; k < m; ++k) F->w[k] = -RTB_NEWTON_E(k + 1) * F->inv[k];
  for (int k = m + 1; k < n - 1; ++k) F->g[k] = -RTB_NEWTON_E(k + 1) * F->inv[k + 1];
  for (int k = m + 1; k < n; ++k) F->w[k] = -RTB_NEWTON_E(k - 1) * F->inv[k];
#undef RTB_NEWTON_A
#undef RTB_NEWTON_E
  return 0;
}

/* x = J^-1 (sign b); x may not alias b. Towards m: y_k = sign b_k - g_k
 * y_k-1 from the top, likewise from the bottom; away from m: x_k = y_k /
 * pivot_k - w_k x_k+-1. The two ends' chains are interleaved in one loop. */
static inline void rtb_newton_substitute(const rtb_newton_lu *F, rtb_real sign, const rtb_real *b,
                                         rtb_real *x) {
  const int n = F->n, m = F->m;
  rtb_real yt = 0.0, yb = 0.0;
  if (m > 0) x[0] = yt = sign * b[0];
  if (n - 1 > m) x[n - 1] = yb = sign * b[n - 1];
  /* Both ends side by side for as many rows as the shorter has, with one
   * loop counter (a step is bound by instructions, not latency: docs/
   * benchmarks.md, session 12), then the longer end's rest. */
  const int shorter = m - 1 < n - 2 - m ? m - 1 : n - 2 - m;
  const int both = shorter > 0 ? shorter : 0;
  for (int i = 1; i <= both; ++i) {
    x[i] = yt = sign * b[i] - F->g[i] * yt;
    x[n - 1 - i] = yb = sign * b[n - 1 - i] - F->g[n - 1 - i] * yb;
  }
  for (int kt = both + 1; kt < m; ++kt) x[kt] = yt = sign * b[kt] - F->g[kt] * yt;
  for (int kb = n - 2 - both; kb > m; --kb) x[kb] = yb = sign * b[kb] - F->g[kb] * yb;
  const rtb_real xm = (sign * b[m] - F->g[m] * yt - F->gm * yb) * F->inv[m];
  x[m] = xm;
  rtb_real xt = xm, xb = xm;
  const int away = m < n - 1 - m ? m : n - 1 - m; /* rows both sides have beyond m */
  for (int i = 1; i <= away; ++i) {
    x[m - i] = xt = x[m - i] * F->inv[m - i] - F->w[m - i] * xt;
    x[m + i] = xb = x[m + i] * F->inv[m + i] - F->w[m + i] * xb;
  }
  for (int kt = m - away - 1; kt >= 0; --kt) x[kt] = xt = x[kt] * F->inv[kt] - F->w[kt] * xt;
  for (int kb = m + away + 1; kb < n; ++kb) x[kb] = xb = x[kb] * F->inv[kb] - F->w[kb] * xb;
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

/* Q = df + h K dv, the second-order term of H = f + h K v - r from the
 * pairs' second-order moves df (steep DOFs) and dv (the others); returns
 * max |Q|. */
static inline rtb_real rtb_newton_second_order_sum(int n, rtb_real hK0, rtb_real hKr,
                                                   const rtb_real *df, const rtb_real *dv,
                                                   rtb_real *Q) {
  rtb_newton_hK_apply(n, hK0, hKr, dv, Q);
  rtb_real m = 0.0;
  for (int k = 0; k < n; ++k) {
    Q[k] += df[k];
    m = fabs(Q[k]) > m ? fabs(Q[k]) : m;
  }
  return m;
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
  *move = mv;
  return rtb_newton_second_order_sum(n, hK0, hKr, df, dv, Q);
}

/* The same term for any law given its curvature C = psi''/psi' at each pair
 * (the eq. (14) smoothing, whose psi_s'' has no form in f and v alone): a
 * steep DOF gains 1/2 psi'' (D dl)^2 = 1/2 C D dl^2 in f, the others
 * 1/2 phi'' dl^2 = -1/2 C D^2 dl^2 in v (phi'' = -psi'' / psi'^3, psi' =
 * 1/D). For eq. (1), C = (alpha - 1)/v gives rtb_newton_second_order's
 * terms. No division. Returns max |Q|. */
static inline rtb_real rtb_newton_second_order_curv(int n, rtb_real hK0, rtb_real hKr,
                                                    const bool *steep, const rtb_real *D,
                                                    const rtb_real *C, const rtb_real *dl,
                                                    rtb_real *Q, rtb_real *slope_change) {
  rtb_real df[RTB_MAX_CELLS], dv[RTB_MAX_CELLS];
  rtb_real sc = 0.0;
  for (int k = 0; k < n; ++k) {
    const rtb_real cdv = fabs(C[k] * D[k] * dl[k]); /* |psi'(v + dv) / psi'(v) - 1| to first order */
    sc = cdv > sc ? cdv : sc;
    const rtb_real q = 0.5 * C[k] * D[k] * dl[k] * dl[k];
    df[k] = steep[k] ? q : 0.0;
    dv[k] = steep[k] ? 0.0 : -q * D[k];
  }
  *slope_change = sc;
  return rtb_newton_second_order_sum(n, hK0, hKr, df, dv, Q);
}

/* The pair after an update dc taken without a law sweep (eq. (1) only): the
 * update variable moves by its linear part (steep DOFs: v + D dc, the
 * others: f + dc) and the other one by its Taylor expansion to second order,
 * with the coefficients of rtb_newton_second_order; t3f / t3v receive the
 * third-order terms, psi_3 (D dc)^3 / 6 = (alpha-1)(alpha-2)/6 rel^2 dc on
 * steep DOFs and phi_3 dc^3 / 6 = (1/alpha-1)(1/alpha-2)/6 D rel^2 dc on
 * the others (psi_3, phi_3 the third derivatives of eq. (1) and its inverse;
 * rel = D dc / v, resp. dc / f), i.e. how far the pair is off the curve to
 * leading order. D_out: the slope dv/df at the new pair to first order,
 * D (1 - (alpha-1) rel) on steep DOFs (1/psi'(v (1 + rel))) and
 * D (1 + (1/alpha-1) rel) on the others (phi'(f (1 + rel))), so the tangent
 * and the next stage's start see the slope to second order in the move.
 * Returns the largest relative move |rel| (+inf where a DOF at the origin
 * moves: the expansion does not hold there). */
static inline rtb_real rtb_newton_expanded_pair(int n, rtb_real alpha, const bool *steep,
                                                const rtb_real *f, const rtb_real *v,
                                                const rtb_real *D, const rtb_real *dc,
                                                rtb_real *f_out, rtb_real *v_out,
                                                rtb_real *D_out, rtb_real *t3f, rtb_real *t3v) {
  const rtb_real cs = 0.5 * (alpha - 1.0), cf = 0.5 * (1.0 / alpha - 1.0);
  const rtb_real c3s = (alpha - 1.0) * (alpha - 2.0) / 6.0;
  const rtb_real c3f = (1.0 / alpha - 1.0) * (1.0 / alpha - 2.0) / 6.0;
  rtb_real mv = 0.0;
  for (int k = 0; k < n; ++k) {
    const rtb_real du = steep[k] ? D[k] * dc[k] : dc[k];
    const rtb_real u = steep[k] ? v[k] : f[k];
    rtb_real rel = 0.0;
    if (du != 0.0) {
      if (u == 0.0) return INFINITY;
      rel = du / u;
    }
    const rtb_real a = fabs(rel);
    mv = a > mv ? a : mv;
    if (steep[k]) {
      v_out[k] = v[k] + du;
      f_out[k] = f[k] + dc[k] + cs * rel * dc[k];
      D_out[k] = D[k] - 2.0 * cs * rel * D[k];
      t3f[k] = c3s * rel * rel * dc[k];
      t3v[k] = 0.0;
    } else {
      f_out[k] = f[k] + dc[k];
      v_out[k] = v[k] + D[k] * dc[k] + cf * D[k] * rel * dc[k];
      D_out[k] = D[k] + 2.0 * cf * rel * D[k];
      t3f[k] = 0.0;
      t3v[k] = c3f * D[k] * rel * rel * dc[k];
    }
  }
  return mv;
}

#endif
