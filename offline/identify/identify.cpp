// identify.cpp -- glue between the misfit/adjoint and the optimizers.
#include "identify/identify.h"

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
  const ParamTransform tf(opt.free, start);
  const MisfitValue m0 = misfit(start, recs, opt.misfit, false);
  const double J0 = m0.J0;
  out.error_start = m0.error();
  int fwd = 1, adj = 0, tan = 0;

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
      const Eigen::VectorXd d = tf.dp_dtheta(th);
      grad->resize(th.size());
      for (Eigen::Index i = 0; i < th.size(); ++i) (*grad)[i] = m.grad[tf.free[i]] * d[i] / J0;
    }
    return m.J / J0;
  };
  obj.residuals = [&](const Eigen::VectorXd &th, Eigen::VectorXd &r, Eigen::MatrixXd *jac) {
    const rtb_params p = tf.to_params(th, start);
    try {
      if (rtb_params_validate(&p) != RTB_OK) throw std::runtime_error("invalid");
      residual_jacobian(p, recs, opt.misfit, tf.free, r, jac);
    } catch (const std::runtime_error &) {
      r = Eigen::VectorXd::Constant(r.size() > 0 ? r.size() : 1, INFINITY);
      return;
    }
    ++fwd;
    const double s = 1.0 / std::sqrt(J0);
    r *= s;
    if (jac) {
      tan += (int)tf.free.size();
      *jac = (*jac) * tf.dp_dtheta(th).asDiagonal() * s;
    }
    // Tikhonov rows R (p - p0), eq. (11).
    for (size_t i = 0; i < tf.free.size(); ++i) {
      const ParamId id = tf.free[i];
      if (opt.misfit.R[id] == 0.0) continue;
      r.conservativeResize(r.size() + 1);
      r[r.size() - 1] = s * opt.misfit.R[id] * (param_get(p, id) - opt.misfit.p0[id]);
      if (jac) {
        jac->conservativeResize(jac->rows() + 1, Eigen::NoChange);
        jac->row(jac->rows() - 1).setZero();
        (*jac)(jac->rows() - 1, (Eigen::Index)i) = s * opt.misfit.R[id] * tf.dp_dtheta(th)[i];
      }
    }
  };

  OptOptions oo;
  oo.max_iter = opt.max_iter;
  if (!opt.quiet)
    oo.progress = [&](int it, double f, double gn) {
      std::fprintf(stderr, "  iter %3d  error %.6e  |grad| %.3e\n", it, std::sqrt(2.0 * f), gn);
    };
  // value_grad returns J/J0 while residuals give 1/2 |r|^2 = J/J0 as well.
  const Eigen::VectorXd th0 = tf.to_theta(start);
  OptResult r = opt.method == Method::Bfgs ? minimize_bfgs(obj, th0, oo)
                                           : minimize_trust_region(obj, th0, oo);
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
  for (const Record &rec : recs)
    for (double v : quadrature_weights(rec, opt.fit_from))
      if (v > 0.0) w.push_back(v);
  if ((Eigen::Index)w.size() != r.size()) return u;
  const Eigen::Map<Eigen::VectorXd> wv(w.data(), r.size());
  u.valid = sandwich_covariance(r, Jw, wv, u.stddev, &u.correlation, &u.noise_sigma);
  return u;
}

bool sandwich_covariance(const Eigen::VectorXd &r, const Eigen::MatrixXd &Jw,
                         const Eigen::VectorXd &w, Eigen::VectorXd &stddev,
                         Eigen::MatrixXd *correlation, double *noise_sigma) {
  // White noise of variance s^2 per sample, weights w_j (quadrature):
  //   Cov = s^2 A^-1 B A^-1,  A = sum w J_j J_j^T,  B = sum w^2 J_j J_j^T.
  const Eigen::Index m = r.size(), n = Jw.cols();
  if (m <= n || n == 0) return false;
  double ss = 0.0;
  for (Eigen::Index j = 0; j < m; ++j) ss += r[j] * r[j] / w[j];
  const double s2 = ss / double(m - n);
  if (noise_sigma) *noise_sigma = std::sqrt(s2);
  // Scale columns to unit size so the inversion is well conditioned.
  const Eigen::VectorXd cs = Jw.colwise().norm().transpose().cwiseMax(1e-300);
  const Eigen::MatrixXd Js = Jw * cs.cwiseInverse().asDiagonal();
  const Eigen::MatrixXd A = Js.transpose() * Js;
  const Eigen::MatrixXd B = Js.transpose() * w.asDiagonal() * Js;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::VectorXd sv = svd.singularValues();
  if (!(sv[n - 1] > 1e-14 * sv[0])) return false;
  const Eigen::MatrixXd Ai = svd.solve(Eigen::MatrixXd::Identity(n, n));
  Eigen::MatrixXd C = s2 * Ai * B * Ai;
  C = cs.cwiseInverse().asDiagonal() * C * cs.cwiseInverse().asDiagonal();
  stddev = C.diagonal().cwiseSqrt();
  if (correlation)
    *correlation = stddev.cwiseInverse().asDiagonal() * C * stddev.cwiseInverse().asDiagonal();
  return true;
}

}  // namespace rtb
