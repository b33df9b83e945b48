// step_linearization.cpp -- exact tangent and adjoint of one stepper step.
#include "adjoint/step_linearization.h"

#include <cmath>
#include <cstring>

#include "rt_bushing/src/dashpot_law.h"
#include "rt_bushing/src/tridiagonal.h"

namespace rtb {

void StateDual::clear() { std::memset(this, 0, sizeof *this); }

namespace {

constexpr double kGamma = RTB_SDIRK_GAMMA;
constexpr double kRho = (1.0 - kGamma) / kGamma;  // c2 = y + rho (Y1 - y)

// ------------------------------------------------------------- one stage
// The dashpot derivatives (D = dv/df, dv/dC0 and dv/dalpha at fixed f) come
// from dashpot_law.h: eq. (1), or eq. (14) when p.smoothing > 0. The
// smoothing s itself is a fixed model setting, not a parameter: no dp entry.
// Stage matrix A = I + h D K (transpose = false) or A^T = I + h K D.
void stage_matrix(const rtb_params &p, const StageView &st, bool transpose, double *lo,
                  double *di, double *up, double *D) {
  const int n = p.cells;
  for (int k = 0; k < n; ++k)
    D[k] = st.lin ? st.lin->D[k] : rtb_dashpot_dvdf(st.f[k], st.v[k], p.C0, p.alpha, p.smoothing);
  for (int k = 0; k < n; ++k) {
    di[k] = 1.0 + st.h * D[k] * rtb_chain_diag(k, p.Kpa, p.Kr);
    const int l = transpose ? k - 1 : k, u = transpose ? k + 1 : k;
    lo[k] = k > 0 ? -st.h * D[l] * p.Kr : 0.0;
    up[k] = k + 1 < n ? -st.h * D[u] * p.Kr : 0.0;
  }
}

// (dK/dKr Y)_k: the chain pattern with unit Kr and no Kpa.
double dK_dKr_row(const StageView &st, int k, int n) {
  double s = (k == 0 ? 1.0 : 2.0) * st.y[k];
  if (k > 0) s -= st.y[k - 1];
  if (k + 1 < n) s -= st.y[k + 1];
  return s;
}

double dv_dC0(const rtb_params &p, const StageView &st, int k) {
  return st.lin ? st.lin->dv_dC0[k]
                : rtb_dashpot_dv_dC0(st.f[k], st.v[k], p.C0, p.alpha, p.smoothing);
}
double dv_dalpha(const rtb_params &p, const StageView &st, int k) {
  return st.lin ? st.lin->dv_dalpha[k]
                : rtb_dashpot_dv_dalpha(st.f[k], st.v[k], p.C0, p.alpha, p.smoothing);
}

// dY = A^-1 [dc + h D e1 db1 - h D (dK Y) + h phi_p dp].
void stage_jvp(const rtb_params &p, const StageView &st, const double *dc, double db1,
               const double *dp, double *dY) {
  const int n = p.cells;
  double lo[RTB_MAX_CELLS], di[RTB_MAX_CELLS], up[RTB_MAX_CELLS], D[RTB_MAX_CELLS],
      work[RTB_MAX_CELLS];
  stage_matrix(p, st, false, lo, di, up, D);
  for (int k = 0; k < n; ++k) {
    const double dKY = dp[P_Kr] * dK_dKr_row(st, k, n) + (k == 0 ? dp[P_Kpa] * st.y[0] : 0.0);
    dY[k] = dc[k] + st.h * D[k] * ((k == 0 ? db1 : 0.0) - dKY) +
            st.h * (dv_dC0(p, st, k) * dp[P_C0] + dv_dalpha(p, st, k) * dp[P_alpha]);
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
  for (int k = 0; k < n; ++k) {
    cbar[k] += mu[k];
    pbar[P_Kr] -= st.h * D[k] * mu[k] * dK_dKr_row(st, k, n);
    pbar[P_C0] += st.h * mu[k] * dv_dC0(p, st, k);
    pbar[P_alpha] += st.h * mu[k] * dv_dalpha(p, st, k);
  }
  pbar[P_Kpa] -= st.h * D[0] * mu[0] * st.y[0];
  return st.h * D[0] * mu[0];
}

// ------------------------------------------------------------- partials
// Maxwell branch, exact for xb linear over the step (step.cpp):
//   z_new = xb_new - s tau + E (z_old - xb_old + s tau),  s = (xb_new - xb_old)/dt.
struct MaxwellLin {
  double E = 0, dtau = 0, dxb_new = 0, dxb_old = 0;
};
MaxwellLin maxwell_lin(const StepView &v) {
  MaxwellLin m;
  const rtb_params &p = *v.p;
  if (!(p.maxwell_tau > 0.0)) return m;  // branch off: z frozen
  const double tau = p.maxwell_tau, dt = v.dt;
  const double s = (v.xb_new - v.xb_old) / dt;
  m.E = std::exp(-dt / tau);
  m.dtau = -s + m.E * s + (v.z_old - v.xb_old + s * tau) * m.E * dt / (tau * tau);
  m.dxb_new = 1.0 - tau / dt + m.E * tau / dt;
  m.dxb_old = tau / dt - m.E - m.E * tau / dt;
  return m;
}

// Partial derivatives of the force at fixed states (step.cpp,
// rtb_bushing_force, plus inertia).
struct ForceLin {
  double xb_new = 0, xb_old = 0, m_old = 0;  // dF/d(state entries); dF/dy1 = -Kpa, dF/dz = -Kmaxwell
  double g[P_COUNT] = {0};                   // dF/dp
};
ForceLin force_lin(const StepView &v, bool with_inertia) {
  const rtb_params &p = *v.p;
  ForceLin L;
  const double xb = v.xb_new, ax = std::fabs(xb), m = v.xbmax_old, dt = v.dt;
  const double sgn = xb > 0.0 ? 1.0 : (xb < 0.0 ? -1.0 : 0.0);
  // Mullins: eta = 1 - mu (1 - |xb|/m) below the prior maximum m.
  const bool below = ax < m;
  const double deta_dmu = below ? -(1.0 - ax / m) : 0.0;
  const double eta = (p.mullins > 0.0 && below) ? 1.0 + p.mullins * deta_dmu : 1.0;
  const double deta_dxb = (p.mullins > 0.0 && below) ? p.mullins * sgn / m : 0.0;
  const double deta_dm = (p.mullins > 0.0 && below) ? -p.mullins * ax / (m * m) : 0.0;
  // Softening spring Fs tanh(xb/xs): d/dxb = Fs/xs sech^2, d/dFs = tanh,
  // d/dxs = -Fs sech^2 xb/xs^2 (sech^2 = 1 - tanh^2).
  const double xs = p.sat_disp, th = xs > 0.0 ? std::tanh(xb / xs) : 0.0, sech2 = 1.0 - th * th;
  L.xb_new = p.K0 * (eta + xb * deta_dxb) + p.Kpa + 3.0 * p.k3 * xb * xb + p.k_asym * sgn +
             p.maxwell_k + p.viscous_c / dt + (xs > 0.0 ? p.sat_force / xs * sech2 : 0.0);
  L.g[P_sat_force] = th;
  L.g[P_sat_disp] = xs > 0.0 ? -p.sat_force * sech2 * xb / (xs * xs) : 0.0;
  L.xb_old = -p.viscous_c / dt;
  L.m_old = p.K0 * xb * deta_dm;
  L.g[P_K0] = xb * eta;
  L.g[P_Kpa] = xb - v.y_new[0];
  L.g[P_k3] = xb * xb * xb;
  L.g[P_k_asym] = ax;
  L.g[P_maxwell_k] = xb - v.z_new;
  L.g[P_viscous_c] = (xb - v.xb_old) / dt;
  L.g[P_mullins] = p.K0 * xb * deta_dmu;
  if (with_inertia) L.g[P_mass] = (v.vx_new - v.vx_old) / dt;
  return L;
}

// ------------------------------------------------------------- C and Fo
// State map C with the bushing displacement's own tangent dxb given.
void chain_jvp(const StepView &v, const StateDual &d, const double *dp, double dxb,
               StateDual &dn) {
  const rtb_params &p = *v.p;
  const int n = p.cells;
  if (p.model == RTB_MODEL_RT) {
    if (rtb_integrator_stages(&p) == 1) {
      stage_jvp(p, v.st[0], d.y, dp[P_Kpa] * v.xb_new + p.Kpa * dxb, dp, dn.y);
    } else {
      const double xg = v.xb_old + kGamma * (v.xb_new - v.xb_old);
      const double dxg = d.xb + kGamma * (dxb - d.xb);
      double dY1[RTB_MAX_CELLS], dc2[RTB_MAX_CELLS];
      stage_jvp(p, v.st[0], d.y, dp[P_Kpa] * xg + p.Kpa * dxg, dp, dY1);
      for (int k = 0; k < n; ++k) dc2[k] = d.y[k] + kRho * (dY1[k] - d.y[k]);
      stage_jvp(p, v.st[1], dc2, dp[P_Kpa] * v.xb_new + p.Kpa * dxb, dp, dn.y);
    }
  }
  const MaxwellLin mx = maxwell_lin(v);
  dn.z = mx.E * d.z + mx.dtau * dp[P_maxwell_tau] + mx.dxb_new * dxb + mx.dxb_old * d.xb;
  dn.xb = dxb;
  dn.m = std::fabs(v.xb_new) > v.xbmax_old ? (v.xb_new > 0 ? dxb : -dxb) : d.m;
}

// Transpose of chain_jvp; *xbbar receives the cotangent of xb_new.
void chain_vjp(const StepView &v, const StateDual &bn, StateDual &bo, double *pbar,
               double *xbbar) {
  const rtb_params &p = *v.p;
  const int n = p.cells;
  double dxb_bar = bn.xb;
  if (std::fabs(v.xb_new) > v.xbmax_old) dxb_bar += (v.xb_new > 0 ? bn.m : -bn.m);
  else bo.m += bn.m;
  const MaxwellLin mx = maxwell_lin(v);
  bo.z += mx.E * bn.z;
  pbar[P_maxwell_tau] += mx.dtau * bn.z;
  dxb_bar += mx.dxb_new * bn.z;
  bo.xb += mx.dxb_old * bn.z;
  if (p.model == RTB_MODEL_RT) {
    if (rtb_integrator_stages(&p) == 1) {
      const double b1 = stage_vjp(p, v.st[0], bn.y, bo.y, pbar);
      pbar[P_Kpa] += v.xb_new * b1;
      dxb_bar += p.Kpa * b1;
    } else {
      const double xg = v.xb_old + kGamma * (v.xb_new - v.xb_old);
      double c2bar[RTB_MAX_CELLS] = {0}, Y1bar[RTB_MAX_CELLS];
      const double b2 = stage_vjp(p, v.st[1], bn.y, c2bar, pbar);
      pbar[P_Kpa] += v.xb_new * b2;
      dxb_bar += p.Kpa * b2;
      for (int k = 0; k < n; ++k) {
        Y1bar[k] = kRho * c2bar[k];
        bo.y[k] += (1.0 - kRho) * c2bar[k];
      }
      const double b1 = stage_vjp(p, v.st[0], Y1bar, bo.y, pbar);
      pbar[P_Kpa] += xg * b1;
      dxb_bar += p.Kpa * kGamma * b1;
      bo.xb += p.Kpa * (1.0 - kGamma) * b1;
    }
  }
  *xbbar = dxb_bar;
}

double force_jvp(const StepView &v, const StateDual &d, const StateDual &dn, const double *dp,
                 bool with_inertia) {
  const ForceLin L = force_lin(v, with_inertia);
  double dF = -v.p->Kpa * dn.y[0] - v.p->maxwell_k * dn.z + L.xb_new * dn.xb +
              L.xb_old * d.xb + L.m_old * d.m;
  for (int i = 0; i < P_COUNT; ++i) dF += L.g[i] * dp[i];
  return dF;
}

void force_vjp(const StepView &v, double Fbar, StateDual &bo, StateDual &bn, double *pbar,
               bool with_inertia) {
  const ForceLin L = force_lin(v, with_inertia);
  bn.y[0] -= v.p->Kpa * Fbar;
  bn.z -= v.p->maxwell_k * Fbar;
  bn.xb += L.xb_new * Fbar;
  bo.xb += L.xb_old * Fbar;
  bo.m += L.m_old * Fbar;
  for (int i = 0; i < P_COUNT; ++i) pbar[i] += L.g[i] * Fbar;
}

// ------------------------------------------------------------- clearance B
// Free phase: F_bushing(xb_new) = 0, so dxb = -F_s / F_xb with F_s the
// bushing force's tangent at fixed xb_new and F_xb its total xb derivative.
double free_phase_stiffness(const StepView &v) {
  StateDual z, t;
  z.clear();
  t.clear();
  const double zero[P_COUNT] = {0};
  chain_jvp(v, z, zero, 1.0, t);
  return force_jvp(v, z, t, zero, false);
}

double clearance_jvp(const StepView &v, const StateDual &d, const double *dp) {
  if (v.contact == 2) return 0.0;  // xb = x: input data
  if (v.contact != 0) return -0.5 * v.contact * dp[P_backlash];
  StateDual t;
  t.clear();
  chain_jvp(v, d, dp, 0.0, t);
  return -force_jvp(v, d, t, dp, false) / free_phase_stiffness(v);
}

void clearance_vjp(const StepView &v, double xbbar, StateDual &bo, double *pbar) {
  if (v.contact == 2 || xbbar == 0.0) return;
  if (v.contact != 0) {
    pbar[P_backlash] += -0.5 * v.contact * xbbar;
    return;
  }
  const double seed = -xbbar / free_phase_stiffness(v);
  StateDual bn;
  bn.clear();
  force_vjp(v, seed, bo, bn, pbar, false);
  bn.xb = 0.0;  // xb_new is held fixed in F_s
  double ignored;
  chain_vjp(v, bn, bo, pbar, &ignored);
}

}  // namespace

void step_precompute(StepView &v, StageLin lin[2]) {
  const rtb_params &p = *v.p;
  if (p.model != RTB_MODEL_RT) return;
  for (int s = 0; s < rtb_integrator_stages(&p); ++s) {
    const StageView &st = v.st[s];
    for (int k = 0; k < p.cells; ++k) {
      lin[s].D[k] = rtb_dashpot_dvdf(st.f[k], st.v[k], p.C0, p.alpha, p.smoothing);
      lin[s].dv_dC0[k] = rtb_dashpot_dv_dC0(st.f[k], st.v[k], p.C0, p.alpha, p.smoothing);
      lin[s].dv_dalpha[k] = rtb_dashpot_dv_dalpha(st.f[k], st.v[k], p.C0, p.alpha, p.smoothing);
    }
    v.st[s].lin = &lin[s];
  }
}

double step_jvp(const StepView &v, const StateDual &d_old, const double *dp, StateDual &d_new) {
  const double dxb = clearance_jvp(v, d_old, dp);
  chain_jvp(v, d_old, dp, dxb, d_new);
  return force_jvp(v, d_old, d_new, dp, true);
}

void step_vjp(const StepView &v, const StateDual &bar_new, double Fbar, StateDual &bar_old,
              double *pbar) {
  StateDual bn = bar_new;
  force_vjp(v, Fbar, bar_old, bn, pbar, true);
  double xbbar = 0.0;
  chain_vjp(v, bn, bar_old, pbar, &xbbar);
  clearance_vjp(v, xbbar, bar_old, pbar);
}

}  // namespace rtb
