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
 * Start (issue #11): the caller passes a pair (f0, v0) that lies on the
 * dashpot curve to within the previous solve's tolerance -- the previous step's
 * end for the first stage, the first stage's solution for the second -- with
 * its D0. Its residual costs no law evaluation, so the first Newton step (a
 * linearly implicit predictor) is free of transcendentals; the law is then
 * evaluated once per iteration. If that start is unusable (non-finite, or the
 * first line search fails because the pair was off the curve) the solve
 * restarts from the law evaluated at v_guess, or from rest.
 *
 * With the eq. (14) smoothing (s > 0) the same solver runs on psi_s: it is
 * strictly increasing, so the dual energy stays strictly convex and the
 * variable switch is unchanged; force-updated DOFs invert psi_s by the
 * bounded safeguarded scalar Newton of dashpot_law.h.
 *
 * Chebyshev step (issue #11; eq. (1) only): the curvature of the law along
 * the Newton update is known in closed form (newton_step.h), so each update
 * is first tried with its second-order correction, one more substitution
 * with the same LU: cubic instead of quadratic local convergence. On the
 * 1 kHz benchmark input this takes a stage from 2.8 to 2.0 law sweeps. The
 * same term estimates what a sweep-free last update leaves.
 *
 * Repair of a blown-up step (session 22): where r is far past the
 * dashpots' level (near-friction dashpots under large moves), Newton's full
 * step sends shallow DOFs' forces past the level and v = phi(f) overflows.
 * Rather than halving t a dozen times per iteration, the stage then tries one
 * Gauss-Seidel pass that solves each cell's own row exactly
 * (cell_row_solve.h). On BM_RandomConfigs' 90 000 steps this takes the
 * unconverged share at the default budget from 3.77% to 1.53% and the mean
 * work from 294 to 203 units (at 640 units: 21.4% to 16.6%); near-friction
 * elements driven by large jumps that never converged now do
 * (tests/cell_row_solve_test.cpp). Steps whose full step does not blow up
 * are unchanged, bit for bit.
 *
 * Near-friction start (session 35): for eq. (1) with alpha <= 0.1 the stage
 * also solves its rate-independent limit (friction_limit.h: which cells
 * slide, exactly, in a few tridiagonal solves) and starts from it when its
 * residual is lower. From the last step's pair, a cell that must go from
 * sticking to slipping made Newton overshoot the level and halve its step
 * about ten times per stage. On the records of a diagnosis whose baseline
 * fitted alpha = 0.001 (blindgen backlash+cubic_stiffness, seed 17): 440-610
 * work units per step -> 178-198, 8.5-11.8 -> 2.7 Newton iterations, 10-20
 * -> 0.1-0.2 halvings, 1-7 unconverged steps of 8000 -> none, median step
 * 10-18 -> 3.4-6 us. BM_RandomConfigs' unconverged share: 1.53% -> 1.35% at
 * the default budget, 16.5% -> 12.2% at 640 units from this start alone
 * (1.05% and 11.5% with the STS return map on the same solver). Not with the eq. (14)
 * smoothing, where it cost more than it saved (CellRowSolve's smoothed
 * jumps: 600 -> 830 units per step), nor above alpha = 0.1, where the level
 * changes too much with the velocity for the limit to help (alpha <= 0.3:
 * 12.0% at 640 units, but the default element's median step doubled).
 *
 * Stuck cells (session 18): a cell whose dashpot force keeps its velocity
 * too small to move the residual by a thousandth of the tolerance is held at
 * v = 0 and left out of the law sweeps and the Newton matrix (active_cells,
 * below); the solve runs on the cells that move.
 *
 * Work is bounded by the step's budget (*budget, rt_bushing.h
 * RTB_STEP_WORK): a sweep starts only if the budget still holds one
 * evaluation per cell, and every evaluation (each psi_s evaluation of the
 * smoothed inverse included, at RTB_SLAW_UNIT units) is taken from it. When
 * it runs out the last accepted iterate is kept and RTB_NOT_CONVERGED
 * returned.
 */
#include <float.h>
#include <math.h>

#include "cell_row_solve.h"
#include "dashpot_law.h"
#include "friction_limit.h"
#include "law_lanes.h"
#include "newton_step.h"
#include "rtb_internal.h"
#include "tridiagonal.h"
#include "no_heap.h"

namespace {

struct Chain {
  int n;
  rtb_real Kpa, Kr, h;
  rtb_real hKr, hK0;   /* h Kr and h (Kpa + Kr): the Newton matrix's entries */
  rtb_law law;       /* eq. (1) / (14) with its constants hoisted */
  int unit;          /* work units of one law evaluation (RTB_STEP_WORK) */
  int sweep;         /* ... of a sweep over all cells: n * unit */
};

/* The update variable of DOF k with slope D: its velocity where the dashpot
 * is steep, h K_kk D > 1 (see the top of this file), else its force. */
inline bool steep_at(const Chain &ch, int k, rtb_real D) {
  return (k == 0 ? ch.hK0 : 2.0 * ch.hKr) * D > 1.0;
}

/* H = f + h K v - r; returns the max-norm (and the squared 2-norm in *sq),
 * or +inf if anything is non-finite. */
rtb_real residual(const Chain &ch, const rtb_real *f, const rtb_real *v, const rtb_real *r,
                  rtb_real *H, rtb_real *sq) {
  const int n = ch.n;
  const rtb_real hKr = ch.hKr, hK2 = 2.0 * ch.hKr;
  /* h K v as rtb_newton_hK_apply forms it, then + (f - r): the same bits, one pass. */
  rtb_real Kv0 = ch.hK0 * v[0];
  if (n > 1) Kv0 -= hKr * v[1];
  H[0] = Kv0 + (f[0] - r[0]);
  rtb_real nrm = fabs(H[0]), s2 = nrm * nrm;
  for (int k = 1; k < n - 1; ++k) {
    H[k] = (hK2 * v[k] - hKr * (v[k - 1] + v[k + 1])) + (f[k] - r[k]);
    const rtb_real a = fabs(H[k]);
    nrm = a > nrm ? a : nrm;
    s2 += a * a;
  }
  if (n > 1) {
    H[n - 1] = (hK2 * v[n - 1] - hKr * v[n - 2]) + (f[n - 1] - r[n - 1]);
    const rtb_real a = fabs(H[n - 1]);
    nrm = a > nrm ? a : nrm;
    s2 += a * a;
  }
  if (!(nrm <= RTB_REAL_MAX) || s2 != s2) return INFINITY; /* inf or NaN somewhere */
  *sq = s2;
  return nrm;
}

/* The update choice of cells lo .. hi-1 at their slopes D (steep_at), and
 * max(m, max |f|) over them: what every new iterate needs. */
rtb_real mark_cells(const Chain &ch, int lo, int hi, const rtb_real *f, const rtb_real *D,
                    bool *steep, rtb_real m) {
  for (int k = lo; k < hi; ++k) {
    steep[k] = steep_at(ch, k, D[k]);
    const rtb_real a = fabs(f[k]);
    m = a > m ? a : m;
  }
  return m;
}

/* Evaluate the law at v (steep DOFs) or f (the others) for all cells; D =
 * dv/df at the new pair, and the next iteration's choice of update variable
 * (steep: h K_kk D > 1). Smoothed law: C = psi_s''/psi_s' at the pairs (the
 * Chebyshev step's curvature; no further transcendental). ftol: the smoothed
 * inverse's force tolerance (0: to rounding). Takes the evaluations from
 * *budget; returns max |f|. */
rtb_real law_sweep(const Chain &ch, bool *steep, rtb_real *f, rtb_real *v, rtb_real *D,
                   rtb_real *C, int *budget, rtb_real ftol = 0.0) {
  const int n = ch.n;
  if (!(ch.law.s > 0.0)) { /* eq. (1): one power per cell, all cells at once */
    rtb_law_sweep_lanes(&ch.law, n, steep, f, v, D);
    *budget -= n;
  } else {
    for (int k = 0; k < n; ++k) {
      if (steep[k]) {
        f[k] = rtb_law_eval_v_c(&ch.law, v[k], &D[k], &C[k]);
        *budget -= ch.unit;
      } else {
        /* v[k] holds the tangent prediction: the smoothed inverse's warm
         * start. Leave one evaluation for each cell still to come. */
        int cap = (*budget - ch.unit * (n - 1 - k)) / ch.unit;
        v[k] = rtb_law_eval_f(&ch.law, f[k], v[k], ftol, &D[k], &cap, &C[k]);
        *budget -= ch.unit * cap;
      }
    }
  }
  return mark_cells(ch, 0, n, f, D, steep, 0.0);
}

/* Pair (f, v), slopes D, residual H and the update choice of one iterate;
 * with the smoothed law, the curvatures C = psi_s''/psi_s' where known. */
struct Iterate {
  rtb_real f[RTB_MAX_CELLS], v[RTB_MAX_CELLS], D[RTB_MAX_CELLS], H[RTB_MAX_CELLS];
  rtb_real C[RTB_MAX_CELLS];
  bool steep[RTB_MAX_CELLS];
  bool curv_ok;                  /* C holds every cell's curvature (smoothed law) */
  rtb_real fmax_abs, hnorm, h2;  /* max |f|, max |H|, |H|_2^2 */
};

/* A bound of the third-order part of what the linearised update dl leaves,
 * for the eq. (14) law, from K = |psi_s'''/psi_s'| and C = |psi_s''/psi_s'|:
 * K + 3 C^2 <= min(4 s^2, 256 / v^2) at every v (the law is a function of
 * s v; measured over s|v| = 1e-6 .. 1e6, alpha = 0.001 .. 1: K <= 0.96 s^2
 * and 57 / v^2, C^2 <= 0.95 s^2 and 48 / v^2), and along a move du = D dl
 * of at most |v| / 2 at most four times that bound at v. A steep DOF's force
 * is then off by at most B du^2 |dl| / 6, another's velocity (|phi'''| <=
 * (K + 3 C^2) D^3) by B D du^2 |dl| / 6, which h K carries into H with its
 * row sum. NaN: no bound. */
rtb_real smoothed_third_order(const Chain &ch, const Iterate &x, const rtb_real *dl) {
  const rtb_real s2 = 4.0 * ch.law.s * ch.law.s;
  rtb_real fs = 0.0, vs = 0.0;
  for (int k = 0; k < ch.n; ++k) {
    const rtb_real du = x.D[k] * dl[k], v = x.v[k];
    const rtb_real near = 1024.0 / (v * v); /* 4 x 256 / v^2, inf at v = 0 */
    const rtb_real B = fabs(du) <= 0.5 * fabs(v) && near < s2 ? near : s2;
    const rtb_real t = B * du * du * fabs(dl[k]) / 6.0;
    if (x.steep[k]) fs = t > fs || t != t ? t : fs;
    else vs = x.D[k] * t > vs || t != t ? x.D[k] * t : vs;
  }
  const rtb_real rows = ch.hK0 + ch.hKr > 4.0 * ch.hKr ? ch.hK0 + ch.hKr : 4.0 * ch.hKr;
  return fs + rows * vs;
}

/* What the linearised update dl would leave of the residual, or +inf when
 * that cannot be told. Eq. (1): the second-order term Q (newton_step.h),
 * computed directly, where it is the leading one (relative moves below
 * alpha / 10), and Q is kept for chebyshev_step (*have_Q); *cubic the order
 * of what Chebyshev's update would leave, |Q| move (1 + 1/alpha) (the third
 * order over the second is ~ move / alpha), to skip sweep_free_chebyshev
 * where it cannot succeed. Smoothed law: with the iterate's curvatures, Q
 * plus a bound of the third-order term (smoothed_third_order); without
 * them, in the quadratic phase after a Newton step, |H_next| ~ |H|^3 /
 * |H_prev|^2 (|H_k+1| = c |H_k|^2; after Chebyshev's step, whose rate is
 * cubic, that c would be too small: 12x the tolerance was left in
 * SmoothedChebyshev.StagesMeetTheToleranceWithLessWork). */
rtb_real linearised_residual(const Chain &ch, const Iterate &x, const rtb_real *dl,
                             rtb_real prev_hnorm, bool last_newton, rtb_real *Q, bool *have_Q,
                             rtb_real *cubic) {
  *cubic = INFINITY;
  if (!(ch.law.s > 0.0)) {
    *have_Q = true;
    rtb_real move;
    const rtb_real q = rtb_newton_second_order(ch.n, ch.hK0, ch.hKr, ch.law.alpha, x.steep, x.f,
                                               x.v, x.D, dl, Q, &move);
    if (!(move <= 0.1 * ch.law.alpha)) return INFINITY;
    *cubic = q * move * (1.0 + ch.law.inv_alpha);
    return q;
  }
  if (x.curv_ok) {
    rtb_real slope_change;
    return rtb_newton_second_order_curv(ch.n, ch.hK0, ch.hKr, x.steep, x.D, x.C, dl, Q,
                                        &slope_change) +
           smoothed_third_order(ch, x, dl);
  }
  if (!last_newton || !(x.hnorm < 1e-3 * prev_hnorm)) return INFINITY;
  const rtb_real ratio = x.hnorm / prev_hnorm;
  return x.hnorm * ratio * ratio;
}

/* The smoothed Chebyshev step is tried only while no cell's slope changes
 * by more than this to first order along Newton's update (|C du|, du = D
 * dl): beyond it the quadratic model is no better than the linear one. On
 * BM_Extension's smoothed sine (units per step) and the smoothed half of
 * 400 random configurations (unconverged steps of 120 600): no gate 214 /
 * 439, 1.0: 216 / 264, 0.5: 222 / 267, 0.1: 250 / 261 (session 47, before
 * the sweep-free estimate of smoothed_third_order). */
#define RTB_CHEB_SLOPE_CHANGE 1.0

/* Chebyshev's step dc = dl - J^-1 Q, Q = 1/2 H''[dl, dl] (cubic local
 * convergence, one substitution with the kept LU and no law evaluation):
 * the iterate's curvature along dl is known in closed form for eq. (1), and
 * from the last sweep for the smoothed law (x.C; session 47: a smoothed step
 * on BM_Extension's sine took ~6.6 sweeps without it). Used only when the
 * correction is at most half the step (the expansion holds); returns false
 * otherwise. Q: computed here unless have_Q. */
bool chebyshev_step(const Chain &ch, const Iterate &x, const rtb_newton_lu &lu,
                    const rtb_real *dl, bool have_Q, rtb_real *Q, rtb_real *dc) {
  rtb_real move;
  if (ch.law.s > 0.0) {
    rtb_real slope_change;
    if (!x.curv_ok) return false;
    rtb_newton_second_order_curv(ch.n, ch.hK0, ch.hKr, x.steep, x.D, x.C, dl, Q, &slope_change);
    if (!(slope_change <= RTB_CHEB_SLOPE_CHANGE)) return false;
  } else if (!have_Q) {
    rtb_newton_second_order(ch.n, ch.hK0, ch.hKr, ch.law.alpha, x.steep, x.f, x.v, x.D, dl, Q,
                            &move);
  }
  rtb_newton_substitute(&lu, 1.0, Q, dc);
  rtb_real cn = 0.0, dn = 0.0;
  for (int k = 0; k < ch.n; ++k) {
    cn = fabs(dc[k]) > cn ? fabs(dc[k]) : cn;
    dn = fabs(dl[k]) > dn ? fabs(dl[k]) : dn;
  }
  if (!(cn <= 0.5 * dn)) return false;
  for (int k = 0; k < ch.n; ++k) dc[k] = dl[k] - dc[k];
  return true;
}

/* The Chebyshev update dc taken without a law sweep (eq. (1) only): the pair
 * expanded to second order along it (rtb_newton_expanded_pair), and its
 * residual with the third-order terms added -- the residual of the pair the
 * law would give, to leading order. Accepted into *out (the trial buffer)
 * when that is below `bound` and every relative move is below alpha / 10,
 * where the next order is at most a tenth of the third. */
bool sweep_free_chebyshev(const Chain &ch, const Iterate &x, const rtb_real *dc,
                          const rtb_real *r, rtb_real bound, Iterate *out) {
  if (ch.law.s > 0.0) return false;
  rtb_real t3f[RTB_MAX_CELLS], t3v[RTB_MAX_CELLS], E[RTB_MAX_CELLS];
  const rtb_real move = rtb_newton_expanded_pair(ch.n, ch.law.alpha, x.steep, x.f, x.v, x.D, dc,
                                                 out->f, out->v, out->D, t3f, t3v);
  if (!(move <= 0.1 * ch.law.alpha)) return false;
  rtb_real sq;
  if (!(residual(ch, out->f, out->v, r, out->H, &sq) <= RTB_REAL_MAX)) return false;
  rtb_newton_hK_apply(ch.n, ch.hK0, ch.hKr, t3v, E);
  rtb_real e = 0.0, fm = 0.0;
  for (int k = 0; k < ch.n; ++k) {
    const rtb_real a = fabs(out->H[k] + E[k] + t3f[k]);
    e = a > e ? a : e;
    fm = fabs(out->f[k]) > fm ? fabs(out->f[k]) : fm;
  }
  if (!(e <= bound)) return false;
  for (int k = 0; k < ch.n; ++k) out->steep[k] = x.steep[k];
  out->fmax_abs = fm;
  out->hnorm = e; /* the predicted residual, reported in st */
  out->h2 = sq;
  return true;
}

/* A trial that repairs a Newton step which blew up: one Gauss-Seidel pass
 * of exact per-cell row solves (cell_row_solve.cpp), its evaluations taken
 * from *budget (the caller checks it holds RTB_ROW_SOLVE_EVALS sweeps);
 * returns whether the trial's residual is finite. */
bool gauss_seidel_trial(const Chain &ch, const Iterate &x, const rtb_real *r, Iterate *t,
                        int *budget) {
  const int n = ch.n;
  *budget -= ch.unit * rtb_cell_gauss_seidel(&ch.law, n, ch.hK0, ch.hKr, r, x.v, t->f, t->v, t->D);
  t->curv_ok = false;
  t->fmax_abs = mark_cells(ch, 0, n, t->f, t->D, t->steep, 0.0);
  t->hnorm = residual(ch, t->f, t->v, r, t->H, &t->h2);
  return t->hnorm <= RTB_REAL_MAX;
}

/* The law at v = v_guess (rest if NULL or unusable): a start on the curve. */
void evaluated_start(const Chain &ch, const rtb_real *v_guess, const rtb_real *r, Iterate *x,
                     int *budget) {
  for (int attempt = v_guess ? 0 : 1; attempt < 2; ++attempt) {
    for (int k = 0; k < ch.n; ++k) {
      x->v[k] = attempt == 0 ? v_guess[k] : 0.0;
      x->steep[k] = true;
    }
    x->fmax_abs = law_sweep(ch, x->steep, x->f, x->v, x->D, x->C, budget);
    x->curv_ok = ch.law.s > 0.0; /* law_sweep fills C for the smoothed law only */
    x->hnorm = residual(ch, x->f, x->v, r, x->H, &x->h2);
    if (x->hnorm <= RTB_REAL_MAX) return;
  }
}

/* Stuck cells (issue #11). A cell whose dashpot force stays at or below
 * f_lock = C0 v_lock^alpha moves at |v| <= v_lock (eq. (1) is monotone), and
 * v_lock = RTB_LOCK_MARGIN tol |r|_inf / max(h K_kk) is chosen so that its
 * whole contribution to the stage residual, h K v, is a thousandth of the
 * tolerance: the solve would accept it as converged either way. Deep in the
 * chain such cells are the rule (the benchmark's 1 mm sine leaves cells
 * 11-15 at |v| < 1e-25, their exp/log and rows pure cost), so the solve runs
 * on the active cells 0 .. n_act-1 with the rest locked at v = 0: y = c,
 * f = r - h K v (their own rows of H then vanish exactly), D = 0. A locked
 * suffix is exact to decide a priori except for its first cell, whose force
 * also takes h Kr v of its moving neighbour: it is checked after the solve,
 * and unlocked (rtb_stage_solve) if it went past f_lock. Not used with the
 * eq. (14) smoothing, whose law is linear near v = 0 (no stuck regime).
 * Returns n_act; *f_lock the threshold (0: no cell can lock). */
#define RTB_LOCK_MARGIN 1e-3
int active_cells(const Chain &ch, rtb_real tol, rtb_real rnorm, const rtb_real *r,
                 rtb_real *f_lock) {
  *f_lock = 0.0;
  const int n = ch.n;
  if (ch.law.s > 0.0 || !(rnorm > 0.0)) return n;
  const rtb_real kmax = ch.hK0 > 2.0 * ch.hKr ? ch.hK0 : 2.0 * ch.hKr;
  const rtb_real v_lock = RTB_LOCK_MARGIN * tol * rnorm / kmax;
  if (!(v_lock > 0.0 && v_lock <= RTB_REAL_MAX)) return n;
  const rtb_real level = ch.law.C0m < ch.law.C0p ? ch.law.C0m : ch.law.C0p;
  /* A lower bound of v_lock^alpha within a factor 1.3, without exp/log (a
   * smaller threshold only locks fewer cells): with v_lock = m 2^e, m in
   * [0.5, 1), log2 v_lock >= e + 2 m - 2 (the chord of the concave log2),
   * and for x = alpha (e + 2 m - 2), 2^x >= 2^floor(x) (1 + (x - floor(x))
   * ln 2) (the tangent of the convex 2^x). */
  int e;
  const rtb_real m = frexp(v_lock, &e);
  const rtb_real x = ch.law.alpha * ((rtb_real)e + 2.0 * m - 2.0);
  int fx = (int)x;
  fx -= (rtb_real)fx > x;
  const rtb_real fl = ldexp(level, fx) * (1.0 + (x - (rtb_real)fx) * RTB_LN2);
  *f_lock = fl <= RTB_REAL_MAX ? fl : RTB_REAL_MAX;
  int k = n;
  while (k > 0 && fabs(r[k - 1]) <= *f_lock) --k;
  return k;
}

/* The start of the Newton iteration on the active cells (ch.n): the free
 * pair (f0, v0) if given and finite, else the law at v_guess, else rest.
 * The free pair's slopes D0 and (smoothed law) curvatures C0 are taken
 * where given, else computed from the pair. Returns whether the free pair
 * was taken. */
bool start_iterate(const Chain &ch, const rtb_real *f0, const rtb_real *v0, const rtb_real *D0,
                   const rtb_real *C0, const rtb_real *v_guess, const rtb_real *r, Iterate *x,
                   int *budget) {
  const int n = ch.n;
  bool free_start = f0 && v0;
  if (free_start) {
    const bool smoothed = ch.law.s > 0.0;
    x->curv_ok = smoothed && (!D0 || C0);
    for (int k = 0; k < n; ++k) x->f[k] = f0[k], x->v[k] = v0[k];
    if (D0) {
      for (int k = 0; k < n; ++k) x->D[k] = D0[k];
      if (x->curv_ok) for (int k = 0; k < n; ++k) x->C[k] = C0[k];
    } else {
      for (int k = 0; k < n; ++k) {
        int units = 0;
        x->D[k] = rtb_law_dvdf_pair(&ch.law, f0[k], v0[k], ch.unit, &units,
                                    smoothed ? &x->C[k] : nullptr);
        *budget -= units;
      }
    }
    x->fmax_abs = mark_cells(ch, 0, n, x->f, x->D, x->steep, 0.0);
    x->hnorm = residual(ch, x->f, x->v, r, x->H, &x->h2);
    free_start = x->hnorm <= RTB_REAL_MAX;
  }
  if (!free_start) evaluated_start(ch, v_guess, r, x, budget);
  if (!(x->hnorm <= RTB_REAL_MAX)) { /* from rest: f = v = 0 is finite whatever r is */
    for (int k = 0; k < n; ++k) x->f[k] = x->v[k] = x->D[k] = 0.0, x->steep[k] = false;
    x->fmax_abs = 0.0;
    x->hnorm = residual(ch, x->f, x->v, r, x->H, &x->h2);
  }
  return free_start;
}

/* Near-friction dashpots: eq. (1) with alpha at most this. */
#define RTB_FRICTION_ALPHA 0.1

/* The start from the stage's rate-independent limit (friction_limit.h),
 * for near-friction dashpots: the limit's active set at the base levels
 * C0 (1 +- a) (|v| = 1), then one law sweep puts the pair on the curve
 * (sliding cells at their velocity, still ones at their force). Taken into
 * *t when its residual is below the start's x, unless x is already
 * converged (|H| <= done); each solve costs a sweep's units. Returns
 * whether it was taken. */
bool friction_start(const Chain &ch, const rtb_real *r, rtb_real done, const Iterate &x,
                    Iterate *t, int *budget) {
  const int n = ch.n;
  if (ch.law.s > 0.0 || !(ch.law.alpha <= RTB_FRICTION_ALPHA) || x.hnorm <= done) return false;
  const int room = *budget / ch.sweep - 1; /* leave the sweep that follows */
  const int max_solves = room < RTB_STS_MAX_ITERS(n) ? room : RTB_STS_MAX_ITERS(n);
  if (max_solves < 2) return false;
  int act[RTB_MAX_CELLS];
  const int solves = rtb_friction_limit(n, ch.hK0, ch.hKr, r, ch.law.C0p, ch.law.C0m, 0,
                                        max_solves, act, t->v, t->f);
  *budget -= (solves < 0 ? -solves : solves) * ch.sweep;
  if (solves == 0) return false;
  for (int k = 0; k < n; ++k) t->steep[k] = act[k] != 0;
  t->fmax_abs = law_sweep(ch, t->steep, t->f, t->v, t->D, t->C, budget);
  t->curv_ok = false; /* eq. (1) only */
  t->hnorm = residual(ch, t->f, t->v, r, t->H, &t->h2);
  return t->hnorm <= RTB_REAL_MAX && t->h2 < x.h2;
}

/* A trial residual this many times the current one is a blow-up, not a
 * poor step: the Gauss-Seidel repair is tried. Thresholds 1e3 and 1e6 leave
 * 1.73% and 1.40% of BM_RandomConfigs' steps unconverged (without the gain
 * rule below); at 1e3 the repair also replaces halvings that would have
 * done better on well-behaved elements (alpha >= 0.1: 0.12% against 0.04%
 * unconverged). */
#define RTB_BLOWUP 1e6
/* A repair is taken only if it lowers |H|_2^2 below this fraction of the
 * current (|H|_2 by 5%); otherwise the line search halves Newton's step as
 * before. Gauss-Seidel along a long chain propagates a load front one cell
 * per pass, so repeated repairs can creep (|H| down 1-2% per pass), where
 * halving does better: the hard jump of tests/hard_cases.h converges in 39
 * iterations and 2118 units with this rule, had not converged after 100
 * without it, and took 56 and 2937 before the repair. BM_RandomConfigs'
 * unconverged share: 1.53% (1.36% without the rule). */
#define RTB_REPAIR_GAIN 0.9

/* The smoothed inverse's force tolerance in a Newton trial, as a fraction
 * of the stage's (times the iterate's scale): the pair it leaves is off the
 * curve by at most this much, as the sweep-free last update's is. On
 * BM_RandomConfigs' generator (seeds 1-4, 90 000 steps each, default
 * budget) it took the unconverged steps from 3923 to 3349 on top of the
 * inverse's own stopping rule (dashpot_law.h); on BM_Extension's smoothed
 * sine it changes nothing (the warm-started inverse is already exact). */
#define RTB_INVERSE_TOL 0.01

/* Halvings of the first Newton step from the free start before the solve
 * restarts from the law at the extrapolated velocities (session 47). From a
 * pair on the curve Newton's direction descends at once; one that needs more
 * halvings starts from a pair off the curve (the last step ran out of
 * budget: f_n = b - K y_n then is not psi(v_n)), from which halving does not
 * help: such steps spent their whole budget in 30 halvings, and so did every
 * step after them (a near-friction smoothed chain after a 40 mm jump: 191 of
 * 300 steps). BM_RandomConfigs' generator (90 000 steps per seed),
 * unconverged steps, 30 -> 2 halvings (with the smoothed Chebyshev step):
 * default budget 577 -> 335 (seeds 1-4: 3106 -> 1936), 640 units 8021 ->
 * 5181, 512 units 10061 -> 7084; session 46's library: 393, 2756, 8581 and
 * 10377. */
#define RTB_FREE_START_BACKTRACKS 2

/* Newton's iteration on the active cells from *x (bufs: *x and the trial
 * buffer), until converged or out of the stage's iterations (set->max_iter
 * over all its calls) or budget. Adds its iterations and backtracks to st,
 * sets st->converged; returns the convergence scale. lu: the factorization
 * storage; from a free start with lu.n == ch.n on entry, the first step
 * takes it as it is (rtb_stage_solve); on return it holds the last
 * factorization (n = 0 after a failed one). */
rtb_real newton_iterate(const Chain &ch, const rtb_settings *set, const rtb_real *r,
                        rtb_real rnorm, const rtb_real *v_guess, bool free_start,
                        Iterate bufs[2], Iterate **xp, rtb_stage *st, int *budget,
                        rtb_newton_lu &lu) {
  const int n = ch.n;
  rtb_real dl[RTB_MAX_CELLS], dc[RTB_MAX_CELLS], Q[RTB_MAX_CELLS];
  bool have_lu = free_start && lu.n == n;
  Iterate *x = *xp, *trial = x == &bufs[0] ? &bufs[1] : &bufs[0];
  st->converged = 0;
  int it = 0;
  rtb_real scale = rnorm;
  rtb_real prev_hnorm = 0.0; /* |H| before the last full (t = 1) step; 0: none yet */
  bool last_newton = false;  /* ... and that step was Newton's, not Chebyshev's */
  for (;; ++it) {
    scale = x->fmax_abs > rnorm ? x->fmax_abs : rnorm;
    if (x->hnorm <= set->tol * scale || x->hnorm <= RTB_REAL_MIN) { st->converged = 1; break; }
    if (st->iterations + it >= set->max_iter || *budget < ch.sweep) break;
    if (!have_lu && rtb_newton_factor(n, ch.hK0, ch.hKr, x->D, &lu) != 0) {
      lu.n = 0;
      break;
    }
    have_lu = false;
    rtb_newton_substitute(&lu, -1.0, x->H, dl);

    /* Last step without a law sweep: when the linearised update (f + dl,
     * v + D dl) leaves a residual 100x below the tolerance, it is the
     * converged pair to within it, and the sweep that would only confirm it
     * is skipped. D stays at the previous pair: the tangent and the offline
     * adjoint see a slope off by O(|dl|/|f|) ~ tol. Only after a full step
     * of this stage, so every stage's pair has been on the curve once. */
    bool have_Q = false;
    rtb_real cubic = INFINITY;
    const rtb_real left = prev_hnorm > 0.0
                              ? linearised_residual(ch, *x, dl, prev_hnorm, last_newton, Q,
                                                    &have_Q, &cubic)
                              : INFINITY;
    if (left <= 0.01 * set->tol * scale) {
      for (int k = 0; k < n; ++k) {
        x->v[k] += x->D[k] * dl[k];
        x->f[k] += dl[k];
      }
      x->hnorm = left; /* the predicted residual, reported in st */
      st->converged = 1;
      ++it;
      break;
    }
    const bool cheb = chebyshev_step(ch, *x, lu, dl, have_Q, Q, dc);
    if (cheb && cubic <= set->tol * scale &&
        sweep_free_chebyshev(ch, *x, dc, r, 0.01 * set->tol * scale, trial)) {
      Iterate *tmp = x;
      x = trial;
      trial = tmp;
      st->converged = 1;
      ++it;
      break;
    }

    /* Line search on the merit 1/2 |H|_2^2. Both update rules leave the
     * pair on the dashpot curve with df/dt = df at t = 0, so dH/dt = J df = -H
     * and the Newton path is a descent direction: Armijo with slope -|H|^2.
     * (A single merit: alternating between two merits can cycle.) The
     * Chebyshev step, when there is one, is tried first, then Newton's
     * from t = 1; if that blows up, the Gauss-Seidel repair. */
    rtb_real t = 1.0;
    bool accepted = false;
    const int max_bt = it == 0 && free_start && RTB_FREE_START_BACKTRACKS < set->max_backtrack
                           ? RTB_FREE_START_BACKTRACKS
                           : set->max_backtrack;
    for (int bt = cheb ? -1 : 0; bt <= max_bt && *budget >= ch.sweep; ++bt) {
      const rtb_real *d = bt < 0 ? dc : dl;
      t = bt <= 0 ? 1.0 : 0.5 * t;
      for (int k = 0; k < n; ++k) {
        /* steep: v moves, f = psi(v); else f moves, v = phi(f) warm-started
         * at the tangent prediction. */
        trial->v[k] = x->v[k] + t * x->D[k] * d[k];
        trial->f[k] = x->f[k] + t * d[k];
        trial->steep[k] = x->steep[k];
      }
      trial->fmax_abs = law_sweep(ch, trial->steep, trial->f, trial->v, trial->D, trial->C,
                                  budget, RTB_INVERSE_TOL * set->tol * scale);
      trial->curv_ok = ch.law.s > 0.0;
      trial->hnorm = residual(ch, trial->f, trial->v, r, trial->H, &trial->h2);
      const bool descent = trial->hnorm <= RTB_REAL_MAX && !(trial->h2 > (1.0 - 2e-4 * t) * x->h2);
      if (!descent) {
        ++st->backtracks;
        /* Newton's full step blew up (overflow, or a residual a million
         * times the current): repair every row instead of halving. */
        const bool repaired = bt == 0 && !(trial->hnorm <= RTB_BLOWUP * x->hnorm) &&
                              *budget >= RTB_ROW_SOLVE_EVALS * ch.sweep &&
                              gauss_seidel_trial(ch, *x, r, trial, budget) &&
                              trial->h2 < RTB_REPAIR_GAIN * x->h2;
        if (!repaired) continue;
      }
      /* linearised_residual's reference: |H| before a full step only */
      prev_hnorm = descent && t == 1.0 ? x->hnorm : 0.0;
      last_newton = bt >= 0;
      Iterate *tmp = x;
      x = trial;
      trial = tmp;
      accepted = true;
      break;
    }
    if (!accepted && it == 0 && free_start && *budget >= ch.sweep) {
      /* The free pair was too far off the curve for a descent: restart from
       * the law evaluated at v_guess (one more sweep). */
      free_start = false;
      evaluated_start(ch, v_guess, r, x, budget);
      if (!(x->hnorm <= RTB_REAL_MAX)) break;
      --it;
      continue;
    }
    if (!accepted) break;
  }
  st->iterations += it;
  *xp = x;
  return scale;
}

/* Unlock `count` locked cells from index ch->n on, the first of which has
 * the force f past f_lock. Each starts on the curve where it was held: the
 * first at the force f_lock with f's sign (the law there is finite, while
 * at f itself a near-friction dashpot's velocity can overflow), the others
 * at their r. One law evaluation each; the residual over the grown set. */
void unlock_cells(Chain *ch, int count, rtb_real f, rtb_real f_lock, const rtb_real *r,
                  Iterate *x, int *budget) {
  const int first = ch->n;
  ch->n += count;
  ch->sweep = ch->n * ch->unit;
  for (int k = first; k < ch->n; ++k) {
    x->f[k] = k > first ? r[k] : (f < 0.0 ? -f_lock : f_lock);
    x->v[k] = rtb_law_eval_pow_f(&ch->law, x->f[k], &x->D[k]);
  }
  x->fmax_abs = mark_cells(*ch, first, ch->n, x->f, x->D, x->steep, x->fmax_abs);
  *budget -= count * ch->unit;
  x->hnorm = residual(*ch, x->f, x->v, r, x->H, &x->h2);
}

/* Force of locked cell k >= ch.n: v = 0 there, so f = r - h K v takes only
 * the first locked cell's moving neighbour. */
inline rtb_real locked_force(const Chain &ch, const rtb_real *r, const Iterate &x, int k) {
  return r[k] + (k == ch.n && k > 0 ? ch.hKr * x.v[k - 1] : 0.0);
}

}  // namespace

extern "C" rtb_status rtb_stage_solve(const rtb_params *p, const rtb_settings *set,
                                      const rtb_real *f0, const rtb_real *v0, const rtb_real *D0,
                                      const rtb_real *C0, const rtb_real *v_guess, rtb_stage *st,
                                      int *budget, rtb_newton_lu *lu) {
  Chain ch;
  ch.n = p->cells;
  ch.Kpa = p->Kpa;
  ch.Kr = p->Kr;
  ch.h = st->h;
  ch.hKr = st->h * p->Kr;
  ch.hK0 = st->h * (p->Kpa + p->Kr);
  rtb_law_init(&ch.law, p->C0, p->alpha, p->smoothing, p->fric_asym);
  ch.unit = rtb_law_unit(p);
  const int n = ch.n;
  if (n < 1 || n > RTB_MAX_CELLS) return RTB_ERR_STATE;

  /* r = b - K c: the dashpot forces if no cell moved during the stage. */
  rtb_real r[RTB_MAX_CELLS];
  rtb_chain_apply(n, ch.Kpa, ch.Kr, st->c, r);
  rtb_real rnorm = 0.0;
  for (int k = 0; k < n; ++k) {
    r[k] = (k == 0 ? st->b1 : 0.0) - r[k];
    rnorm = fabs(r[k]) > rnorm ? fabs(r[k]) : rnorm;
  }
  rtb_real f_lock;
  ch.n = active_cells(ch, set->tol, rnorm, r, &f_lock);
  ch.sweep = ch.n * ch.unit;

  Iterate bufs[2];
  Iterate *x = &bufs[0];
  st->iterations = 0;
  st->backtracks = 0;
  st->converged = 1;
  x->hnorm = 0.0;
  rtb_real scale = rnorm;
  x->curv_ok = false;
  bool free_start = ch.n > 0 && start_iterate(ch, f0, v0, D0, C0, v_guess, r, x, budget);
  const rtb_real done = set->tol * (x->fmax_abs > rnorm ? x->fmax_abs : rnorm);
  if (ch.n > 0 && friction_start(ch, r, done, *x, &bufs[1], budget)) {
    x = &bufs[1];
    free_start = false;
  }
  /* A locked cell pushed past f_lock is unlocked with the next ones, 1, 2,
   * 4, ... at a time, so a load front running deep into the chain costs
   * log2(N) re-solves rather than N. */
  for (int unlock = 1; ch.n > 0; unlock *= 2) {
    scale = newton_iterate(ch, set, r, rnorm, v_guess, free_start && unlock == 1, bufs, &x, st,
                           budget, *lu);
    if (ch.n == n || !st->converged) break;
    const rtb_real f_next = locked_force(ch, r, *x, ch.n);
    if (fabs(f_next) <= f_lock) break;
    const int count = unlock < n - ch.n ? unlock : n - ch.n;
    if (*budget < ch.sweep + count * ch.unit) { st->converged = 0; break; }
    unlock_cells(&ch, count, f_next, f_lock, r, x, budget);
  }
  st->residual = x->hnorm <= RTB_REAL_MIN ? 0.0 : x->hnorm / scale; /* scale > 0 when H != 0 */
  for (int k = 0; k < n; ++k) {
    const bool active = k < ch.n;
    st->f[k] = active ? x->f[k] : locked_force(ch, r, *x, k);
    st->v[k] = active ? x->v[k] : 0.0;
    st->D[k] = active ? x->D[k] : 0.0;
    if (x->curv_ok) st->C[k] = x->C[k]; /* smoothed law: no cell is locked */
    st->y[k] = st->c[k] + ch.h * st->v[k];
    if (!isfinite(st->y[k])) return RTB_ERR_OVERFLOW;
  }
  st->have_C = x->curv_ok;
  return st->converged ? RTB_OK : RTB_NOT_CONVERGED;
}
