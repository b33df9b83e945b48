/* tridiagonal.h -- Thomas algorithm for the chain matrices of eq. (2).
 *
 * The cell chain couples only neighbours, so every linear system of the
 * stepper (Newton step, tangent, adjoint) is tridiagonal: O(N) work, no
 * pivoting. The Newton matrix I + h K D is column diagonally dominant and the
 * stiffness K is symmetric positive definite, both safe without pivoting.
 */
#ifndef RTB_TRIDIAGONAL_H
#define RTB_TRIDIAGONAL_H

#include "rtb_scalar.h"

/* Thomas factorization of A, with sub-diagonal lo[1..n-1], diagonal
 * di[0..n-1] and super-diagonal up[0..n-2]: the pivots piv[0..n-1] and the
 * eliminated super-diagonal w[1..n-1]. Factor once, then substitute for
 * each right-hand side (the offline Jacobian's columns share one stage
 * matrix). Returns 0, or -1 on a zero pivot. */
static inline int rtb_tridiag_factor(int n, const rtb_real *lo, const rtb_real *di,
                                     const rtb_real *up, rtb_real *piv, rtb_real *w) {
  if (n < 1) return -1;
  piv[0] = di[0];
  if (piv[0] == 0.0) return -1;
  for (int k = 1; k < n; ++k) {
    w[k] = up[k - 1] / piv[k - 1];
    piv[k] = di[k] - lo[k] * w[k];
    if (piv[k] == 0.0) return -1;
  }
  return 0;
}

/* x[c] = A^-1 x[c] for the m right-hand sides x[0..m-1], from
 * rtb_tridiag_factor's piv and w. The columns advance row by row together:
 * each is a chain of dependent divisions, and interleaved the chains
 * overlap (the offline Jacobian's columns); each column's arithmetic is
 * the same as alone. */
static inline void rtb_tridiag_subst_many(int n, const rtb_real *lo, const rtb_real *piv,
                                          const rtb_real *w, int m, rtb_real *const *x) {
  for (int c = 0; c < m; ++c) x[c][0] /= piv[0];
  for (int k = 1; k < n; ++k)
    for (int c = 0; c < m; ++c) x[c][k] = (x[c][k] - lo[k] * x[c][k - 1]) / piv[k];
  for (int k = n - 2; k >= 0; --k)
    for (int c = 0; c < m; ++c) x[c][k] -= w[k + 1] * x[c][k + 1];
}

/* x = A^-1 rhs from rtb_tridiag_factor's piv and w; rhs is overwritten. */
static inline void rtb_tridiag_subst(int n, const rtb_real *lo, const rtb_real *piv,
                                     const rtb_real *w, rtb_real *rhs) {
  rtb_tridiag_subst_many(n, lo, piv, w, 1, &rhs);
}

/* Solve A x = rhs (A as in rtb_tridiag_factor); rhs is overwritten by x,
 * and left unchanged on a zero pivot. work has n entries. Returns 0, or -1
 * on a zero pivot or n outside 1..RTB_MAX_CELLS. */
static inline int rtb_tridiag_solve(int n, const rtb_real *lo, const rtb_real *di,
                                    const rtb_real *up, rtb_real *rhs, rtb_real *work) {
  rtb_real piv[RTB_MAX_CELLS];
  if (n > RTB_MAX_CELLS || rtb_tridiag_factor(n, lo, di, up, piv, work) != 0) return -1;
  rtb_tridiag_subst(n, lo, piv, work, rhs);
  return 0;
}

/* Diagonal of the chain stiffness K of eq. (2): Kpa+Kr for the first DOF,
 * 2 Kr for the others (the last cell's spring ties to ground). Off-diagonals
 * are -Kr. */
static inline rtb_real rtb_chain_diag(int k, rtb_real Kpa, rtb_real Kr) {
  return k == 0 ? Kpa + Kr : 2.0 * Kr;
}

/* The matrix of a converged stage's tangent, A = I + h D K (transpose = 0;
 * row k carries D[k]) or its transpose I + h K D (the adjoint's), with
 * D = dv/df of each dashpot: the one assembly the stepper's dF/dx and the
 * offline tangent and adjoint all solve with. */
static inline void rtb_stage_matrix(int n, rtb_real h, const rtb_real *D, rtb_real Kpa, rtb_real Kr,
                                    int transpose, rtb_real *lo, rtb_real *di, rtb_real *up) {
  for (int k = 0; k < n; ++k) {
    di[k] = 1.0 + h * D[k] * rtb_chain_diag(k, Kpa, Kr);
    const int l = transpose ? k - 1 : k, u = transpose ? k + 1 : k;
    lo[k] = k > 0 ? -h * D[l] * Kr : 0.0;
    up[k] = k + 1 < n ? -h * D[u] * Kr : 0.0;
  }
}

/* out = K u for the chain stiffness. */
static inline void rtb_chain_apply(int n, rtb_real Kpa, rtb_real Kr, const rtb_real *u, rtb_real *out) {
  if (n < 1) return;
  /* The end rows peeled so the interior loop has no branch (a step calls
   * this three times); each row sums in the same order as ever. */
  const rtb_real K2 = 2.0 * Kr;
  out[0] = (Kpa + Kr) * u[0];
  if (n == 1) return;
  out[0] -= Kr * u[1];
  for (int k = 1; k < n - 1; ++k) out[k] = K2 * u[k] - Kr * u[k - 1] - Kr * u[k + 1];
  out[n - 1] = K2 * u[n - 1] - Kr * u[n - 2];
}

/* Solve K x = rhs in place (K symmetric positive definite). */
static inline int rtb_chain_solve(int n, rtb_real Kpa, rtb_real Kr, rtb_real *rhs, rtb_real *work) {
  if (n < 1 || n > RTB_MAX_CELLS) return -1;
  rtb_real lo[RTB_MAX_CELLS], di[RTB_MAX_CELLS], up[RTB_MAX_CELLS];
  for (int k = 0; k < n; ++k) {
    di[k] = rtb_chain_diag(k, Kpa, Kr);
    lo[k] = -Kr;
    up[k] = -Kr;
  }
  return rtb_tridiag_solve(n, lo, di, up, rhs, work);
}

#endif
