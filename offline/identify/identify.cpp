// identify.cpp -- glue between the misfit/adjoint and the optimizers.
#include "identify/identify.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "identify/optimizer.h"

namespace rtb {

Method parse_method(const std::string &s) {
  if (s == "trust-region" || s == "tr") return Method::TrustRegion;
  if (s == "bfgs" || s == "line-search") return Method::Bfgs;
  throw InputError("--method must be 'bfgs' or 'trust-region', got '" + s + "'");
}

const char *method_name(Method m) { return m == Method::Bfgs ? "bfgs" : "trust-region"; }

IdentifyResult identify(const std::vector<Record> &recs, const rtb_params &start,
                        const IdentifyOptions &opt) {
  const auto t0 = std::chrono::steady_clock::now();
  IdentifyResult out;
  out.start = start;
  out.method = opt.method;
  const ParamTransform tf(opt.free, start, stiffness_cap_for(recs));
  const MisfitValue m0 = misfit(start, recs, opt.misfit, false);
  const double J0 = m0.J0;
  out.error_start = m0.error();
  int fwd = 1, adj = 0, tan = 0;

  SensitivityCache cache;  // the accepted trial's forward run serves its Jacobian
  // f(theta) = J / J0: dimensionless, so tolerances mean the same for any units.
  Objective obj;
  obj.value_grad = [&](const Eigen::VectorXd &th, Eigen::VectorXd *grad) {
    const rtb_params p = tf.to_params(th, start);
    if (rtb_params_validate(&p) != RTB_OK) return (double)INFINITY;
    MisfitValue m;
    try {
      m = misfit(p, recs, opt.misfit, grad != nullptr);
    } catch (const std::runtime_error &) {
      return (double)INFINITY;
    }
    ++fwd;
    if (grad) {
      ++adj;
      *grad = tf.theta_gradient(m.grad, th, start) / J0;
    }
    return m.J / J0;
  };
  obj.residuals = [&](const Eigen::VectorXd &th, Eigen::VectorXd &r, Eigen::MatrixXd *jac) {
    const rtb_params p = tf.to_params(th, start);
    try {
      if (rtb_params_validate(&p) != RTB_OK) throw std::runtime_error("invalid");
      residual_jacobian(p, recs, opt.misfit, tf.free, r, jac, &cache);
    } catch (const std::runtime_error &) {
      r = Eigen::VectorXd::Constant(r.size() > 0 ? r.size() : 1, INFINITY);
      return;
    }
    ++fwd;
    const double s = 1.0 / std::sqrt(J0);
    r *= s;
    const Eigen::MatrixXd dp = tf.jacobian(th, start);
    if (jac) {
      tan += (int)tf.free.size();
      *jac = (*jac) * dp * s;
    }
    // Tikhonov rows R (p - p0), eq. (11).
    for (size_t i = 0; i < tf.free.size(); ++i) {
      const ParamId id = tf.free[i];
      if (opt.misfit.R[id] == 0.0) continue;
      r.conservativeResize(r.size() + 1);
      r[r.size() - 1] = s * opt.misfit.R[id] * (param_get(p, id) - opt.misfit.p0[id]);
      if (jac) {
        jac->conservativeResize(jac->rows() + 1, Eigen::NoChange);
        jac->row(jac->rows() - 1) = s * opt.misfit.R[id] * dp.row((Eigen::Index)i);
      }
    }
  };

  OptOptions oo;
  oo.max_iter = opt.max_iter;
  oo.chi2_tol = opt.chi2_tol;
  oo.lower = tf.lower();
  oo.upper = tf.upper();
  if (!opt.quiet)
    oo.progress = [&](int it, double f, double gn) {
      std::fprintf(stderr, "  iter %3d  error %.6e  |grad| %.3e\n", it, std::sqrt(2.0 * f), gn);
    };
  // value_grad returns J/J0 while residuals give 1/2 |r|^2 = J/J0 as well.
  const Eigen::VectorXd th0 = tf.to_theta(start);
  const RunFrom run = [&](const Eigen::VectorXd &t, const OptOptions &o) {
    return opt.method == Method::Bfgs ? minimize_bfgs(obj, t, o) : minimize_trust_region(obj, t, o);
  };
  OptResult r = run(th0, oo);
  // J >= 0: a fit at rounding level (f = J/J0) is the global minimum already
  // (restart_sloppy skips it). A run that stopped at its iteration limit is
  // still descending (a valley towards a limit model, e.g. rigid cells
  // absorbing an inertia force): restarts around it would only continue the
  // crawl, and restart_sloppy skips an unconverged run too.
  out.restart_improved = restart_sloppy(obj, run, oo, opt.restarts, r);
  out.params = tf.to_params(r.theta, start);
  const MisfitValue m = misfit(out.params, recs, opt.misfit, false);
  ++fwd;
  out.J = m.J;
  out.J0 = m.J0;
  out.error = m.error();
  for (size_t i = 0; i < m.J_rec.size(); ++i)
    out.error_per_record.push_back(m.J0_rec[i] > 0 ? std::sqrt(m.J_rec[i] / m.J0_rec[i]) : NAN);
  out.iterations = r.iterations;
  out.converged = r.converged;
  out.message = r.message;
  out.uncertainty = estimate_uncertainty(out.params, recs, opt.misfit, opt.free);
  out.forward_solves = fwd + 1;
  out.adjoint_solves = adj;
  out.tangent_sweeps = tan + (int)opt.free.size();
  out.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return out;
}

Uncertainty estimate_uncertainty(const rtb_params &p, const std::vector<Record> &recs,
                                 const MisfitOptions &opt, const std::vector<ParamId> &ids) {
  Uncertainty u;
  u.ids = ids;
  Eigen::VectorXd r;
  Eigen::MatrixXd Jw;
  residual_jacobian(p, recs, opt, ids, r, &Jw);
  std::vector<double> w;
  std::vector<int> group;
  row_groups(recs, opt.fit_from, w, group);
  if ((Eigen::Index)w.size() != r.size()) return u;
  const Eigen::Map<Eigen::VectorXd> wv(w.data(), r.size());
  u.valid = sandwich_covariance(r, Jw, wv, group, u.stddev, &u.correlation, &u.noise_sigma);
  return u;
}

void row_groups(const std::vector<Record> &recs, double fit_from, std::vector<double> &w,
                std::vector<int> &group) {
  w.clear();
  group.clear();
  for (size_t i = 0; i < recs.size(); ++i)
    for (double v : quadrature_weights(recs[i], fit_from))
      if (v > 0.0) {
        w.push_back(v);
        group.push_back((int)i);
      }
}

bool sandwich_covariance(const Eigen::VectorXd &r, const Eigen::MatrixXd &Jw,
                         const Eigen::VectorXd &w, const std::vector<int> &group,
                         Eigen::VectorXd &stddev, Eigen::MatrixXd *correlation,
                         double *noise_sigma) {
  // White noise of variance s_g^2 per sample in record g, weights w_j:
  //   Cov = A^-1 B A^-1,  A = sum w J_j J_j^T,  B = sum s_g^2 w^2 J_j J_j^T,
  // s_g^2 from record g's residuals with its share of the lost degrees of freedom.
  const Eigen::Index m = r.size(), n = Jw.cols();
  if (m <= n || n == 0 || (Eigen::Index)group.size() != m) return false;
  // Eigen's SVD leaves its rank undefined on non-finite input (a solve then
  // reads past its singular values): no figure rather than a crash.
  if (!r.allFinite() || !Jw.allFinite() || !w.allFinite()) return false;
  const int ng = 1 + *std::max_element(group.begin(), group.end());
  std::vector<double> ss(ng, 0.0), cnt(ng, 0.0);
  double sall = 0.0;
  for (Eigen::Index j = 0; j < m; ++j) {
    const double e2 = r[j] * r[j] / w[j];
    ss[group[j]] += e2;
    cnt[group[j]] += 1.0;
    sall += e2;
  }
  std::vector<double> s2(ng, 0.0);
  for (int g = 0; g < ng; ++g)
    if (cnt[g] > 0) s2[g] = ss[g] / std::max(1.0, cnt[g] * (1.0 - double(n) / double(m)));
  if (noise_sigma) *noise_sigma = std::sqrt(sall / double(m - n));
  // Scale columns to unit size so the inversion is well conditioned.
  const Eigen::VectorXd cs = Jw.colwise().norm().transpose().cwiseMax(1e-300);
  const Eigen::MatrixXd Js = Jw * cs.cwiseInverse().asDiagonal();
  Eigen::VectorXd d(m);
  for (Eigen::Index j = 0; j < m; ++j) d[j] = s2[group[j]] * w[j];
  // Parameters the data cannot determine at all (a stiffness driven to ~0 or
  // to its ceiling, a column identical to another) make A singular. Drop
  // them one at a time, by the null direction's largest component, and give
  // them an infinite standard deviation; the others are then conditional on
  // them (the only meaningful figure left).
  std::vector<Eigen::Index> keep(n);
  for (Eigen::Index i = 0; i < n; ++i) keep[i] = i;
  Eigen::MatrixXd Ck;
  while (!keep.empty()) {
    const Eigen::Index k = (Eigen::Index)keep.size();
    Eigen::MatrixXd Jk(m, k);
    for (Eigen::Index i = 0; i < k; ++i) Jk.col(i) = Js.col(keep[i]);
    const Eigen::MatrixXd A = Jk.transpose() * Jk;
    const Eigen::MatrixXd B = Jk.transpose() * d.asDiagonal() * Jk;
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
    const Eigen::VectorXd sv = svd.singularValues();
    if (sv[k - 1] > 1e-14 * sv[0]) {
      const Eigen::MatrixXd Ai = svd.solve(Eigen::MatrixXd::Identity(k, k));
      Ck = Ai * B * Ai;
      break;
    }
    Eigen::Index worst = 0;
    svd.matrixV().col(k - 1).cwiseAbs().maxCoeff(&worst);
    keep.erase(keep.begin() + worst);
  }
  if (keep.empty()) return false;
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index i = 0; i < n; ++i) C(i, i) = INFINITY;
  for (size_t a = 0; a < keep.size(); ++a)
    for (size_t b = 0; b < keep.size(); ++b)
      C(keep[a], keep[b]) = Ck((Eigen::Index)a, (Eigen::Index)b) / (cs[keep[a]] * cs[keep[b]]);
  stddev = C.diagonal().cwiseSqrt();
  if (correlation) {
    *correlation = Eigen::MatrixXd::Identity(n, n);
    for (size_t a = 0; a < keep.size(); ++a)
      for (size_t b = 0; b < keep.size(); ++b)
        (*correlation)(keep[a], keep[b]) = C(keep[a], keep[b]) / (stddev[keep[a]] * stddev[keep[b]]);
  }
  return true;
}

}  // namespace rtb
