/* bushing_force.h -- the bushing's force law and its memories, with every
 * partial derivative: the ONE definition the real-time stepper (step.cpp)
 * evaluates and the offline adjoint (offline/adjoint/step_linearization.cpp)
 * differentiates, so the two cannot drift apart.
 *
 *   F = K0 eta(xb) xb + Kpa (xb - y1)                      eq. (11), Mullins eta
 *     + k3 xb^3 + k_asym |xb| + sat_force tanh(xb/sat_disp)  elastic extensions
 *     + maxwell_k (xb - z) + sum_j k_j (xb - z_j)            Maxwell branch, spectrum
 *     + viscous_c (xb - xb_old)/dt                           linear dashpot
 * (the inertia term m a acts on the input x and is added by the step).
 */
#ifndef RTB_BUSHING_FORCE_H
#define RTB_BUSHING_FORCE_H

#include <math.h>

#include "../rt_bushing.h"

/* ------------------------------------------------------------------ */
/* One Maxwell branch tau z' = xb - z, integrated exactly for xb linear   */
/* over the step (no time-step error in the branch itself).              */
/* ------------------------------------------------------------------ */
typedef struct rtb_maxwell_lin {
  double z;         /* z at the end of the step */
  double d_z_old;   /* = E = exp(-dt/tau) */
  double d_xb_new, d_xb_old, d_tau;
} rtb_maxwell_lin;

/*   z_new = xb_new - s tau + E (z_old - xb_old + s tau),  s = (xb_new - xb_old)/dt. */
static inline void rtb_maxwell_step(double tau, double dt, double xb_old, double xb_new,
                                    double z_old, rtb_maxwell_lin *m) {
  const double one_minus_e = -expm1(-dt / tau); /* accurate for dt << tau */
  const double E = 1.0 - one_minus_e;
  const double s = (xb_new - xb_old) / dt;
  const double q = z_old - xb_old + s * tau;
  m->z = xb_new - s * tau + E * q;
  m->d_z_old = E;
  m->d_xb_new = 1.0 - tau / dt * one_minus_e;
  m->d_xb_old = tau / dt * one_minus_e - E;
  m->d_tau = -s * one_minus_e + q * E * dt / (tau * tau);
}

/* ------------------------------------------------------------------ */
/* Relaxation spectrum: M branches log-spaced over [spec_tau_min,         */
/* spec_tau_max], two per decade, stiffness k_j = spec_k w_j with         */
/* w_j = tau_j^-beta / sum_i tau_i^-beta (beta = spec_exp): a power-law-  */
/* like long memory from two fitted numbers (level, exponent).            */
/* ------------------------------------------------------------------ */
typedef struct rtb_spectrum {
  int M;                            /* 0: off */
  double tau[RTB_MAX_BRANCHES];
  double w[RTB_MAX_BRANCHES];       /* weights, sum 1 */
  double dw_dbeta[RTB_MAX_BRANCHES];
} rtb_spectrum;

static inline int rtb_spectrum_branches(const rtb_params *p) {
  if (!(p->spec_tau_min > 0.0)) return 0;
  const double decades = log10(p->spec_tau_max / p->spec_tau_min);
  int M = 1 + (int)floor(2.0 * decades + 0.5);
  return M < 1 ? 1 : (M > RTB_MAX_BRANCHES ? RTB_MAX_BRANCHES : M);
}

static inline void rtb_spectrum_layout(const rtb_params *p, rtb_spectrum *sp) {
  sp->M = rtb_spectrum_branches(p);
  if (sp->M == 0) return;
  const double l0 = log(p->spec_tau_min);
  const double dl = sp->M > 1 ? (log(p->spec_tau_max) - l0) / (sp->M - 1) : 0.0;
  /* Weights relative to the fastest branch (exponents <= |beta| * range:
   * no overflow for any finite beta that keeps them representable). */
  double sum = 0.0, mean_l = 0.0;
  for (int j = 0; j < sp->M; ++j) {
    sp->tau[j] = exp(l0 + j * dl);
    sp->w[j] = exp(-p->spec_exp * j * dl);
    sum += sp->w[j];
  }
  for (int j = 0; j < sp->M; ++j) {
    sp->w[j] /= sum;
    mean_l += sp->w[j] * j * dl;
  }
  /* d w_j / d beta = w_j (mean log tau - log tau_j) */
  for (int j = 0; j < sp->M; ++j) sp->dw_dbeta[j] = sp->w[j] * (mean_l - j * dl);
}

/* ------------------------------------------------------------------ */
/* Force and partials at fixed memories (y1, z, z_j)                      */
/* ------------------------------------------------------------------ */
typedef struct rtb_force_lin {
  double F;          /* force without inertia */
  double d_xb;       /* dF/dxb_new at fixed y1, z, z_j (dF/dy1 = -Kpa, dF/dz = -maxwell_k,
                        dF/dz_j = -spec_k w_j) */
  double d_xb_old;   /* through the linear dashpot */
  double d_xbmax;    /* through the Mullins memory (prior max |xb|) */
  /* dF/d(parameter) */
  double d_K0, d_Kpa, d_k3, d_k_asym, d_maxwell_k, d_viscous_c, d_mullins;
  double d_sat_force, d_sat_disp, d_spec_k, d_spec_exp;
} rtb_force_lin;

static inline void rtb_force_eval(const rtb_params *p, double xb, double xb_old, double xbmax_old,
                                  double y1, double z, const double *z_spec,
                                  const rtb_spectrum *sp, double dt, rtb_force_lin *L) {
  const double ax = fabs(xb);
  const double sgn = xb > 0.0 ? 1.0 : (xb < 0.0 ? -1.0 : 0.0);
  /* Mullins: K0 softened by eta = 1 - mu (1 - |xb|/m) below the prior max m. */
  const int below = p->mullins > 0.0 && ax < xbmax_old;
  const double deta_dmu = below ? -(1.0 - ax / xbmax_old) : 0.0;
  const double eta = 1.0 + p->mullins * deta_dmu;
  const double deta_dxb = below ? p->mullins * sgn / xbmax_old : 0.0;
  const double deta_dm = below ? -p->mullins * ax / (xbmax_old * xbmax_old) : 0.0;
  /* Softening spring Fs tanh(xb/xs); sech^2 = 1 - tanh^2. */
  const double xs = p->sat_disp;
  const double th = xs > 0.0 ? tanh(xb / xs) : 0.0, sech2 = 1.0 - th * th;
  /* Spectrum branches. */
  double Fsp = 0.0, dFsp_dbeta = 0.0;
  for (int j = 0; j < sp->M; ++j) {
    Fsp += sp->w[j] * (xb - z_spec[j]);
    dFsp_dbeta += sp->dw_dbeta[j] * (xb - z_spec[j]);
  }
  const double v = (xb - xb_old) / dt;

  L->F = p->K0 * eta * xb + p->Kpa * (xb - y1) + p->k3 * xb * xb * xb + p->k_asym * ax +
         p->sat_force * th + p->maxwell_k * (xb - z) + p->spec_k * Fsp + p->viscous_c * v;
  L->d_xb = p->K0 * (eta + xb * deta_dxb) + p->Kpa + 3.0 * p->k3 * xb * xb + p->k_asym * sgn +
            (xs > 0.0 ? p->sat_force / xs * sech2 : 0.0) + p->maxwell_k +
            (sp->M > 0 ? p->spec_k : 0.0) + p->viscous_c / dt;
  L->d_xb_old = -p->viscous_c / dt;
  L->d_xbmax = p->K0 * xb * deta_dm;
  L->d_K0 = eta * xb;
  L->d_Kpa = xb - y1;
  L->d_k3 = xb * xb * xb;
  L->d_k_asym = ax;
  L->d_maxwell_k = xb - z;
  L->d_viscous_c = v;
  L->d_mullins = p->K0 * xb * deta_dmu;
  L->d_sat_force = th;
  L->d_sat_disp = xs > 0.0 ? -p->sat_force * sech2 * xb / (xs * xs) : 0.0;
  L->d_spec_k = Fsp;
  L->d_spec_exp = p->spec_k * dFsp_dbeta;
}

#endif
