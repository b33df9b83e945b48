// optimizer_bfgs.cpp -- BFGS with a bracketing Wolfe line search.
#include <cmath>

#include "identify/optimizer.h"

namespace rtb {

namespace {

struct LinePoint {
  double t, f, dg;  // step, value, directional derivative
  Eigen::VectorXd g;
};

// Strong-Wolfe line search by bracketing and bisection/interpolation
// (Nocedal & Wright, Algorithm 3.5/3.6), at most 30 evaluations.
bool wolfe_search(const Objective &obj, const Eigen::VectorXd &x, const Eigen::VectorXd &d,
                  double f0, double dg0, LinePoint &out, int &evals) {
  const double c1 = 1e-4, c2 = 0.9;
  auto eval = [&](double t) {
    LinePoint p;
    p.t = t;
    p.g.resize(x.size());
    p.f = obj.value_grad(x + t * d, &p.g);
    ++evals;
    p.dg = std::isfinite(p.f) ? p.g.dot(d) : NAN;
    return p;
  };
  LinePoint lo{0.0, f0, dg0, Eigen::VectorXd()}, hi{0.0, INFINITY, NAN, Eigen::VectorXd()};
  bool have_hi = false;
  double t = 1.0;
  for (int k = 0; k < 30; ++k) {
    LinePoint p = eval(t);
    if (!std::isfinite(p.f) || p.f > f0 + c1 * t * dg0 || (k > 0 && p.f >= lo.f)) {
      hi = p;
      have_hi = true;
    } else if (std::fabs(p.dg) <= -c2 * dg0) {
      out = p;
      return true;
    } else if (p.dg >= 0.0) {
      hi = lo;
      lo = p;
      have_hi = true;
    } else {
      lo = p;
    }
    if (!have_hi) {
      t *= 2.0;
      continue;
    }
    // Cubic-free safeguarded step: quadratic interpolation from lo, clipped.
    const double a = lo.t, b = hi.t;
    double tq = NAN;
    if (std::isfinite(hi.f)) {
      const double den = 2.0 * (hi.f - lo.f - lo.dg * (b - a));
      if (den > 0.0) tq = a - lo.dg * (b - a) * (b - a) / den;
    }
    const double lo_b = std::fmin(a, b), hi_b = std::fmax(a, b), w = hi_b - lo_b;
    t = (std::isfinite(tq) && tq > lo_b + 0.1 * w && tq < hi_b - 0.1 * w) ? tq : 0.5 * (a + b);
    if (w < 1e-14 * std::fmax(1.0, hi_b)) break;
  }
  if (lo.t > 0.0) {
    out = lo;  // sufficient decrease without curvature: still progress
    return true;
  }
  return false;
}

}  // namespace

OptResult minimize_bfgs(const Objective &obj, const Eigen::VectorXd &theta0, const OptOptions &opt) {
  OptResult res;
  const Eigen::Index n = theta0.size();
  Eigen::VectorXd x = theta0, g(n);
  double f = obj.value_grad(x, &g);
  res.evaluations = 1;
  Eigen::MatrixXd H = Eigen::MatrixXd::Identity(n, n);  // inverse Hessian
  bool scaled = false;
  int it = 0;
  for (; it < opt.max_iter; ++it) {
    if (opt.progress) opt.progress(it, f, g.norm());
    Eigen::VectorXd d = -H * g;
    double dg = g.dot(d);
    if (!(dg < 0.0)) {  // lost positive definiteness: restart
      H.setIdentity();
      d = -g;
      dg = -g.squaredNorm();
    }
    // Keep the first trial step modest in theta (log) units.
    const double dn = d.norm();
    if (dn > 1.0) {
      d *= 1.0 / dn;
      dg /= dn;
    }
    LinePoint p;
    if (!wolfe_search(obj, x, d, f, dg, p, res.evaluations)) {
      res.message = "line search failed (no decrease along the BFGS direction)";
      res.converged = g.norm() < 1e-8 * std::fmax(1.0, std::fabs(f));
      break;
    }
    const Eigen::VectorXd s = p.t * d, y = p.g - g;
    const double f_old = f;
    x += s;
    f = p.f;
    g = p.g;
    const double sy = s.dot(y);
    if (sy > 1e-12 * s.norm() * y.norm()) {
      if (!scaled) {
        H *= sy / y.squaredNorm();
        scaled = true;
      }
      const double r = 1.0 / sy;
      const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n);
      H = (I - r * s * y.transpose()) * H * (I - r * y * s.transpose()) + r * s * s.transpose();
    }
    if (f_old - f <= opt.ftol * std::fmax(std::fabs(f_old), 1e-300) && s.norm() < 1e-6) {
      res.converged = true;
      res.message = "relative decrease below ftol";
      ++it;
      break;
    }
    if (s.norm() < opt.xtol) {
      res.converged = true;
      res.message = "step below xtol";
      ++it;
      break;
    }
  }
  if (it >= opt.max_iter && res.message.empty()) res.message = "iteration limit";
  res.theta = x;
  res.f = f;
  res.iterations = it;
  return res;
}

}  // namespace rtb
