// misfit_gradient.cpp -- adjoint sweep, tangent sweeps and dot-product test
// over whole records, built from the per-step linearization.
#include "adjoint/misfit_gradient.h"

#include <cmath>
#include <random>

#include "adjoint/step_linearization.h"
#include "model/forward.h"

namespace rtb {

double MisfitValue::error() const { return J0 > 0.0 ? std::sqrt(J / J0) : INFINITY; }

std::vector<double> quadrature_weights(const Record &rec, double fit_from) {
  const size_t n = rec.t.size();
  std::vector<double> w(n, 0.0);
  const double t_start = rec.t[0] + fit_from;
  for (size_t j = 0; j < n; ++j) {
    const double left = j > 0 ? rec.t[j] - rec.t[j - 1] : 0.0;
    const double right = j + 1 < n ? rec.t[j + 1] - rec.t[j] : 0.0;
    w[j] = rec.t[j] >= t_start ? 0.5 * (left + right) * rec.weight : 0.0;
  }
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
  MisfitValue m;
  for (const Record &rec : recs) {
    const DriveGrid g = make_drive_grid(rec, opt.sim);
    const Trajectory tr = run_forward(p, g, want_grad, opt.sim.tol);
    ++m.forward_solves;
    m.forward_steps += (long)g.x.size() - 1;
    m.newton_iterations += tr.newton_iterations;
    const std::vector<double> w = quadrature_weights(rec, opt.fit_from);
    std::vector<double> Fbar(g.x.size(), 0.0);
    KahanSum Js, J0s;
    for (size_t j = 0; j < rec.F.size(); ++j) {
      const double res = tr.force[g.first_sample + j] - rec.F[j];
      Js.add(0.5 * w[j] * res * res);
      J0s.add(0.5 * w[j] * rec.F[j] * rec.F[j]);
      Fbar[g.first_sample + j] = w[j] * res;
    }
    const double J = Js.s, J0 = J0s.s;
    m.J += J;
    m.J0 += J0;
    m.J_rec.push_back(J);
    m.J0_rec.push_back(J0);
    if (!want_grad) continue;
    // Backward sweep: the adjoint of the discrete stepper, last step first.
    double *pbar = m.grad.data();
    StateDual bar, bar_prev;
    bar.clear();
    for (size_t i = g.x.size() - 1; i >= 1; --i) {
      bar_prev.clear();
      step_vjp(tr.step(p, g, i), bar, Fbar[i], bar_prev, pbar);
      bar = bar_prev;
    }
    ++m.adjoint_solves;
    // Step 0 is the model at rest at x = 0 (the grid ramps in otherwise):
    // its force is 0 whatever p, so it adds nothing to the gradient.
  }
  add_tikhonov(p, opt, m);
  return m;
}

void record_sensitivities(const rtb_params &p, const Record &rec, const SimOptions &sim,
                          const std::vector<ParamId> &free, Eigen::VectorXd &F,
                          Eigen::MatrixXd *jac) {
  const DriveGrid g = make_drive_grid(rec, sim);
  const Trajectory tr = run_forward(p, g, jac != nullptr, sim.tol);
  const Eigen::Index n = (Eigen::Index)rec.F.size();
  F = Eigen::Map<const Eigen::VectorXd>(tr.force.data() + g.first_sample, n);
  if (!jac) return;
  jac->setZero(n, (Eigen::Index)free.size());
  StateDual d, dn;
  for (size_t c = 0; c < free.size(); ++c) {
    double dp[P_COUNT] = {0};
    dp[free[c]] = 1.0;
    d.clear();
    for (size_t i = 1; i < g.x.size(); ++i) {
      dn.clear();
      const double dF = step_jvp(tr.step(p, g, i), d, dp, dn);
      if ((int)i >= g.first_sample) (*jac)((Eigen::Index)i - g.first_sample, (Eigen::Index)c) = dF;
      d = dn;
    }
  }
}

void residual_jacobian(const rtb_params &p, const std::vector<Record> &recs,
                       const MisfitOptions &opt, const std::vector<ParamId> &free,
                       Eigen::VectorXd &r, Eigen::MatrixXd *jac) {
  std::vector<double> rv;
  std::vector<Eigen::RowVectorXd> rows;
  for (const Record &rec : recs) {
    Eigen::VectorXd F;
    Eigen::MatrixXd J;
    record_sensitivities(p, rec, opt.sim, free, F, jac ? &J : nullptr);
    const std::vector<double> w = quadrature_weights(rec, opt.fit_from);
    for (size_t j = 0; j < rec.F.size(); ++j) {
      if (!(w[j] > 0.0)) continue;
      const double s = std::sqrt(w[j]);
      rv.push_back(s * (F[(Eigen::Index)j] - rec.F[j]));
      if (jac) rows.push_back(s * J.row((Eigen::Index)j));
    }
  }
  r = Eigen::Map<Eigen::VectorXd>(rv.data(), (Eigen::Index)rv.size());
  if (jac) {
    jac->resize((Eigen::Index)rv.size(), (Eigen::Index)free.size());
    for (size_t k = 0; k < rows.size(); ++k) jac->row((Eigen::Index)k) = rows[k];
  }
}

double dot_product_test(const rtb_params &p, const Record &rec, const SimOptions &sim,
                        unsigned seed) {
  const DriveGrid g = make_drive_grid(rec, sim);
  const Trajectory tr = run_forward(p, g, true, sim.tol);
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
