// optimizer_trust_region.cpp -- Gauss-Newton trust region (Levenberg-
// Marquardt, Moré 1978): the step solves (J^T J + lambda S) d = -J^T r with S
// the column scaling, lambda adapted from the ratio of actual to predicted
// decrease (the trust-region radius in Moré's form).
//
// Box constraints (OptOptions::lower/upper) by an active set and projection:
// a coordinate at a bound whose gradient points out of the box is held
// there; the others take the damped Gauss-Newton step, which is then
// projected onto the box, and the ratio test judges the projected step.
#include <cmath>

#include "identify/optimizer.h"

namespace rtb {

namespace {

struct Box {
  Eigen::VectorXd lo, hi;
  Box(const OptOptions &opt, Eigen::Index n)
      : lo(opt.lower.size() == n ? opt.lower : Eigen::VectorXd::Constant(n, -INFINITY)),
        hi(opt.upper.size() == n ? opt.upper : Eigen::VectorXd::Constant(n, INFINITY)) {}
  Eigen::VectorXd project(const Eigen::VectorXd &x) const { return x.cwiseMax(lo).cwiseMin(hi); }
  // Held at a bound: the descent direction -g points out of the box.
  bool held(const Eigen::VectorXd &x, const Eigen::VectorXd &g, Eigen::Index i) const {
    return (x[i] <= lo[i] && g[i] > 0.0) || (x[i] >= hi[i] && g[i] < 0.0);
  }
};

}  // namespace

OptResult minimize_trust_region(const Objective &obj, const Eigen::VectorXd &theta0,
                                const OptOptions &opt) {
  OptResult res;
  const Eigen::Index n = theta0.size();
  const Box box(opt, n);
  Eigen::VectorXd x = box.project(theta0), r, r_new;
  Eigen::MatrixXd J;
  obj.residuals(x, r, &J);
  res.evaluations = 1;
  double f = 0.5 * r.squaredNorm();
  double lambda = 1e-3;
  int it = 0, stalled = 0;
  // chi2_tol noise-variance units in f, the variance estimated as 2 f / m.
  auto noise_tol = [&](double f_now, const Eigen::VectorXd &res_now) {
    return opt.chi2_tol * f_now / std::fmax(1.0, (double)res_now.size());
  };
  for (; it < opt.max_iter; ++it) {
    const Eigen::VectorXd g = J.transpose() * r;
    const Eigen::MatrixXd A = J.transpose() * J;
    // The reduced problem on the coordinates not held at a bound.
    Eigen::VectorXd gr = g;
    Eigen::MatrixXd Ar = A;
    for (Eigen::Index i = 0; i < n; ++i)
      if (box.held(x, g, i)) {
        gr[i] = 0.0;
        Ar.row(i).setZero();
        Ar.col(i).setZero();
        Ar(i, i) = 1.0;
      }
    if (opt.progress) opt.progress(it, f, gr.norm());
    Eigen::VectorXd S = Ar.diagonal().cwiseMax(1e-12 * Ar.diagonal().maxCoeff());
    // Stationarity test: the decrease the undamped Gauss-Newton step
    // predicts. (A small damped step is not convergence: lambda may just be
    // large after rejections.)
    {
      Eigen::MatrixXd M = Ar;
      M.diagonal() += 1e-12 * S;
      const double gn_pred = 0.5 * gr.dot(M.ldlt().solve(gr));
      if (gn_pred <= std::fmax(opt.ftol * f, noise_tol(f, r)) || f < 1e-30) {
        res.converged = true;
        res.message = "Gauss-Newton predicted decrease below ftol / chi2_tol";
        break;
      }
    }
    bool accepted = false;
    Eigen::VectorXd step, r_acc;
    Eigen::MatrixXd J_acc;
    double f_new = f;
    for (int tries = 0; tries < 40; ++tries) {
      Eigen::MatrixXd M = Ar;
      M.diagonal() += lambda * S;
      step = M.ldlt().solve(-gr);
      // Never step more than e^3 in a log parameter at once.
      const double smax = step.cwiseAbs().maxCoeff();
      if (smax > 3.0) step *= 3.0 / smax;
      step = box.project(x + step) - x;
      obj.residuals(x + step, r_new, nullptr);
      ++res.evaluations;
      f_new = std::isfinite(r_new.squaredNorm()) ? 0.5 * r_new.squaredNorm() : INFINITY;
      const double predicted = -(g.dot(step) + 0.5 * step.dot(A * step));
      const double rho = predicted > 0.0 ? (f - f_new) / predicted : -1.0;
      if (rho > 1e-4) {
        // A point whose Jacobian is not finite is refused like a step that
        // failed: the tangent sweeps overflow near a limit model, and from
        // there no step can be computed (blindgen backlash_held_s31: the
        // baseline went to C0 = 4e-14 with alpha -> 1, a NaN gradient
        // stopped it at 26% where the fit ends at 17.5% otherwise).
        obj.residuals(x + step, r_acc, &J_acc);
        ++res.evaluations;
        if (r_acc.allFinite() && J_acc.allFinite()) {
          accepted = true;
          lambda *= rho > 0.75 ? 0.2 : (rho > 0.25 ? 1.0 : 2.0);
          lambda = std::fmax(lambda, 1e-12);
          break;
        }
      }
      lambda *= 4.0;
      if (lambda > 1e12) break;
    }
    if (!accepted) {
      res.converged = gr.norm() < 1e-6 * std::sqrt(std::fmax(f, 1e-300)) || f < 1e-28;
      res.message = "no acceptable step (stationary point within rounding)";
      break;
    }
    x += step;
    r.swap(r_acc);
    J.swap(J_acc);
    const double gained = f - 0.5 * r.squaredNorm();
    f = 0.5 * r.squaredNorm();
    // Stalled: three accepted steps in a row each gained less than chi2_tol
    // noise units. The undamped Gauss-Newton prediction can stay large where
    // the model is poor (alpha at its floor makes the dashpot a near-friction
    // element), and damped steps then crawl for hundreds of iterations.
    stalled = opt.chi2_tol > 0.0 && gained < noise_tol(f, r) ? stalled + 1 : 0;
    if (stalled >= 3) {
      res.converged = true;
      res.message = "decrease below chi2_tol noise units for 3 steps";
      ++it;
      break;
    }
    if (step.norm() < opt.xtol && lambda < 1.0) {
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
