// misfit_gradient.cpp -- adjoint sweep, tangent sweeps and dot-product test
// over whole records, built from the per-step linearization.
#include "adjoint/misfit_gradient.h"

#include <array>
#include <cmath>
#include <cstring>
#include <random>

#include "adjoint/step_linearization.h"
#include "model/forward.h"
#include "model/misfit_norms.h"
#include "model/parallel_for.h"

namespace rtb {

double MisfitValue::error() const { return J0 > 0.0 ? std::sqrt(J / J0) : INFINITY; }

std::vector<double> quadrature_weights(const Record &rec, double fit_from) {
  std::vector<double> w = trapezoid_weights(rec.t);
  const double t_start = rec.t[0] + fit_from;
  for (size_t j = 0; j < w.size(); ++j) w[j] = rec.t[j] >= t_start ? w[j] * rec.weight : 0.0;
  if (!rec.masked.empty())
    for (size_t j = 0; j < w.size(); ++j)
      if (rec.masked[j]) w[j] = 0.0;
  return w;
}

namespace {

// Compensated (Kahan) sum: the misfit is a sum of 1e4..1e6 terms and finite
// differences of it (gradcheck) see its rounding directly.
struct KahanSum {
  double s = 0.0, c = 0.0;
  void add(double v) {
    const double y = v - c, t = s + y;
    c = (t - s) - y;
    s = t;
  }
};

void add_tikhonov(const rtb_params &p, const MisfitOptions &opt, MisfitValue &m) {
  for (int i = 0; i < P_COUNT; ++i) {
    const double R = opt.R[i];
    if (R == 0.0) continue;
    const double d = param_get(p, ParamId(i)) - opt.p0[i];
    m.J += 0.5 * R * R * d * d;
    m.grad[i] += R * R * d;
  }
}

}  // namespace

MisfitValue misfit(const rtb_params &p, const std::vector<Record> &recs,
                   const MisfitOptions &opt, bool want_grad) {
  struct Part {
    double J = 0, J0 = 0;
    std::array<double, P_COUNT> grad{};
    long steps = 0, iters = 0;
  };
  std::vector<Part> parts(recs.size());
  parallel_for(recs.size(), default_threads(), [&](size_t k) {
    const Record &rec = recs[k];
    Part &pt = parts[k];
    const DriveGrid g = make_drive_grid(rec, opt.sim);
    const Trajectory tr = run_forward(p, g, want_grad, fit_tol(opt.sim));
    pt.steps = (long)g.x.size() - 1;
    pt.iters = tr.newton_iterations;
    const std::vector<double> w = quadrature_weights(rec, opt.fit_from);
    std::vector<double> Fbar(g.x.size(), 0.0);
    KahanSum Js, J0s;
    for (size_t j = 0; j < rec.F.size(); ++j) {
      const double res = tr.force[g.first_sample + j] - rec.F[j];
      Js.add(0.5 * w[j] * res * res);
      J0s.add(0.5 * w[j] * rec.F[j] * rec.F[j]);
      Fbar[g.first_sample + j] = w[j] * res;
    }
    pt.J = Js.s;
    pt.J0 = J0s.s;
    if (!want_grad) return;
    // Backward sweep: the adjoint of the discrete stepper, last step first.
    // Step 0 is the model at rest at x = 0 (the grid ramps in, and holds,
    // otherwise): its force is 0 whatever p, so it adds nothing to the gradient.
    StateDual bar, bar_prev;
    bar.clear();
    for (size_t i = g.x.size() - 1; i >= 1; --i) {
      bar_prev.clear();
      step_vjp(tr.step(p, g, i), bar, Fbar[i], bar_prev, pt.grad.data());
      bar = bar_prev;
    }
  });
  MisfitValue m;
  for (const Part &pt : parts) {
    m.J += pt.J;
    m.J0 += pt.J0;
    m.J_rec.push_back(pt.J);
    m.J0_rec.push_back(pt.J0);
    for (int i = 0; i < P_COUNT; ++i) m.grad[i] += pt.grad[i];
    m.forward_steps += pt.steps;
    m.newton_iterations += pt.iters;
    ++m.forward_solves;
    if (want_grad) ++m.adjoint_solves;
  }
  add_tikhonov(p, opt, m);
  return m;
}

SensitivityCache::Entry &SensitivityCache::entry(const Record *rec) {
  for (auto &e : entries_)
    if (e.first == rec) return e.second;
  entries_.emplace_back(rec, Entry());
  return entries_.back().second;
}

void SensitivityCache::prepare(const std::vector<Record> &recs) {
  for (const Record &r : recs) entry(&r);
}

void record_sensitivities(const rtb_params &p, const Record &rec, const SimOptions &sim,
                          const std::vector<ParamId> &free, Eigen::VectorXd &F,
                          Eigen::MatrixXd *jac, SensitivityCache *cache) {
  DriveGrid gl;
  Trajectory tl;
  const DriveGrid *gp = &gl;
  const Trajectory *tp = &tl;
  if (cache) {
    SensitivityCache::Entry &e = cache->entry(&rec);
    const bool hit = e.valid && std::memcmp(&e.p, &p, sizeof p) == 0 && e.tol == fit_tol(sim) &&
                     e.ramp == sim.ramp_time && e.start == sim.start;
    if (!hit) {
      e.grid = make_drive_grid(rec, sim);
      e.tr = run_forward(p, e.grid, true, fit_tol(sim));
      e.p = p;
      e.tol = fit_tol(sim);
      e.ramp = sim.ramp_time;
      e.start = sim.start;
      e.valid = true;
    }
    gp = &e.grid;
    tp = &e.tr;
  } else {
    gl = make_drive_grid(rec, sim);
    tl = run_forward(p, gl, jac != nullptr, fit_tol(sim));
  }
  const DriveGrid &g = *gp;
  const Trajectory &tr = *tp;
  const Eigen::Index n = (Eigen::Index)rec.F.size();
  F = Eigen::Map<const Eigen::VectorXd>(tr.force.data() + g.first_sample, n);
  if (!jac) return;
  const size_t nc = free.size();
  jac->setZero(n, (Eigen::Index)nc);
  // All columns advance together, step by step, so that the step's
  // linearization (dashpot partials: powers and logs) is computed once.
  std::vector<StateDual> d(nc);
  std::vector<std::array<double, P_COUNT>> dp(nc);
  for (size_t c = 0; c < nc; ++c) {
    d[c].clear();
    dp[c].fill(0.0);
    dp[c][free[c]] = 1.0;
  }
  StageLin lin[2];
  std::vector<double> dF(nc);
  for (size_t i = 1; i < g.x.size(); ++i) {
    StepView v = tr.step(p, g, i);
    step_precompute(v, lin);
    step_jvp_columns(v, d, dp, dF.data());
    if ((int)i >= g.first_sample)
      for (size_t c = 0; c < nc; ++c)
        (*jac)((Eigen::Index)i - g.first_sample, (Eigen::Index)c) = dF[c];
  }
}

void residual_jacobian(const rtb_params &p, const std::vector<Record> &recs,
                       const MisfitOptions &opt, const std::vector<ParamId> &free,
                       Eigen::VectorXd &r, Eigen::MatrixXd *jac, SensitivityCache *cache) {
  // Records in parallel, then stacked in order.
  std::vector<Eigen::VectorXd> Fs(recs.size());
  std::vector<Eigen::MatrixXd> Js(recs.size());
  if (cache) cache->prepare(recs);
  parallel_for(recs.size(), default_threads(), [&](size_t k) {
    record_sensitivities(p, recs[k], opt.sim, free, Fs[k], jac ? &Js[k] : nullptr, cache);
  });
  Eigen::Index total = 0;
  std::vector<std::vector<double>> ws(recs.size());
  for (size_t k = 0; k < recs.size(); ++k) {
    ws[k] = quadrature_weights(recs[k], opt.fit_from);
    for (double w : ws[k]) total += w > 0.0;
  }
  r.resize(total);
  if (jac) jac->resize(total, (Eigen::Index)free.size());
  Eigen::Index row = 0;
  for (size_t k = 0; k < recs.size(); ++k)
    for (size_t j = 0; j < recs[k].F.size(); ++j) {
      const double w = ws[k][j];
      if (!(w > 0.0)) continue;
      const double s = std::sqrt(w);
      r[row] = s * (Fs[k][(Eigen::Index)j] - recs[k].F[j]);
      if (jac) jac->row(row) = s * Js[k].row((Eigen::Index)j);
      ++row;
    }
}

double dot_product_test(const rtb_params &p, const Record &rec, const SimOptions &sim,
                        unsigned seed) {
  const DriveGrid g = make_drive_grid(rec, sim);
  const Trajectory tr = run_forward(p, g, true, fit_tol(sim));
  const size_t n = g.x.size();
  const int N = p.cells;
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> nd(0.0, 1.0);
  // Parameter directions scaled to the parameters so every term matters.
  double dp[P_COUNT] = {0}, pbar[P_COUNT] = {0};
  for (int i = 0; i < P_COUNT; ++i) {
    const double v = param_get(p, ParamId(i));
    dp[i] = nd(rng) * (v != 0.0 ? std::fabs(v) : 1.0) * 1e-3;
  }
  if (!(p.maxwell_tau > 0.0)) dp[P_maxwell_tau] = 0.0;
  // Random sources a_i on every state entry and random cotangents.
  auto fill = [&](StateDual &s, double scale) {
    s.clear();
    for (int k = 0; k < N; ++k) s.y[k] = nd(rng) * scale;
    s.z = nd(rng) * scale;
    s.xb = p.backlash > 0.0 ? nd(rng) * scale : 0.0;  // xb = x (data) otherwise
    s.m = nd(rng) * scale;
  };
  auto dot = [&](const StateDual &a, const StateDual &b) {
    double s = a.z * b.z + a.xb * b.xb + a.m * b.m;
    for (int k = 0; k < N; ++k) s += a.y[k] * b.y[k];
    return s;
  };
  std::vector<StateDual> a(n), ybar(n), abar(n);
  std::vector<double> Fbar(n);
  for (size_t i = 0; i < n; ++i) {
    fill(a[i], 1e-3);
    fill(ybar[i], 1.0);
    Fbar[i] = nd(rng);
  }
  // Tangent sweep: d_i = L_i(d_{i-1}, dp) + a_i with output dF_i.
  StateDual d = a[0], dn;
  double lhs = dot(ybar[0], d);
  for (size_t i = 1; i < n; ++i) {
    dn.clear();
    lhs += Fbar[i] * step_jvp(tr.step(p, g, i), d, dp, dn);
    dn.xb += a[i].xb;
    for (int k = 0; k < N; ++k) dn.y[k] += a[i].y[k];
    dn.z += a[i].z;
    dn.m += a[i].m;
    lhs += dot(ybar[i], dn);
    d = dn;
  }
  // Adjoint sweep.
  StateDual bar = ybar[n - 1], prev;
  for (size_t i = n - 1; i >= 1; --i) {
    abar[i] = bar;
    prev = ybar[i - 1];
    step_vjp(tr.step(p, g, i), bar, Fbar[i], prev, pbar);
    bar = prev;
  }
  abar[0] = bar;
  double rhs = 0.0;
  for (size_t i = 0; i < n; ++i) rhs += dot(abar[i], a[i]);
  for (int i = 0; i < P_COUNT; ++i) rhs += pbar[i] * dp[i];
  return std::fabs(lhs - rhs) / std::fmax(std::fabs(lhs), std::fabs(rhs));
}

}  // namespace rtb
