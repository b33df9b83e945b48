/* dashpot_law.h -- the RT cell's nonlinear dashpot, eq. (1), and its inverse.
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

#include <math.h>

/* psi(v), eq. (1). */
static inline double rtb_law_force(double v, double C0, double alpha) {
  if (v == 0.0) return 0.0;
  double m = C0 * exp(alpha * log(fabs(v)));
  return v > 0.0 ? m : -m;
}

/* phi(f), inverse of eq. (1). May overflow to +-inf far in the steep regime;
 * callers treat a non-finite value as a rejected trial point. */
static inline double rtb_law_velocity(double f, double C0, double alpha) {
  if (f == 0.0) return 0.0;
  double m = exp(log(fabs(f) / C0) / alpha);
  return f > 0.0 ? m : -m;
}

/* phi'(f) = (1/alpha) v/f, given v = phi(f); 0 at f = 0. */
static inline double rtb_law_dvdf(double f, double v, double alpha) {
  return (f == 0.0 || v == 0.0) ? 0.0 : v / (alpha * f);
}

/* d phi / d C0 at fixed f = -(1/alpha) v / C0. */
static inline double rtb_law_dv_dC0(double v, double C0, double alpha) {
  return -v / (alpha * C0);
}

/* d phi / d alpha at fixed f = -v ln(|f|/C0) / alpha^2 (0 at f = 0). */
static inline double rtb_law_dv_dalpha(double f, double v, double C0, double alpha) {
  /* v == 0 also covers f so small that |f|/C0 underflows (log would be -inf). */
  return v == 0.0 ? 0.0 : -v * log(fabs(f) / C0) / (alpha * alpha);
}

/* Dissipation potential of phi: Phi*(f) = int_0^f phi = alpha/(1+alpha) f v. */
static inline double rtb_law_dual_potential(double f, double v, double alpha) {
  return alpha / (1.0 + alpha) * f * v;
}

#endif
