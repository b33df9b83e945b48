// step_linearization.cpp -- exact tangent and adjoint of one stepper step.
#include "adjoint/step_linearization.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "rt_bushing/src/bushing_force.h"
#include "rt_bushing/src/dashpot_law.h"
#include "rt_bushing/src/tridiagonal.h"

namespace rtb {

void StateDual::clear() { std::memset(this, 0, sizeof *this); }

void StateDual::assign_used(const StateDual &o, int cells, int branches) {
  std::memcpy(y, o.y, sizeof(double) * (size_t)cells);
  std::memcpy(zs, o.zs, sizeof(double) * (size_t)branches);
  z = o.z;
  xb = o.xb;
  m = o.m;
}

namespace {

constexpr double kGamma = RTB_SDIRK_GAMMA;
constexpr double kRho = (1.0 - kGamma) / kGamma;  // c2 = y + rho (Y1 - y)

// ------------------------------------------------------------- one stage
// The dashpot derivatives (D = dv/df, and dv/dC0, dv/dalpha, dv/dfric_asym at
// fixed f) come from dashpot_law.h: eq. (1), or eq. (14) when p.smoothing > 0,
// at the level C0 (1 +- fric_asym) of the force's sign. The smoothing s is a
// fixed model setting, not a parameter: no dp entry.
void stage_partials(const rtb_params &p, double f, double v, double *D, double *dC0,
                    double *dalpha, double *dfa) {
  const double L = rtb_dashpot_level(p.C0, p.fric_asym, f);
  const double sgn = f < 0.0 ? -1.0 : 1.0;
  const double dv_dL = rtb_dashpot_dv_dC0(f, v, L, p.alpha, p.smoothing);
  *D = rtb_dashpot_dvdf(f, v, L, p.alpha, p.smoothing);
  *dC0 = dv_dL * (1.0 + sgn * p.fric_asym);
  *dfa = dv_dL * sgn * p.C0;
  *dalpha = rtb_dashpot_dv_dalpha(f, v, L, p.alpha, p.smoothing);
}

StageLin stage_lin(const rtb_params &p, const StageView &st) {
  StageLin l;
  for (int k = 0; k < p.cells; ++k)
    stage_partials(p, st.f[k], st.v[k], &l.D[k], &l.dv_dC0[k], &l.dv_dalpha[k], &l.dv_dfa[k]);
  return l;
}

// Stage matrix A = I + h D K (transpose = false) or A^T = I + h K D.
void stage_matrix(const rtb_params &p, const StageView &st, const double *D, bool transpose,
                  double *lo, double *di, double *up) {
  rtb_stage_matrix(p.cells, st.h, D, p.Kpa, p.Kr, transpose ? 1 : 0, lo, di, up);
}

// stage_lin plus the Thomas factors of A = I + h D K, which every tangent
// direction (stage_jvp) solves with.
StageLin stage_lin_factored(const rtb_params &p, const StageView &st) {
  StageLin l = stage_lin(p, st);
  double di[RTB_MAX_CELLS], up[RTB_MAX_CELLS];
  stage_matrix(p, st, l.D, false, l.lo, di, up);
  rtb_tridiag_factor(p.cells, l.lo, di, up, l.piv, l.w);  // I + h D K, D >= 0: no zero pivot
  return l;
}

// (dK/dKr Y)_k: the chain pattern with unit Kr and no Kpa.
double dK_dKr_row(const StageView &st, int k, int n) {
  double s = (k == 0 ? 1.0 : 2.0) * st.y[k];
  if (k > 0) s -= st.y[k - 1];
  if (k + 1 < n) s -= st.y[k + 1];
  return s;
}

// Tangent directions advance through a step together (a Jacobian's
// columns, step_jvp_columns), at most this many at a time.
constexpr int kMaxColumns = P_COUNT;

// dY[c] = A^-1 [dc[c] + h D e1 db1[c] - h D (dK Y) + h phi_p dp[c]] for the
// m directions c, substituted together (rtb_tridiag_subst_many): each
// column's arithmetic is the same as alone.
void stage_jvp(const rtb_params &p, const StageView &st, int m, const double *const *dc,
               const double *db1, const double *const *dp, double *const *dY) {
  const int n = p.cells;
  StageLin own;  // only when the step was not precomputed
  if (!st.lin) own = stage_lin_factored(p, st);
  const StageLin &l = st.lin ? *st.lin : own;
  // What does not depend on the direction, once for all m: dK/dKr Y and h D.
  double dKrY[RTB_MAX_CELLS], hD[RTB_MAX_CELLS];
  for (int k = 0; k < n; ++k) dKrY[k] = dK_dKr_row(st, k, n), hD[k] = st.h * l.D[k];
  auto law = [&](const double *q, int k) {  // h dv/dp q at fixed f
    return st.h * (l.dv_dC0[k] * q[P_C0] + l.dv_dalpha[k] * q[P_alpha] + l.dv_dfa[k] * q[P_fric_asym]);
  };
  for (int c = 0; c < m; ++c) {
    const double *q = dp[c];
    // Row 0 carries the input's db1 and dKpa; the others 0.0 - dKY, as the
    // row-0 form with those zero (the same bits, signed zeros included).
    dY[c][0] = dc[c][0] + hD[0] * (db1[c] - (q[P_Kr] * dKrY[0] + q[P_Kpa] * st.y[0])) + law(q, 0);
    for (int k = 1; k < n; ++k)
      dY[c][k] = dc[c][k] + hD[k] * (0.0 - (q[P_Kr] * dKrY[k] + 0.0)) + law(q, k);
  }
  rtb_tridiag_subst_many(n, l.lo, l.piv, l.w, m, dY);
}

// Transpose of stage_jvp: given Ybar, add to cbar and pbar; returns b1bar.
double stage_vjp(const rtb_params &p, const StageView &st, const double *Ybar, double *cbar,
                 double *pbar) {
  const int n = p.cells;
  double lo[RTB_MAX_CELLS], di[RTB_MAX_CELLS], up[RTB_MAX_CELLS], mu[RTB_MAX_CELLS] = {0},
      work[RTB_MAX_CELLS];
  StageLin own;
  if (!st.lin) own = stage_lin(p, st);
  const StageLin &l = st.lin ? *st.lin : own;
  stage_matrix(p, st, l.D, true, lo, di, up);
  for (int k = 0; k < n; ++k) mu[k] = Ybar[k];
  rtb_tridiag_solve(n, lo, di, up, mu, work);
  for (int k = 0; k < n; ++k) {
    cbar[k] += mu[k];
    pbar[P_Kr] -= st.h * l.D[k] * mu[k] * dK_dKr_row(st, k, n);
    pbar[P_C0] += st.h * mu[k] * l.dv_dC0[k];
    pbar[P_alpha] += st.h * mu[k] * l.dv_dalpha[k];
    pbar[P_fric_asym] += st.h * mu[k] * l.dv_dfa[k];
  }
  pbar[P_Kpa] -= st.h * l.D[0] * mu[0] * st.y[0];
  return st.h * l.D[0] * mu[0];
}

// ------------------------------------------------------------- branches
// The Maxwell branch and the spectrum's, linearized by bushing_force.h's own
// update (rtb_maxwell_step); branch index -1 is the Maxwell branch.
struct Branches {
  rtb_spectrum sp;
  rtb_maxwell_lin mx;                       // Maxwell branch (zeros when off)
  rtb_maxwell_lin s[RTB_MAX_BRANCHES];      // spectrum branches
};
Branches branches_lin(const StepView &v) {
  Branches b;
  std::memset(&b, 0, sizeof b);
  const rtb_params &p = *v.p;
  rtb_spectrum_layout(&p, &b.sp);
  if (p.maxwell_tau > 0.0) rtb_maxwell_step(p.maxwell_tau, v.dt, v.xb_old, v.xb_new, v.z_old, &b.mx);
  for (int j = 0; j < b.sp.M; ++j)
    rtb_maxwell_step(b.sp.tau[j], v.dt, v.xb_old, v.xb_new, v.zs_old[j], &b.s[j]);
  return b;
}

// Partial derivatives of the force at fixed states (bushing_force.h, plus
// inertia), mapped onto the parameter ids.
struct ForceLin {
  rtb_force_lin f;
  double g[P_COUNT] = {0};  // dF/dp
};
ForceLin force_lin(const StepView &v, const rtb_spectrum &sp, bool with_inertia) {
  const rtb_params &p = *v.p;
  ForceLin L;
  rtb_force_eval(&p, v.xb_new, v.xb_old, v.xbmax_old, v.y_new[0], v.z_new, v.zs_new, &sp, v.dt,
                 &L.f);
  const rtb_force_lin &f = L.f;
  L.g[P_K0] = f.d_K0;
  L.g[P_Kpa] = f.d_Kpa;
  L.g[P_k2] = f.d_k2;
  L.g[P_k3] = f.d_k3;
  L.g[P_k_asym] = f.d_k_asym;
  L.g[P_maxwell_k] = f.d_maxwell_k;
  L.g[P_viscous_c] = f.d_viscous_c;
  L.g[P_mullins] = f.d_mullins;
  L.g[P_mullins_width] = f.d_mullins_width;
  L.g[P_sat_force] = f.d_sat_force;
  L.g[P_sat_disp] = f.d_sat_disp;
  L.g[P_spec_k] = f.d_spec_k;
  L.g[P_spec_exp] = f.d_spec_exp;
  L.g[P_relax_width] = f.d_relax_width;
  if (with_inertia) L.g[P_mass] = v.ax_new;
  return L;
}

// ------------------------------------------------------------- C and Fo
// The stages of the state map C for m directions (column c: d[c], dp[c] and
// the bushing displacement's own tangent dxb[c]) into dn[c].
void stages_jvp(const StepView &v, int m, const StateDual *const *d, const double *const *dp,
                const double *dxb, StateDual *const *dn) {
  const rtb_params &p = *v.p;
  const int n = p.cells;
  const double *dc[kMaxColumns];
  double *dy[kMaxColumns], db[kMaxColumns];
  for (int c = 0; c < m; ++c) dc[c] = d[c]->y, dy[c] = dn[c]->y;
  if (rtb_integrator_stages(&p) == 1) {
    for (int c = 0; c < m; ++c) db[c] = dp[c][P_Kpa] * v.xb_new + p.Kpa * dxb[c];
    stage_jvp(p, v.st[0], m, dc, db, dp, dy);
    return;
  }
  const double xg = v.xb_old + kGamma * (v.xb_new - v.xb_old);
  double Y1[kMaxColumns][RTB_MAX_CELLS], c2[kMaxColumns][RTB_MAX_CELLS];
  double *y1[kMaxColumns];
  const double *c2p[kMaxColumns];
  for (int c = 0; c < m; ++c) {
    const double dxg = d[c]->xb + kGamma * (dxb[c] - d[c]->xb);
    db[c] = dp[c][P_Kpa] * xg + p.Kpa * dxg;
    y1[c] = Y1[c];
  }
  stage_jvp(p, v.st[0], m, dc, db, dp, y1);
  for (int c = 0; c < m; ++c) {
    for (int k = 0; k < n; ++k) c2[c][k] = d[c]->y[k] + kRho * (Y1[c][k] - d[c]->y[k]);
    db[c] = dp[c][P_Kpa] * v.xb_new + p.Kpa * dxb[c];
    c2p[c] = c2[c];
  }
  stage_jvp(p, v.st[1], m, c2p, db, dp, dy);
}

// The rest of C: the Maxwell and spectrum branches, xb, the Mullins memory.
void memory_jvp(const StepView &v, const Branches &br, const StateDual &d, const double *dp,
                double dxb, StateDual &dn) {
  const rtb_params &p = *v.p;
  const rtb_maxwell_lin &mx = br.mx;
  dn.z = p.maxwell_tau > 0.0 ? mx.d_z_old * d.z + mx.d_tau * dp[P_maxwell_tau] +
                                   mx.d_xb_new * dxb + mx.d_xb_old * d.xb
                             : d.z;
  for (int j = 0; j < br.sp.M; ++j)
    dn.zs[j] = br.s[j].d_z_old * d.zs[j] + br.s[j].d_xb_new * dxb + br.s[j].d_xb_old * d.xb;
  dn.xb = dxb;
  dn.m = std::fabs(v.xb_new) > v.xbmax_old ? (v.xb_new > 0 ? dxb : -dxb) : d.m;
}

// State map C for m directions (dn[c] distinct from d[c]).
void chain_jvp(const StepView &v, const Branches &br, int m, const StateDual *const *d,
               const double *const *dp, const double *dxb, StateDual *const *dn) {
  if (v.p->model == RTB_MODEL_RT) stages_jvp(v, m, d, dp, dxb, dn);
  for (int c = 0; c < m; ++c) memory_jvp(v, br, *d[c], dp[c], dxb[c], *dn[c]);
}

// State map C with the bushing displacement's own tangent dxb given.
void chain_jvp(const StepView &v, const Branches &br, const StateDual &d, const double *dp,
               double dxb, StateDual &dn) {
  const StateDual *pd = &d;
  StateDual *pn = &dn;
  chain_jvp(v, br, 1, &pd, &dp, &dxb, &pn);
}

// Transpose of chain_jvp; *xbbar receives the cotangent of xb_new.
void chain_vjp(const StepView &v, const Branches &br, const StateDual &bn, StateDual &bo,
               double *pbar, double *xbbar) {
  const rtb_params &p = *v.p;
  const int n = p.cells;
  double dxb_bar = bn.xb;
  if (std::fabs(v.xb_new) > v.xbmax_old) dxb_bar += (v.xb_new > 0 ? bn.m : -bn.m);
  else bo.m += bn.m;
  if (p.maxwell_tau > 0.0) {
    bo.z += br.mx.d_z_old * bn.z;
    pbar[P_maxwell_tau] += br.mx.d_tau * bn.z;
    dxb_bar += br.mx.d_xb_new * bn.z;
    bo.xb += br.mx.d_xb_old * bn.z;
  } else {
    bo.z += bn.z;
  }
  for (int j = 0; j < br.sp.M; ++j) {
    bo.zs[j] += br.s[j].d_z_old * bn.zs[j];
    dxb_bar += br.s[j].d_xb_new * bn.zs[j];
    bo.xb += br.s[j].d_xb_old * bn.zs[j];
  }
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

// dF/d(memory), bushing_force.h's: y1 -> d_y1, z -> d_z, z_j -> d_z_spec w_j.
double force_jvp(const ForceLin &L, const Branches &br, const StateDual &d, const StateDual &dn,
                 const double *dp) {
  double dF = L.f.d_y1 * dn.y[0] + L.f.d_z * dn.z + L.f.d_xb * dn.xb + L.f.d_xb_old * d.xb +
              L.f.d_xbmax * d.m;
  for (int j = 0; j < br.sp.M; ++j) dF += L.f.d_z_spec * br.sp.w[j] * dn.zs[j];
  for (int i = 0; i < P_COUNT; ++i) dF += L.g[i] * dp[i];
  return dF;
}

void force_vjp(const StepView &v, const Branches &br, double Fbar, StateDual &bo, StateDual &bn,
               double *pbar, bool with_inertia) {
  const ForceLin L = force_lin(v, br.sp, with_inertia);
  bn.y[0] += L.f.d_y1 * Fbar;
  bn.z += L.f.d_z * Fbar;
  for (int j = 0; j < br.sp.M; ++j) bn.zs[j] += L.f.d_z_spec * br.sp.w[j] * Fbar;
  bn.xb += L.f.d_xb * Fbar;
  bo.xb += L.f.d_xb_old * Fbar;
  bo.m += L.f.d_xbmax * Fbar;
  for (int i = 0; i < P_COUNT; ++i) pbar[i] += L.g[i] * Fbar;
}

// ------------------------------------------------------------- clearance B
// Phases (rtb_state.contact): 2 xb = x (data); +-1 xb = x -+ g/2; 3 held,
// xb = xb_old; 0 floating, F_bushing(xb_new) = 0, so dxb = -F_s / F_xb with
// F_s the bushing force's tangent at fixed xb_new and F_xb its total xb
// derivative.
double free_phase_stiffness(const StepView &v, const Branches &br) {
  StateDual z, t;
  z.clear();
  t.clear();
  const double zero[P_COUNT] = {0};
  chain_jvp(v, br, z, zero, 1.0, t);
  return force_jvp(force_lin(v, br.sp, false), br, z, t, zero);
}

double clearance_jvp(const StepView &v, const Branches &br, const StateDual &d, const double *dp) {
  if (v.contact == 2) return 0.0;
  if (v.contact == 3) return d.xb;
  if (v.contact != 0) return -0.5 * v.contact * dp[P_backlash];
  StateDual t;
  t.clear();
  chain_jvp(v, br, d, dp, 0.0, t);
  return -force_jvp(force_lin(v, br.sp, false), br, d, t, dp) / free_phase_stiffness(v, br);
}

void clearance_vjp(const StepView &v, const Branches &br, double xbbar, StateDual &bo,
                   double *pbar) {
  if (v.contact == 2 || xbbar == 0.0) return;
  if (v.contact == 3) {
    bo.xb += xbbar;
    return;
  }
  if (v.contact != 0) {
    pbar[P_backlash] += -0.5 * v.contact * xbbar;
    return;
  }
  const double seed = -xbbar / free_phase_stiffness(v, br);
  StateDual bn;
  bn.clear();
  force_vjp(v, br, seed, bo, bn, pbar, false);
  bn.xb = 0.0;  // xb_new is held fixed in F_s
  double ignored;
  chain_vjp(v, br, bn, bo, pbar, &ignored);
}

// One step's tangent for m directions with the step's linearization given
// (br, L: the same for every direction); d_new[c] distinct from d_old[c].
void step_jvp_at(const StepView &v, const Branches &br, const ForceLin &L, int m,
                 const StateDual *const *d_old, const double *const *dp, StateDual *const *d_new,
                 double *dF) {
  double dxb[kMaxColumns];
  for (int c = 0; c < m; ++c) {
    // chain_jvp writes every entry of the state it uses but the cells of a
    // model without stages (STS: y carries no tangent); the capacity beyond
    // (cells, branches) is left as it is (step_jvp_columns).
    if (v.p->model != RTB_MODEL_RT)
      std::memset(d_new[c]->y, 0, sizeof(double) * (size_t)v.p->cells);
    dxb[c] = clearance_jvp(v, br, *d_old[c], dp[c]);
  }
  chain_jvp(v, br, m, d_old, dp, dxb, d_new);
  for (int c = 0; c < m; ++c) dF[c] = force_jvp(L, br, *d_old[c], *d_new[c], dp[c]);
}

}  // namespace

void step_precompute(StepView &v, StageLin lin[2]) {
  const rtb_params &p = *v.p;
  if (p.model != RTB_MODEL_RT) return;
  for (int s = 0; s < rtb_integrator_stages(&p); ++s) {
    lin[s] = stage_lin_factored(p, v.st[s]);
    v.st[s].lin = &lin[s];
  }
}

double step_jvp(const StepView &v, const StateDual &d_old, const double *dp, StateDual &d_new) {
  const Branches br = branches_lin(v);
  const StateDual *po = &d_old;
  StateDual *pn = &d_new;
  double dF = 0.0;
  d_new.clear();
  step_jvp_at(v, br, force_lin(v, br.sp, true), 1, &po, &dp, &pn, &dF);
  return dF;
}

void step_jvp_columns(const StepView &v, std::vector<StateDual> &d,
                      const std::vector<std::array<double, P_COUNT>> &dp, double *dF) {
  const Branches br = branches_lin(v);
  const ForceLin L = force_lin(v, br.sp, true);
  // Only the entries the model uses are written and copied back (the
  // cells, the branches, z, xb, m): the whole capacity, cleared and copied
  // for every column and step, was 5% of a diagnosis (perf, maxwell case).
  const int n = v.p->cells, M = br.sp.M;
  StateDual dn[kMaxColumns];
  const StateDual *po[kMaxColumns];
  StateDual *pn[kMaxColumns];
  const double *pp[kMaxColumns];
  for (size_t c0 = 0; c0 < d.size(); c0 += kMaxColumns) {
    const int m = (int)std::min<size_t>(kMaxColumns, d.size() - c0);
    for (int c = 0; c < m; ++c) po[c] = &d[c0 + c], pn[c] = &dn[c], pp[c] = dp[c0 + c].data();
    step_jvp_at(v, br, L, m, po, pp, pn, dF + c0);
    for (int c = 0; c < m; ++c) d[c0 + c].assign_used(dn[c], n, M);
  }
}

void step_vjp(const StepView &v, const StateDual &bar_new, double Fbar, StateDual &bar_old,
              double *pbar) {
  const Branches br = branches_lin(v);
  StateDual bn = bar_new;
  force_vjp(v, br, Fbar, bar_old, bn, pbar, true);
  double xbbar = 0.0;
  chain_vjp(v, br, bn, bar_old, pbar, &xbbar);
  clearance_vjp(v, br, xbbar, bar_old, pbar);
}

}  // namespace rtb
