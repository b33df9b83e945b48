/* stage_newton.cpp -- Newton solve of one implicit RT stage, eq. (2).
 *
 * Unknowns: the N dashpot forces f. Residual (see rtb_internal.h)
 *   H(f) = f + h K phi(f) - r,   r = b - K c,
 * which is M * grad E*(f) for the strictly convex dual energy
 *   E*(f) = 1/2 (f - r)^T K^-1 (f - r) + h sum_k Phi*(f_k),
 * so H = 0 has exactly one solution for every h > 0 (unconditional
 * solvability). The line search uses 1/2 |H|_2^2, of which Newton's
 * direction is a descent direction whatever the per-DOF update rule.
 *
 * Newton matrix: J = I + h K D, D = diag(phi'(f)), tridiagonal.
 * Update rule per DOF (same tangent, different return to the curve): where the
 * dashpot is steep (h K_kk phi'(f_k) > 1) the velocity is updated and the
 * force recomputed as psi(v); elsewhere the force is updated and the velocity
 * recomputed as phi(f). This keeps |v|^(1/alpha)-type growth out of the
 * iteration when alpha is small (near-friction dashpots), where plain
 * Newton in f needs O(1/alpha) iterations.
 *
 * With the eq. (14) smoothing (s > 0) the same solver runs on psi_s: it is
 * strictly increasing, so the dual energy stays strictly convex and the
 * variable switch is unchanged; force-updated DOFs invert psi_s by the
 * bounded safeguarded scalar Newton of dashpot_law.h.
 *
 * Work per stage is bounded: at most max_iter iterations, each with one
 * tridiagonal solve and at most max_backtrack+1 residual evaluations (with
 * smoothing, times at most RTB_SLAW_INV_ITERS per force-updated DOF).
 */
#include <float.h>
#include <math.h>

#include "dashpot_law.h"
#include "rtb_internal.h"
#include "tridiagonal.h"
#include "no_heap.h"

namespace {

struct Chain {
  int n;
  double Kpa, Kr, C0, alpha, h;
  double s;  /* eq. (14) smoothing [1/velocity], 0 = exact eq. (1) */
  double asym; /* fric_asym: level C0 (1 +- asym) by the sign of the motion */
  double level(double sign_of) const { return rtb_dashpot_level(C0, asym, sign_of); }
};

/* H = f + h K v - r; returns the max-norm (and the squared 2-norm in *sq),
 * or +inf if anything is non-finite. */
double residual(const Chain &ch, const double *f, const double *v, const double *r,
                double *H, double *sq) {
  double Kv[RTB_MAX_CELLS];
  rtb_chain_apply(ch.n, ch.Kpa, ch.Kr, v, Kv);
  double nrm = 0.0, s2 = 0.0;
  for (int k = 0; k < ch.n; ++k) {
    H[k] = f[k] + ch.h * Kv[k] - r[k];
    const double a = fabs(H[k]);
    if (!(a <= DBL_MAX)) return INFINITY;
    nrm = a > nrm ? a : nrm;
    s2 += a * a;
  }
  *sq = s2;
  return nrm;
}

}  // namespace

extern "C" rtb_status rtb_stage_solve(const rtb_params *p, const rtb_settings *set,
                                      const double *v_guess, rtb_stage *st) {
  const Chain ch = {p->cells, p->Kpa, p->Kr, p->C0, p->alpha, st->h, p->smoothing, p->fric_asym};
  const int n = ch.n;
  if (n < 1 || n > RTB_MAX_CELLS) return RTB_ERR_STATE;
  double r[RTB_MAX_CELLS], H[RTB_MAX_CELLS], D[RTB_MAX_CELLS], dl[RTB_MAX_CELLS];
  double lo[RTB_MAX_CELLS], di[RTB_MAX_CELLS], up[RTB_MAX_CELLS], work[RTB_MAX_CELLS];
  double ft[RTB_MAX_CELLS], vt[RTB_MAX_CELLS], Ht[RTB_MAX_CELLS];
  bool steep[RTB_MAX_CELLS];

  /* r = b - K c: the dashpot forces if no cell moved during the stage. */
  rtb_chain_apply(n, ch.Kpa, ch.Kr, st->c, r);
  double rnorm = 0.0;
  for (int k = 0; k < n; ++k) {
    r[k] = (k == 0 ? st->b1 : 0.0) - r[k];
    if (fabs(r[k]) > rnorm) rnorm = fabs(r[k]);
  }

  double *f = st->f, *v = st->v;
  for (int k = 0; k < n; ++k) {
    v[k] = v_guess ? v_guess[k] : 0.0;
    f[k] = rtb_dashpot_force(v[k], ch.level(v[k]), ch.alpha, ch.s);
  }
  double h2;
  double hnorm = residual(ch, f, v, r, H, &h2);
  if (!(hnorm <= DBL_MAX)) { /* warm start unusable: start from rest */
    for (int k = 0; k < n; ++k) f[k] = v[k] = 0.0;
    hnorm = residual(ch, f, v, r, H, &h2);
  }

  st->converged = 0;
  int it = 0;
  for (;; ++it) {
    double scale = rnorm;
    for (int k = 0; k < n; ++k) scale = fmax(scale, fabs(f[k]));
    if (hnorm <= set->tol * scale || hnorm <= DBL_MIN) { st->converged = 1; break; }
    if (it >= set->max_iter) break;

    /* Newton step: (I + h K D) df = -H. Column k of h K D carries D[k], so
     * every D must be known before the matrix is assembled. */
    for (int k = 0; k < n; ++k) D[k] = rtb_dashpot_dvdf(f[k], v[k], ch.level(f[k]), ch.alpha, ch.s);
    for (int k = 0; k < n; ++k) {
      const double hKD = ch.h * rtb_chain_diag(k, ch.Kpa, ch.Kr) * D[k];
      steep[k] = hKD > 1.0;
      di[k] = 1.0 + hKD;
      lo[k] = k > 0 ? -ch.h * ch.Kr * D[k - 1] : 0.0;
      up[k] = k + 1 < n ? -ch.h * ch.Kr * D[k + 1] : 0.0;
      dl[k] = -H[k];
    }
    if (rtb_tridiag_solve(n, lo, di, up, dl, work) != 0) break;

    /* Line search on the merit 1/2 |H|_2^2. Both update rules leave the
     * pair on the dashpot curve with df/dt = df at t = 0, so dH/dt = J df = -H
     * and the Newton path is a descent direction: Armijo with slope -|H|^2.
     * (A single merit: alternating between two merits can cycle.) */
    double t = 1.0;
    bool accepted = false;
    for (int bt = 0; bt <= set->max_backtrack; ++bt, t *= 0.5) {
      for (int k = 0; k < n; ++k) {
        if (steep[k]) {
          vt[k] = v[k] + t * D[k] * dl[k];
          ft[k] = rtb_dashpot_force(vt[k], ch.level(vt[k]), ch.alpha, ch.s);
        } else {
          ft[k] = f[k] + t * dl[k];
          /* guess: the tangent prediction (warm start of the s > 0 inverse) */
          vt[k] = rtb_dashpot_velocity(ft[k], ch.level(ft[k]), ch.alpha, ch.s, v[k] + t * D[k] * dl[k]);
        }
      }
      double ht2;
      const double ht = residual(ch, ft, vt, r, Ht, &ht2);
      if (!(ht <= DBL_MAX) || ht2 > (1.0 - 2e-4 * t) * h2) continue;
      for (int k = 0; k < n; ++k) { f[k] = ft[k]; v[k] = vt[k]; H[k] = Ht[k]; }
      hnorm = ht;
      h2 = ht2;
      accepted = true;
      break;
    }
    if (!accepted) break;
  }
  st->iterations = it;
  for (int k = 0; k < n; ++k) {
    st->y[k] = st->c[k] + ch.h * v[k];
    if (!isfinite(st->y[k])) return RTB_ERR_OVERFLOW;
  }
  return st->converged ? RTB_OK : RTB_NOT_CONVERGED;
}
