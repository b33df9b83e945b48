/* bushing_force.h -- the bushing's force law and its memories, with every
 * partial derivative: the ONE definition the real-time stepper (step.cpp)
 * evaluates and the offline adjoint (offline/adjoint/step_linearization.cpp)
 * differentiates, so the two cannot drift apart.
 *
 *   F = K0 eta(xb) xb + Kpa (xb - y1)                      eq. (11), Mullins eta
 *       (eta linear in |xb|, or Ogden-Roxburgh's erf with mullins_width)
 *       (mullins_whole: eta (K0 xb + Kpa (xb - y1)), the whole RT force)
 *     + k2 xb^2 + k3 xb^3 + k_asym |xb|                      elastic extensions
 *     + sat_force tanh(xb/sat_disp)
 *     + maxwell_k (xb - z) + sum_j k_j (xb - z_j)            Maxwell branch, spectrum
 *     + viscous_c (xb - xb_old)/dt                           linear dashpot
 * with relax_width w > 0 the relaxing force (Kpa, Maxwell and spectrum terms)
 * is scaled by g(xb) = 1/sqrt(1 + (xb/w)^2): relaxation weakening with stretch.
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
  rtb_real z;         /* z at the end of the step */
  rtb_real d_z_old;   /* = E = exp(-dt/tau) */
  rtb_real d_xb_new, d_xb_old, d_tau;
} rtb_maxwell_lin;

/*   z_new = xb_new - s tau + E (z_old - xb_old + s tau),  s = (xb_new - xb_old)/dt. */
static inline void rtb_maxwell_step(rtb_real tau, rtb_real dt, rtb_real xb_old, rtb_real xb_new,
                                    rtb_real z_old, rtb_maxwell_lin *m) {
  const rtb_real one_minus_e = -expm1(-dt / tau); /* accurate for dt << tau */
  const rtb_real E = 1.0 - one_minus_e;
  const rtb_real s = (xb_new - xb_old) / dt;
  const rtb_real q = z_old - xb_old + s * tau;
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
  rtb_real tau[RTB_MAX_BRANCHES];
  rtb_real w[RTB_MAX_BRANCHES];       /* weights, sum 1 */
  rtb_real dw_dbeta[RTB_MAX_BRANCHES];
} rtb_spectrum;

static inline int rtb_spectrum_branches(const rtb_params *p) {
  if (!(p->spec_tau_min > 0.0)) return 0;
  const rtb_real decades = log10(p->spec_tau_max / p->spec_tau_min);
  int M = 1 + (int)floor(2.0 * decades + 0.5);
  return M < 1 ? 1 : (M > RTB_MAX_BRANCHES ? RTB_MAX_BRANCHES : M);
}

static inline void rtb_spectrum_layout(const rtb_params *p, rtb_spectrum *sp) {
  sp->M = rtb_spectrum_branches(p);
  if (sp->M == 0) return;
  const rtb_real l0 = log(p->spec_tau_min);
  const rtb_real dl = sp->M > 1 ? (log(p->spec_tau_max) - l0) / (sp->M - 1) : 0.0;
  /* Weights relative to the fastest branch (exponents <= |beta| * range:
   * no overflow for any finite beta that keeps them representable). */
  rtb_real sum = 0.0, mean_l = 0.0;
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
  rtb_real F;          /* force without inertia */
  rtb_real d_xb;       /* dF/dxb_new at fixed y1, z, z_j */
  rtb_real d_y1;       /* dF/dy1: -g Kpa, or -eta g Kpa with mullins_whole */
  rtb_real d_z;        /* dF/dz: -g maxwell_k */
  rtb_real d_z_spec;   /* dF/dz_j = d_z_spec w_j: -g spec_k */
  rtb_real d_xb_old;   /* through the linear dashpot */
  rtb_real d_xbmax;    /* through the Mullins memory (prior max |xb|) */
  /* dF/d(parameter) */
  rtb_real d_K0, d_Kpa, d_k2, d_k3, d_k_asym, d_maxwell_k, d_viscous_c, d_mullins;
  rtb_real d_sat_force, d_sat_disp, d_spec_k, d_spec_exp, d_mullins_width, d_relax_width;
} rtb_force_lin;

/* Stretch factor of the relaxing force, g = (1 + u^2)^(-1/2), u = xb/w, and
 * its partials (g = 1 when w = 0: off). */
typedef struct rtb_relax_lin {
  rtb_real g, d_xb, d_w;
} rtb_relax_lin;

static inline rtb_relax_lin rtb_relax_eval(const rtb_params *p, rtb_real xb) {
  rtb_relax_lin r = {1.0, 0.0, 0.0};
  const rtb_real w = p->relax_width;
  if (!(w > 0.0)) return r;
  const rtb_real u = xb / w;
  r.g = 1.0 / sqrt(1.0 + u * u);
  const rtb_real g3 = r.g * r.g * r.g;
  r.d_xb = -g3 * u / w;
  r.d_w = g3 * u * u / w;
  return r;
}

/* Mullins factor eta below the prior max m and its partials. */
typedef struct rtb_mullins_lin {
  rtb_real eta, d_mu, d_xb, d_m, d_w;
} rtb_mullins_lin;

/* Linear: eta = 1 - mu (1 - |xb|/m). Ogden-Roxburgh (w > 0):
 * eta = 1 - mu erf(a), a = (m^2 - xb^2)/w^2. eta = 1 at and above the max. */
static inline rtb_mullins_lin rtb_mullins_eval(const rtb_params *p, rtb_real xb, rtb_real m) {
  rtb_mullins_lin e = {1.0, 0.0, 0.0, 0.0, 0.0};
  const rtb_real ax = fabs(xb);
  if (!(p->mullins > 0.0 && ax < m)) return e;
  const rtb_real mu = p->mullins, w = p->mullins_width;
  if (w > 0.0) {
    const rtb_real w2 = w * w, a = (m * m - xb * xb) / w2;
    const rtb_real g = erf(a), dg = 1.1283791670955126 * exp(-a * a); /* 2/sqrt(pi) e^-a^2 */
    e.d_mu = -g;
    e.d_xb = mu * dg * 2.0 * xb / w2;
    e.d_m = -mu * dg * 2.0 * m / w2;
    e.d_w = mu * dg * 2.0 * a / w;
  } else {
    const rtb_real sgn = xb > 0.0 ? 1.0 : (xb < 0.0 ? -1.0 : 0.0);
    e.d_mu = -(1.0 - ax / m);
    e.d_xb = mu * sgn / m;
    e.d_m = -mu * ax / (m * m);
  }
  e.eta = 1.0 + mu * e.d_mu;
  return e;
}

static inline void rtb_force_eval(const rtb_params *p, rtb_real xb, rtb_real xb_old, rtb_real xbmax_old,
                                  rtb_real y1, rtb_real z, const rtb_real *z_spec,
                                  const rtb_spectrum *sp, rtb_real dt, rtb_force_lin *L) {
  const rtb_real ax = fabs(xb);
  const rtb_real sgn = xb > 0.0 ? 1.0 : (xb < 0.0 ? -1.0 : 0.0);
  /* Mullins factor eta below the prior max, on K0 xb or on the whole RT
   * force S = K0 xb + g Kpa (xb - y1) (mullins_whole). */
  const rtb_mullins_lin mu = rtb_mullins_eval(p, xb, xbmax_old);
  const rtb_real eta = mu.eta;
  const int whole = p->mullins_whole != 0.0;
  const rtb_real chain = xb - y1;
  const rtb_real eta_pa = whole ? eta : 1.0;                             /* ... on Kpa */
  const rtb_relax_lin g = rtb_relax_eval(p, xb);
  const rtb_real S = whole ? p->K0 * xb + g.g * p->Kpa * chain : p->K0 * xb; /* what eta scales */
  /* Softening spring Fs tanh(xb/xs); sech^2 = 1 - tanh^2. */
  const rtb_real xs = p->sat_disp;
  const rtb_real th = xs > 0.0 ? tanh(xb / xs) : 0.0, sech2 = 1.0 - th * th;
  /* Spectrum branches. */
  rtb_real Fsp = 0.0, dFsp_dbeta = 0.0;
  for (int j = 0; j < sp->M; ++j) {
    Fsp += sp->w[j] * (xb - z_spec[j]);
    dFsp_dbeta += sp->dw_dbeta[j] * (xb - z_spec[j]);
  }
  const rtb_real v = (xb - xb_old) / dt;
  /* The relaxing force before its stretch factor g. */
  const rtb_real R = eta_pa * p->Kpa * chain + p->maxwell_k * (xb - z) + p->spec_k * Fsp;

  L->F = p->K0 * eta * xb + g.g * R + p->k2 * xb * xb + p->k3 * xb * xb * xb + p->k_asym * ax +
         p->sat_force * th + p->viscous_c * v;
  L->d_xb = eta * p->K0 + g.g * (eta_pa * p->Kpa + p->maxwell_k + (sp->M > 0 ? p->spec_k : 0.0)) +
            g.d_xb * R + S * mu.d_xb + 2.0 * p->k2 * xb + 3.0 * p->k3 * xb * xb + p->k_asym * sgn +
            (xs > 0.0 ? p->sat_force / xs * sech2 : 0.0) + p->viscous_c / dt;
  L->d_y1 = -g.g * eta_pa * p->Kpa;
  L->d_z = -g.g * p->maxwell_k;
  L->d_z_spec = -g.g * p->spec_k;
  L->d_xb_old = -p->viscous_c / dt;
  L->d_xbmax = S * mu.d_m;
  L->d_K0 = eta * xb;
  L->d_Kpa = g.g * eta_pa * chain;
  L->d_k2 = xb * xb;
  L->d_k3 = xb * xb * xb;
  L->d_k_asym = ax;
  L->d_maxwell_k = g.g * (xb - z);
  L->d_viscous_c = v;
  L->d_mullins = S * mu.d_mu;
  L->d_mullins_width = S * mu.d_w;
  L->d_sat_force = th;
  L->d_sat_disp = xs > 0.0 ? -p->sat_force * sech2 * xb / (xs * xs) : 0.0;
  L->d_spec_k = g.g * Fsp;
  L->d_spec_exp = g.g * p->spec_k * dFsp_dbeta;
  L->d_relax_width = g.d_w * R;
}

#endif
