/* dashpot_law.h -- the RT cell's nonlinear dashpot, eq. (1), and its inverse;
 * optionally smoothed as in eq. (14).
 *
 * eq. (1):   f = psi(v) = C0 sign(v) |v|^alpha
 * inverse:   v = phi(f) = sign(f) (|f|/C0)^(1/alpha)
 *
 * The stepper works with phi, not psi: psi'(0) is infinite (the singularity
 * that forced the paper's sigmoid smoothing, eq. (14)), while phi is C1 with
 * phi'(0) = 0 for alpha < 1. Every implicit stage is therefore a smooth
 * equation in the dashpot forces and its exact derivative exists everywhere.
 */
#ifndef RTB_DASHPOT_LAW_H
#define RTB_DASHPOT_LAW_H

#include <float.h>
#include <math.h>

#include "rtb_scalar.h"

/* Dashpot level with the friction asymmetry a = rtb_params.fric_asym:
 * C0 (1 + a) where the cell moves (and pushes) positively, C0 (1 - a)
 * negatively. `sign_of` is the cell velocity or force (same sign); at 0 the
 * law gives 0 whatever the level. d level / d a = +-C0. */
static inline rtb_real rtb_dashpot_level(rtb_real C0, rtb_real a, rtb_real sign_of) {
  return sign_of < 0.0 ? C0 * (1.0 - a) : C0 * (1.0 + a);
}

/* psi(v), eq. (1). */
static inline rtb_real rtb_law_force(rtb_real v, rtb_real C0, rtb_real alpha) {
  if (v == 0.0) return 0.0;
  rtb_real m = C0 * exp(alpha * log(fabs(v)));
  return v > 0.0 ? m : -m;
}

/* phi(f), inverse of eq. (1). May overflow to +-inf far in the steep regime;
 * callers treat a non-finite value as a rejected trial point. */
static inline rtb_real rtb_law_velocity(rtb_real f, rtb_real C0, rtb_real alpha) {
  if (f == 0.0) return 0.0;
  rtb_real m = exp(log(fabs(f) / C0) / alpha);
  return f > 0.0 ? m : -m;
}

/* phi'(f) = (1/alpha) v/f, given v = phi(f); 0 at f = 0. */
static inline rtb_real rtb_law_dvdf(rtb_real f, rtb_real v, rtb_real alpha) {
  return (f == 0.0 || v == 0.0) ? 0.0 : v / (alpha * f);
}

/* d phi / d C0 at fixed f = -(1/alpha) v / C0. */
static inline rtb_real rtb_law_dv_dC0(rtb_real v, rtb_real C0, rtb_real alpha) {
  return -v / (alpha * C0);
}

/* d phi / d alpha at fixed f = -v ln(|f|/C0) / alpha^2 (0 at f = 0). */
static inline rtb_real rtb_law_dv_dalpha(rtb_real f, rtb_real v, rtb_real C0, rtb_real alpha) {
  /* 0 where |f|/C0 is 0 (log would be -inf): at f = 0, where it underflows,
   * and at a pair the Newton tolerance left with f = 0 but v != 0 (C0 ->
   * 0: dashpot forces at rounding level, v following the input; blindgen
   * backlash_held_s31 gave every later sensitivity NaN from there). */
  const rtb_real q = fabs(f) / C0;
  return (v == 0.0 || !(q > 0.0)) ? 0.0 : -v * log(q) / (alpha * alpha);
}

/* Dissipation potential of phi: Phi*(f) = int_0^f phi = alpha/(1+alpha) f v. */
static inline rtb_real rtb_law_dual_potential(rtb_real f, rtb_real v, rtb_real alpha) {
  return alpha / (1.0 + alpha) * f * v;
}

/* ------------------------------------------------------------------------
 * Optional smoothing, eq. (14) (rtb_params.smoothing = s > 0, [1/velocity]):
 *   sign_s(v) = 2/(1 + exp(-s v)) - 1,   |v|_s = (2/s) ln(1 + exp(s v)) - v,
 *   f = psi_s(v) = C0 sign_s(v) |v|_s^alpha.
 * Written without overflow: with e = exp(-s|v|) in [0, 1],
 *   sign_s(v) = sign(v) tanh(s|v|/2) = sign(v) (1 - e)/(1 + e),
 *   |v|_s = |v| + (2/s) log1p(e)   (no exp(s v) is ever formed).
 * psi_s is odd, C-infinity and strictly increasing, with the finite slope
 * C0 (s/2)^(1-alpha) (ln 2)^alpha at v = 0; d|v|_s/dv = sign_s(v). As s -> inf
 * psi_s -> psi uniformly (error O(C0 s^-alpha), near |v| ~ 1/s) and
 * exponentially fast at any fixed v != 0.
 */

/* Beyond s|v| = RTB_SLAW_SHARP, tanh(s|v|/2) rounds to 1 and |v|_s/|v| - 1 <
 * 2 exp(-s|v|)/(s|v|) ~ 1e-19: psi_s equals psi to rounding, so eq. (1) is
 * evaluated directly (cheaper; the slope keeps its exact sign_s' term). */
#define RTB_SLAW_SHARP 40.0

/* exp(x) rounds to +0 below ln(smallest subnormal / 2): -745.13 (double),
 * -103.98 (float). */
#ifdef RTB_SINGLE
#define RTB_EXP_ZERO_BELOW -104.0f
#else
#define RTB_EXP_ZERO_BELOW -745.2
#endif

/* ln |v|_s, eq. (14), by the same operations as rtb_slaw_force. With
 * e = exp(-s|v|) in (exp(-40), 1] there: |v|_s = |v| + (2/s) log1p(e), and
 * only for s < ~1e-307 (2/s overflows) ln(s|v| + 2 log1p(e)) - ln s. */
static inline rtb_real rtb_slaw_log_abs(rtb_real v, rtb_real s) {
  const rtb_real a = fabs(v), sa = s * a;
  if (sa >= RTB_SLAW_SHARP) return log(a);
  const rtb_real L = log1p(1.0 + expm1(-sa));
  const rtb_real A = a + 2.0 * L / s;
  return A <= RTB_REAL_MAX ? log(A) : log(sa + 2.0 * L) - log(s);
}

/* Below s|v| = RTB_SLAW_SERIES the stage solver evaluates eq. (14) by its
 * Taylor series in x = s|v| (rtb_slaw_eval), without a transcendental:
 * with |v|_s = (2/s) ln(2 cosh(x/2)) and sign_s = tanh(x/2),
 *   tanh(x/2)          = x/2 - x^3/24 + x^5/240 - 17 x^7/40320 + O(x^9),
 *   ln(2 cosh(x/2))    = ln 2 + G,  G = x^2/8 - x^4/192 + x^6/2880 + O(x^8),
 *   |v|_s^alpha        = P0 (1 + G/ln 2)^alpha,  P0 = (2 ln 2 / s)^alpha,
 * (1 + w)^alpha = exp(alpha log1p(w)) by three terms of each series
 * (w <= 1.8e-5 there); every dropped term is below 1e-19 of what it
 * corrects. The chain's slow cells sit there (a quarter of the smoothed
 * evaluations on BM_Extension's sine: session 47). */
#ifdef RTB_SINGLE
#define RTB_SLAW_SERIES 1e-2f
#else
#define RTB_SLAW_SERIES 1e-2
#endif
#define RTB_LN2 0.69314718055994530942

/* P0 = (2 ln 2 / s)^alpha of the series, or 0 (no series) where 2/s
 * overflows. */
static inline rtb_real rtb_slaw_series_scale(rtb_real alpha, rtb_real s) {
  if (!(s > 4.0 / RTB_REAL_MAX)) return 0.0;
  const rtb_real P0 = exp(alpha * log(2.0 * RTB_LN2 / s));
  return P0 <= RTB_REAL_MAX ? P0 : 0.0;
}

/* psi_s(v), *D = 1/psi_s'(v) (+inf where psi_s' underflows) and, if curv,
 * psi_s''/psi_s' signed as at v (the inverse's stopping rule and the stage
 * solver's Chebyshev step; no further transcendental). P0: the series'
 * scale (rtb_slaw_series_scale), or 0 for no series.
 * psi_s'(v) = C0 |v|_s^alpha (sign_s' + alpha sign_s^2 / |v|_s), sign_s' =
 * 2 s e / (1 + e)^2: both terms are >= 0, so the slope is never negative;
 * it is > 0 wherever psi_s is finite. With S = sign_s, A = |v|_s (A' = S),
 * S' = (s/2)(1 - S^2), S'' = -s S S' and P = A^alpha (P' = alpha P S / A):
 *   psi_s'' / (C0 P) = (alpha S / A)(S' + alpha S^2/A) + S''
 *                      + alpha (2 S S' / A - S^3 / A^2);
 * in the sharp regime (alpha - 1)/v, the terms in e dropped. The stage
 * solver needs D, not psi_s': four divisions in the transition regime
 * instead of seven, two in the sharp one (session 47). */
static inline rtb_real rtb_slaw_eval(rtb_real v, rtb_real C0, rtb_real alpha, rtb_real s,
                                     rtb_real P0, rtb_real *D, rtb_real *curv) {
  const rtb_real a = fabs(v), sa = s * a;
  if (sa >= RTB_SLAW_SHARP) {
    /* exp(-sa) is +0 past RTB_EXP_ZERO_BELOW: returned directly, without
     * libm's underflow path (1% of a smoothed step, issue #11) */
    const rtb_real m = rtb_law_force(a, C0, alpha), e = -sa < RTB_EXP_ZERO_BELOW ? 0.0 : exp(-sa);
    /* psi_s' = C0 |v|^alpha (sign_s' + alpha/|v|); e == 0 or |v| = inf: no 0 * inf */
    const rtb_real t = e > 0.0 ? 2.0 * sa * e / ((1.0 + e) * (1.0 + e)) : 0.0;
    *D = a <= RTB_REAL_MAX ? a / (m * (t + alpha)) : INFINITY;
    if (curv) *curv = (alpha - 1.0) / v;
    return v < 0.0 ? -m : m;
  }
  rtb_real S, A, P, dS, lnA = 0.0;
  if (sa < RTB_SLAW_SERIES && P0 > 0.0) { /* the series above: no transcendental */
    const rtb_real x2 = sa * sa;
    S = 0.5 * sa * (1.0 - x2 / 12.0 * (1.0 - x2 / 10.0 * (1.0 - x2 * (17.0 / 168.0))));
    const rtb_real w = x2 / 8.0 * (1.0 - x2 / 24.0 * (1.0 - x2 / 15.0)) / RTB_LN2;
    const rtb_real z = alpha * (w * (1.0 - w * (0.5 - w / 3.0)));
    A = 2.0 * RTB_LN2 * (1.0 + w) / s;
    P = P0 * (1.0 + z * (1.0 + z * (0.5 + z / 6.0)));
    dS = 0.5 * s * (1.0 - S * S);
  } else {
    const rtb_real em = expm1(-sa), e = 1.0 + em; /* e in (exp(-40), 1]: no underflow */
    const rtb_real iE = 1.0 / (2.0 + em);         /* 1 / (1 + e) */
    S = -em * iE;                                 /* |sign_s(v)| = tanh(s|v|/2) */
    const rtb_real L = log1p(e);
    A = a + 2.0 * L / s;                          /* |v|_s; inf only for s < ~1e-307 */
    lnA = A <= RTB_REAL_MAX ? log(A) : log(sa + 2.0 * L) - log(s);
    P = exp(alpha * lnA);                         /* |v|_s^alpha */
    dS = 2.0 * s * e * iE * iE;
  }
  const bool finite_A = A <= RTB_REAL_MAX;
  const rtb_real iA = finite_A ? 1.0 / A : 0.0;
  const rtb_real PA = finite_A ? P * iA : exp((alpha - 1.0) * lnA); /* |v|_s^(alpha-1) */
  const rtb_real CP = C0 * P;
  *D = 1.0 / (C0 * (dS * P + alpha * S * S * PA));
  if (curv) {
    const rtb_real g = dS + alpha * S * S * iA; /* psi_s' / (C0 P) */
    const rtb_real c = (alpha * S * iA * g - s * S * dS + alpha * S * iA * (2.0 * dS - S * S * iA));
    *curv = (v < 0.0 ? -c : c) * CP * *D;        /* / g, as C0 P D = 1/g */
  }
  const rtb_real m = CP * S;
  return v < 0.0 ? -m : m;
}

/* psi_s(v) and (if dfdv) psi_s'(v), from rtb_slaw_eval (no series);
 * curv (needs dfdv) as there, for |v|. */
static inline rtb_real rtb_slaw_force_c(rtb_real v, rtb_real C0, rtb_real alpha, rtb_real s,
                                        rtb_real *dfdv, rtb_real *curv) {
  rtb_real D;
  const rtb_real f = rtb_slaw_eval(v, C0, alpha, s, 0.0, &D, dfdv ? curv : 0);
  if (dfdv) *dfdv = 1.0 / D;
  if (dfdv && curv && v < 0.0) *curv = -*curv;
  return f;
}

static inline rtb_real rtb_slaw_force(rtb_real v, rtb_real C0, rtb_real alpha, rtb_real s,
                                      rtb_real *dfdv) {
  return rtb_slaw_force_c(v, C0, alpha, s, dfdv, 0);
}

/* v = phi_s(f), the inverse of psi_s, by a safeguarded scalar Newton
 * iteration with bisection fallback on a bracket that is proven a priori:
 *   psi_s(v) <= C0 (|v| + 2 ln2/s)^alpha    -> lo = max(0, vu - 2 ln2/s),
 *   psi_s(v) >= C0 tanh(s|v|/2) |v|^alpha   -> hi = 4 (vu + 2/s),
 * with vu = phi(|f|) the unsmoothed inverse (at hi, tanh >= tanh(4) and
 * 4^alpha tanh(4) >= 1 for alpha >= RTB_ALPHA_MIN). Start: `guess` (the
 * stage solver's tangent prediction, accurate to second order near its
 * solution) when it has f's sign and lies in the bracket, else vu, which is
 * the inverse to rounding when s vu >= RTB_SLAW_SHARP.
 * Why invert at all, instead of making v the only unknown of smoothed cells:
 * for large s, psi_s is as steep near v = 0 as eq. (1), and a Newton in v
 * there needs many damped steps; keeping the stage solver's per-DOF variable
 * switch (stage_newton.cpp) keeps both regimes fast, and the inverse is only
 * needed on the force-updated (shallow-dashpot) DOFs, where it takes 1.5
 * psi_s evaluations on average. Bounded: at most RTB_SLAW_INV_ITERS
 * evaluations. Returns +-inf (a rejected trial point) only if vu overflows. */
#define RTB_SLAW_INV_ITERS 80
#ifdef RTB_SINGLE
#define RTB_SLAW_QUAD_STEP 3e-4f
#else
#define RTB_SLAW_QUAD_STEP 5e-7
#endif
/* The inverse with an explicit evaluation cap: at most max_evals (>= 1)
 * psi_s evaluations, and a force tolerance ftol >= 0: it stops once
 * |psi_s(v) - |f|| <= ftol at an evaluated v (the stage solver passes a
 * hundredth of its own tolerance: an inverse exact to rounding is wasted on
 * a Newton iterate that is not; 0: to rounding); *evals receives the
 * number used (>= 1 whenever f != 0, so a caller's work count stays
 * honest) and *dvdf (may be NULL) 1/psi_s'
 * at the last evaluated point (capped at RTB_REAL_MAX), which differs from the
 * returned v by at most the final Newton correction (rounding level when
 * converged). When the cap ends the iteration the best bracketed iterate is
 * returned. rtb_slaw_velocity_p also takes the series' scale P0 (0: none)
 * and gives *curv (may be NULL), psi_s''/psi_s' at the last evaluated point,
 * signed as at the returned v (the stage solver's Chebyshev step). */
static inline rtb_real rtb_slaw_velocity_p(rtb_real f, rtb_real C0, rtb_real alpha, rtb_real s,
                                         rtb_real P0, rtb_real guess, int max_evals, rtb_real ftol,
                                         int *evals, rtb_real *dvdf, rtb_real *curv) {
  *evals = 1;
  if (dvdf) *dvdf = 0.0;
  if (curv) *curv = 0.0; /* psi_s is odd: psi_s''(0) = 0 */
  if (f == 0.0) return 0.0;
  const rtb_real m = fabs(f);
  const rtb_real vu = rtb_law_velocity(m, C0, alpha);
  if (!(vu <= RTB_REAL_MAX)) return f > 0.0 ? INFINITY : -INFINITY;
  if (s * vu >= RTB_SLAW_SHARP) { /* psi_s(vu) == f to rounding */
    if (dvdf) *dvdf = rtb_law_dvdf(m, vu, alpha);
    if (curv) *curv = f > 0.0 ? (alpha - 1.0) / vu : (1.0 - alpha) / vu; /* eq. (1)'s */
    return f > 0.0 ? vu : -vu;
  }
  rtb_real lo = vu - 2.0 * RTB_LN2 / s;
  if (!(lo > 0.0)) lo = 0.0;
  rtb_real hi = 4.0 * (vu + 2.0 / s);
  if (!(hi <= RTB_REAL_MAX)) hi = RTB_REAL_MAX;
  const rtb_real g = f > 0.0 ? guess : -guess;
  rtb_real v = (g > lo && g < hi) ? g : (vu < lo ? lo : (vu > hi ? hi : vu));
  int it = 0;
  while (it < max_evals) {
    rtb_real D, c;
    const rtb_real r = rtb_slaw_eval(v, C0, alpha, s, P0, &D, &c) - m;
    ++it;
    if (dvdf) *dvdf = D <= RTB_REAL_MAX ? D : RTB_REAL_MAX;
    if (curv) *curv = f > 0.0 ? c : -c;
    if (r == 0.0) break;
    if (r > 0.0) hi = v; else lo = v;
    rtb_real vn = v - r * D;
    /* Converged: the step or the force residual is at rounding level (the
     * inverse amplifies rounding by up to 1/alpha, so a step test alone
     * could idle until the bracket collapses), or what this Newton step
     * leaves, (psi_s'' / 2 psi_s') step^2, is (issue #11: the evaluation
     * that would only confirm it is skipped; the slope is moved to vn to
     * first order). That estimate holds for a small relative step only:
     * the third-order term, ~ (s v)^2 (step/v)^3 / 6 of v near s v = 40
     * and ~ (step/v)^3 in the power-law regime, is then below rounding
     * too (RTB_SLAW_QUAD_STEP); from a far start in the linear regime,
     * where psi_s'' vanishes at v = 0, it would stop at once. */
    const rtb_real dv = vn - v;
    if (fabs(dv) <= 2.0 * RTB_REAL_EPSILON * v || fabs(r) <= 4.0 * RTB_REAL_EPSILON * m ||
        fabs(r) <= ftol ||
        (fabs(dv) <= RTB_SLAW_QUAD_STEP * vn &&
         0.5 * fabs(c) * dv * dv <= 2.0 * RTB_REAL_EPSILON * vn)) {
      if (vn >= lo && vn <= hi) {
        v = vn;
        const rtb_real moved = 1.0 + c * dv; /* psi_s'(vn) / psi_s'(v) to first order */
        if (dvdf && moved > 0.5 && moved < 2.0) {
          const rtb_real Dm = D / moved;
          *dvdf = Dm <= RTB_REAL_MAX ? Dm : RTB_REAL_MAX;
        }
      }
      break;
    }
    /* Outside the bracket (or NaN): bisect, geometrically when the bracket
     * spans orders of magnitude (the root may lie far below hi). */
    if (!(vn > lo && vn < hi))
      vn = (lo > 0.0 && hi > 4.0 * lo) ? sqrt(lo) * sqrt(hi) : lo + 0.5 * (hi - lo);
    v = vn;
    if (hi - lo <= 2.0 * RTB_REAL_EPSILON * hi) break;
  }
  *evals = it > 0 ? it : 1;
  return f > 0.0 ? v : -v;
}

static inline rtb_real rtb_slaw_velocity_n(rtb_real f, rtb_real C0, rtb_real alpha, rtb_real s,
                                         rtb_real guess, int max_evals, rtb_real ftol,
                                         int *evals, rtb_real *dvdf) {
  return rtb_slaw_velocity_p(f, C0, alpha, s, 0.0, guess, max_evals, ftol, evals, dvdf, 0);
}

static inline rtb_real rtb_slaw_velocity(rtb_real f, rtb_real C0, rtb_real alpha, rtb_real s,
                                       rtb_real guess) {
  int evals;
  return rtb_slaw_velocity_n(f, C0, alpha, s, guess, RTB_SLAW_INV_ITERS, 0.0, &evals, 0);
}

/* ------------------------------------------------------------------------
 * The law the stepper uses: eq. (1) when s == 0 (these calls are exactly the
 * unsmoothed functions above, so results are bit-identical to a build
 * without smoothing), eq. (14) when s > 0. Derivatives are those of v at
 * fixed f, as the stage equations need them (rtb_internal.h).
 */
static inline rtb_real rtb_dashpot_force(rtb_real v, rtb_real C0, rtb_real alpha, rtb_real s) {
  return s > 0.0 ? rtb_slaw_force(v, C0, alpha, s, 0) : rtb_law_force(v, C0, alpha);
}

/* `guess` only warm-starts the smoothed inverse (any value is safe). */
static inline rtb_real rtb_dashpot_velocity(rtb_real f, rtb_real C0, rtb_real alpha, rtb_real s,
                                          rtb_real guess) {
  return s > 0.0 ? rtb_slaw_velocity(f, C0, alpha, s, guess) : rtb_law_velocity(f, C0, alpha);
}

/* dv/df = 1/psi_s'(v) (finite and > 0 for s > 0; capped at RTB_REAL_MAX). */
static inline rtb_real rtb_dashpot_dvdf(rtb_real f, rtb_real v, rtb_real C0, rtb_real alpha, rtb_real s) {
  if (!(s > 0.0)) return rtb_law_dvdf(f, v, alpha);
  rtb_real d;
  rtb_slaw_force(v, C0, alpha, s, &d);
  const rtb_real D = 1.0 / d;
  return D <= RTB_REAL_MAX ? D : RTB_REAL_MAX;
}

/* dv/dC0 at fixed f: psi_s is linear in C0, so dv/dC0 = -(f/C0) dv/df. */
static inline rtb_real rtb_dashpot_dv_dC0(rtb_real f, rtb_real v, rtb_real C0, rtb_real alpha, rtb_real s) {
  if (!(s > 0.0)) return rtb_law_dv_dC0(v, C0, alpha);
  return -(f / C0) * rtb_dashpot_dvdf(f, v, C0, alpha, s);
}

/* dv/dalpha at fixed f: d psi_s/d alpha = f ln|v|_s, so dv/dalpha =
 * -f ln|v|_s dv/df. */
static inline rtb_real rtb_dashpot_dv_dalpha(rtb_real f, rtb_real v, rtb_real C0, rtb_real alpha, rtb_real s) {
  if (!(s > 0.0)) return rtb_law_dv_dalpha(f, v, C0, alpha);
  return -f * rtb_slaw_log_abs(v, s) * rtb_dashpot_dvdf(f, v, C0, alpha, s);
}

/* ------------------------------------------------------------------------
 * The stage solver's law evaluations (issue #11): constants hoisted once per
 * stage, one log and one exp per unsmoothed evaluation, and the pair's
 * slope D = dv/df = phi'(f) returned with it (one division), so the Newton
 * matrix needs no further law call. Results equal the functions above to
 * rounding (phi uses the reciprocal of C0 instead of a division by it).
 */

typedef struct rtb_law {
  rtb_real C0, alpha, s;    /* s: eq. (14) smoothing, 0 = exact eq. (1) */
  rtb_real asym;            /* fric_asym: level C0 (1 +- asym) by the sign */
  rtb_real C0p, C0m;        /* the two levels, C0 (1 + asym) and C0 (1 - asym) */
  rtb_real inv_C0p, inv_C0m, inv_alpha;
  rtb_real P0;              /* the smoothed law's series scale (rtb_slaw_series_scale) */
} rtb_law;

static inline void rtb_law_init(rtb_law *L, rtb_real C0, rtb_real alpha, rtb_real s,
                                rtb_real asym) {
  L->C0 = C0;
  L->alpha = alpha;
  L->s = s;
  L->asym = asym;
  L->C0p = rtb_dashpot_level(C0, asym, 1.0);
  L->C0m = rtb_dashpot_level(C0, asym, -1.0);
  L->inv_C0p = 1.0 / L->C0p;
  L->inv_C0m = 1.0 / L->C0m;
  L->inv_alpha = 1.0 / alpha;
  L->P0 = s > 0.0 ? rtb_slaw_series_scale(alpha, s) : 0.0;
}

/* f = psi(v) and *D = phi'(f) at the pair (0 at v = 0). One psi evaluation.
 * Smoothed law: *curv (may be NULL) psi_s''/psi_s' at v. */
static inline rtb_real rtb_law_eval_v_c(const rtb_law *L, rtb_real v, rtb_real *D,
                                        rtb_real *curv) {
  if (L->s > 0.0) {
    rtb_real Dv;
    const rtb_real f = rtb_slaw_eval(v, v < 0.0 ? L->C0m : L->C0p, L->alpha, L->s, L->P0, &Dv, curv);
    *D = Dv <= RTB_REAL_MAX ? Dv : RTB_REAL_MAX;
    return f;
  }
  const rtb_real a = fabs(v);
  if (a == 0.0) { *D = 0.0; return 0.0; }
  const rtb_real m = (v < 0.0 ? L->C0m : L->C0p) * exp(L->alpha * log(a));  /* eq. (1) */
  *D = m > 0.0 ? a / (L->alpha * m) : 0.0;          /* phi' = v / (alpha f) */
  return v > 0.0 ? m : -m;
}

static inline rtb_real rtb_law_eval_v(const rtb_law *L, rtb_real v, rtb_real *D) {
  return rtb_law_eval_v_c(L, v, D, 0);
}

/* v = phi(f) of eq. (1) (no smoothing) and *D = phi'(f). */
static inline rtb_real rtb_law_eval_pow_f(const rtb_law *L, rtb_real f, rtb_real *D) {
  const rtb_real a = fabs(f);
  if (a == 0.0) { *D = 0.0; return 0.0; }
  /* inverse of eq. (1). A cell far below its dashpot's level (|f| / C0 <
   * ~1e-62 for alpha = 0.2) has v = 0 to the last subnormal; libm's exp
   * reaches that 0 through its slow underflow path (errno, 3% of a step on
   * the benchmark input), so it is returned directly, the same bits. */
  const rtb_real e = log(a * (f < 0.0 ? L->inv_C0m : L->inv_C0p)) * L->inv_alpha;
  const rtb_real m = e < RTB_EXP_ZERO_BELOW ? 0.0 : exp(e);
  *D = m > 0.0 ? m / (L->alpha * a) : 0.0;
  return f > 0.0 ? m : -m;
}

/* v = phi(f) and *D = phi'(f). `guess` warm-starts the smoothed inverse,
 * ftol its force tolerance (rtb_slaw_velocity_n); *cap: in, the most psi_s
 * evaluations it may use (>= 1); out, the count used (1 for eq. (1)).
 * Smoothed law: *curv (may be NULL) psi_s''/psi_s' at the pair. */
static inline rtb_real rtb_law_eval_f(const rtb_law *L, rtb_real f, rtb_real guess,
                                      rtb_real ftol, rtb_real *D, int *cap, rtb_real *curv) {
  if (L->s > 0.0) {
    const int max_evals = *cap < 1 ? 1 : (*cap < RTB_SLAW_INV_ITERS ? *cap : RTB_SLAW_INV_ITERS);
    return rtb_slaw_velocity_p(f, f < 0.0 ? L->C0m : L->C0p, L->alpha, L->s, L->P0, guess,
                               max_evals, ftol, cap, D, curv);
  }
  *cap = 1;
  return rtb_law_eval_pow_f(L, f, D);
}

/* phi'(f) of a pair (f, v) already on the curve; *units: what this cost in
 * eq. (1) evaluations (see rtb_law_unit): 0 for eq. (1), which needs only a
 * division; for the smoothed law 1 in its sharp regime (s |v| >=
 * RTB_SLAW_SHARP), where psi_s is eq. (1) to rounding and its slope's
 * exp(-s|v|) term below 4e-13 of it (alpha >= RTB_ALPHA_MIN): eq. (1)'s
 * slope at v, |v| / (alpha psi(v)), one log and one exp; else a smoothed
 * evaluation (`full` units). From v alone: a pair off the curve (an
 * unconverged last step) still gets the slope of its velocity. */
static inline rtb_real rtb_law_dvdf_pair(const rtb_law *L, rtb_real f, rtb_real v, int full,
                                         int *units, rtb_real *curv) {
  if (!(L->s > 0.0)) { *units = 0; return rtb_law_dvdf(f, v, L->alpha); }
  const rtb_real a = fabs(v);
  if (L->s * a >= RTB_SLAW_SHARP && a <= RTB_REAL_MAX) {
    *units = 1;
    if (curv) *curv = (L->alpha - 1.0) / v; /* eq. (1)'s psi''/psi', signed */
    const rtb_real m = (v < 0.0 ? L->C0m : L->C0p) * exp(L->alpha * log(a)); /* eq. (1) */
    return m > 0.0 ? a / (L->alpha * m) : RTB_REAL_MAX;
  }
  *units = full;
  if (!curv) return rtb_dashpot_dvdf(f, v, v < 0.0 ? L->C0m : L->C0p, L->alpha, L->s);
  rtb_real D;
  rtb_law_eval_v_c(L, v, &D, curv);
  return D;
}

#endif
