// step_linearization.cpp -- exact tangent and adjoint of one stepper step.
#include "adjoint/step_linearization.h"

#include <cmath>
#include <cstring>

#include "rt_bushing/src/dashpot_law.h"
#include "rt_bushing/src/tridiagonal.h"

namespace rtb {

void StateDual::clear() { std::memset(this, 0, sizeof *this); }

namespace {

constexpr double kRho = (1.0 - RTB_SDIRK_GAMMA) / RTB_SDIRK_GAMMA;  // c2 = y + rho (Y1 - y)

// Stage matrix A = I + h D K (transpose = false) or A^T = I + h K D.
void stage_matrix(const rtb_params &p, const StageView &st, bool transpose, double *lo,
                  double *di, double *up, double *D) {
  const int n = p.cells;
  for (int k = 0; k < n; ++k) D[k] = rtb_law_dvdf(st.f[k], st.v[k], p.alpha);
  for (int k = 0; k < n; ++k) {
    di[k] = 1.0 + st.h * D[k] * rtb_chain_diag(k, p.Kpa, p.Kr);
    if (!transpose) {
      lo[k] = k > 0 ? -st.h * D[k] * p.Kr : 0.0;
      up[k] = k + 1 < n ? -st.h * D[k] * p.Kr : 0.0;
    } else {
      lo[k] = k > 0 ? -st.h * D[k - 1] * p.Kr : 0.0;
      up[k] = k + 1 < n ? -st.h * D[k + 1] * p.Kr : 0.0;
    }
  }
}

// (dK/dKr Y)_k: the chain pattern with unit Kr and no Kpa.
double dK_dKr_row(const StageView &st, int k, int n) {
  double s = (k == 0 ? 1.0 : 2.0) * st.y[k];
  if (k > 0) s -= st.y[k - 1];
  if (k + 1 < n) s -= st.y[k + 1];
  return s;
}

// dY = A^-1 [dc + h D e1 db1 - h D (dK Y) + h phi_p dp].
void stage_jvp(const rtb_params &p, const StageView &st, const double *dc, double db1,
               const double *dp, double *dY) {
  const int n = p.cells;
  double lo[RTB_MAX_CELLS], di[RTB_MAX_CELLS], up[RTB_MAX_CELLS], D[RTB_MAX_CELLS],
      work[RTB_MAX_CELLS];
  stage_matrix(p, st, false, lo, di, up, D);
  for (int k = 0; k < n; ++k) {
    double dKY = dp[P_Kr] * dK_dKr_row(st, k, n) + (k == 0 ? dp[P_Kpa] * st.y[0] : 0.0);
    double rhs = dc[k] + st.h * D[k] * ((k == 0 ? db1 : 0.0) - dKY);
    rhs += st.h * (rtb_law_dv_dC0(st.v[k], p.C0, p.alpha) * dp[P_C0] +
                   rtb_law_dv_dalpha(st.f[k], st.v[k], p.C0, p.alpha) * dp[P_alpha]);
    dY[k] = rhs;
  }
  rtb_tridiag_solve(n, lo, di, up, dY, work);
}

// Transpose of stage_jvp: given Ybar, add to cbar and pbar; returns b1bar.
double stage_vjp(const rtb_params &p, const StageView &st, const double *Ybar, double *cbar,
                 double *pbar) {
  const int n = p.cells;
  double lo[RTB_MAX_CELLS], di[RTB_MAX_CELLS], up[RTB_MAX_CELLS], D[RTB_MAX_CELLS],
      mu[RTB_MAX_CELLS], work[RTB_MAX_CELLS];
  stage_matrix(p, st, true, lo, di, up, D);
  for (int k = 0; k < n; ++k) mu[k] = Ybar[k];
  rtb_tridiag_solve(n, lo, di, up, mu, work);
  double gKr = 0.0, gC0 = 0.0, gA = 0.0;
  for (int k = 0; k < n; ++k) {
    cbar[k] += mu[k];
    const double hDmu = st.h * D[k] * mu[k];
    gKr -= hDmu * dK_dKr_row(st, k, n);
    gC0 += st.h * mu[k] * rtb_law_dv_dC0(st.v[k], p.C0, p.alpha);
    gA += st.h * mu[k] * rtb_law_dv_dalpha(st.f[k], st.v[k], p.C0, p.alpha);
  }
  pbar[P_Kr] += gKr;
  pbar[P_C0] += gC0;
  pbar[P_alpha] += gA;
  pbar[P_Kpa] -= st.h * D[0] * mu[0] * st.y[0];
  return st.h * D[0] * mu[0];
}

// Maxwell branch z_new = xb - s tau + E (z_old - xb_old + s tau), E = exp(-dt/tau).
struct MaxwellLin {
  double E = 0.0, dz_dtau = 0.0;
};
MaxwellLin maxwell_lin(const StepView &v) {
  MaxwellLin m;
  const rtb_params &p = *v.p;
  if (!(p.maxwell_tau > 0.0)) return m;  // branch off: z frozen
  const double tau = p.maxwell_tau, dt = v.dt;
  const double xb0 = v.xb_old, xb1 = v.xb_new;
  const double s = (xb1 - xb0) / dt;
  m.E = std::exp(-dt / tau);
  m.dz_dtau = -s + m.E * s + (v.z_old - xb0 + s * tau) * m.E * dt / (tau * tau);
  return m;
}

// Mullins factor eta = 1 - mu (1 - |xb|/xb_max_old) below the prior maximum.
double mullins_deta_dmu(const StepView &v) {
  const double ax = std::fabs(v.xb_new), m = v.xbmax_old;
  return ax < m ? -(1.0 - ax / m) : 0.0;
}

// Partial derivatives of the force w.r.t. the parameters at fixed state.
void force_partials(const StepView &v, double *g) {
  const rtb_params &p = *v.p;
  const double xb = v.xb_new, xb0 = v.xb_old, dt = v.dt;
  const double dmu = mullins_deta_dmu(v);
  const double eta = 1.0 + p.mullins * dmu;
  for (int i = 0; i < P_COUNT; ++i) g[i] = 0.0;
  g[P_K0] = xb * eta;
  g[P_Kpa] = xb - v.y_new[0];
  g[P_k3] = xb * xb * xb;
  g[P_k_asym] = std::fabs(xb);
  g[P_maxwell_k] = xb - v.z_new;
  g[P_viscous_c] = (xb - xb0) / dt;
  g[P_mass] = (v.vx_new - v.vx_old) / dt;
  g[P_mullins] = p.K0 * xb * dmu;
}

}  // namespace

void chain_jvp(const StepView &v, const StateDual &d_old, const double *dp, StateDual &d_new) {
  const rtb_params &p = *v.p;
  const int n = p.cells;
  const double xb0 = v.xb_old, xb1 = v.xb_new;
  if (rtb_integrator_stages(&p) == 1) {
    stage_jvp(p, v.st[0], d_old.y, dp[P_Kpa] * xb1, dp, d_new.y);
  } else {
    const double xg = xb0 + RTB_SDIRK_GAMMA * (xb1 - xb0);
    double dY1[RTB_MAX_CELLS], dc2[RTB_MAX_CELLS];
    stage_jvp(p, v.st[0], d_old.y, dp[P_Kpa] * xg, dp, dY1);
    for (int k = 0; k < n; ++k) dc2[k] = d_old.y[k] + kRho * (dY1[k] - d_old.y[k]);
    stage_jvp(p, v.st[1], dc2, dp[P_Kpa] * xb1, dp, d_new.y);
  }
  const MaxwellLin m = maxwell_lin(v);
  d_new.z = m.E * d_old.z + m.dz_dtau * dp[P_maxwell_tau];
}

void chain_vjp(const StepView &v, const StateDual &bar_new, StateDual &bar_old, double *pbar) {
  const rtb_params &p = *v.p;
  const int n = p.cells;
  const double xb0 = v.xb_old, xb1 = v.xb_new;
  if (rtb_integrator_stages(&p) == 1) {
    pbar[P_Kpa] += xb1 * stage_vjp(p, v.st[0], bar_new.y, bar_old.y, pbar);
  } else {
    const double xg = xb0 + RTB_SDIRK_GAMMA * (xb1 - xb0);
    double c2bar[RTB_MAX_CELLS] = {0}, Y1bar[RTB_MAX_CELLS];
    pbar[P_Kpa] += xb1 * stage_vjp(p, v.st[1], bar_new.y, c2bar, pbar);
    for (int k = 0; k < n; ++k) {
      Y1bar[k] = kRho * c2bar[k];
      bar_old.y[k] += (1.0 - kRho) * c2bar[k];
    }
    pbar[P_Kpa] += xg * stage_vjp(p, v.st[0], Y1bar, bar_old.y, pbar);
  }
  const MaxwellLin m = maxwell_lin(v);
  bar_old.z += m.E * bar_new.z;
  pbar[P_maxwell_tau] += m.dz_dtau * bar_new.z;
}

double force_jvp(const StepView &v, const StateDual &d_new, const double *dp) {
  double g[P_COUNT];
  force_partials(v, g);
  double dF = -v.p->Kpa * d_new.y[0] - v.p->maxwell_k * d_new.z;
  for (int i = 0; i < P_COUNT; ++i) dF += g[i] * dp[i];
  return dF;
}

void force_vjp(const StepView &v, double Fbar, StateDual &bar_new, double *pbar) {
  double g[P_COUNT];
  force_partials(v, g);
  bar_new.y[0] -= v.p->Kpa * Fbar;
  bar_new.z -= v.p->maxwell_k * Fbar;
  for (int i = 0; i < P_COUNT; ++i) pbar[i] += g[i] * Fbar;
}

}  // namespace rtb
