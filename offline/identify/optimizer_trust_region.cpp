// optimizer_trust_region.cpp -- Gauss-Newton trust region (Levenberg-
// Marquardt, Moré 1978): the step solves (J^T J + lambda S) d = -J^T r with S
// the column scaling, lambda adapted from the ratio of actual to predicted
// decrease (the trust-region radius in Moré's form).
#include <cmath>

#include "identify/optimizer.h"

namespace rtb {

OptResult minimize_trust_region(const Objective &obj, const Eigen::VectorXd &theta0,
                                const OptOptions &opt) {
  OptResult res;
  Eigen::VectorXd x = theta0, r, r_new;
  Eigen::MatrixXd J;
  obj.residuals(x, r, &J);
  res.evaluations = 1;
  double f = 0.5 * r.squaredNorm();
  double lambda = 1e-3;
  int it = 0;
  for (; it < opt.max_iter; ++it) {
    const Eigen::VectorXd g = J.transpose() * r;
    if (opt.progress) opt.progress(it, f, g.norm());
    const Eigen::MatrixXd A = J.transpose() * J;
    Eigen::VectorXd S = A.diagonal().cwiseMax(1e-12 * A.diagonal().maxCoeff());
    // Stationarity test: the decrease the undamped Gauss-Newton step
    // predicts. (A small damped step is not convergence: lambda may just be
    // large after rejections.)
    {
      Eigen::MatrixXd M = A;
      M.diagonal() += 1e-12 * S;
      const double gn_pred = 0.5 * g.dot(M.ldlt().solve(g));
      if (gn_pred <= opt.ftol * f || f < 1e-30) {
        res.converged = true;
        res.message = "Gauss-Newton predicted decrease below ftol";
        break;
      }
    }
    bool accepted = false;
    Eigen::VectorXd step;
    double f_new = f;
    for (int tries = 0; tries < 40; ++tries) {
      Eigen::MatrixXd M = A;
      M.diagonal() += lambda * S;
      step = M.ldlt().solve(-g);
      // Never step more than e^3 in a log parameter at once.
      const double smax = step.cwiseAbs().maxCoeff();
      if (smax > 3.0) step *= 3.0 / smax;
      obj.residuals(x + step, r_new, nullptr);
      ++res.evaluations;
      f_new = std::isfinite(r_new.squaredNorm()) ? 0.5 * r_new.squaredNorm() : INFINITY;
      const double predicted = -(g.dot(step) + 0.5 * step.dot(A * step));
      const double rho = predicted > 0.0 ? (f - f_new) / predicted : -1.0;
      if (rho > 1e-4) {
        accepted = true;
        lambda *= rho > 0.75 ? 0.2 : (rho > 0.25 ? 1.0 : 2.0);
        lambda = std::fmax(lambda, 1e-12);
        break;
      }
      lambda *= 4.0;
      if (lambda > 1e12) break;
    }
    if (!accepted) {
      res.converged = g.norm() < 1e-6 * std::sqrt(std::fmax(f, 1e-300)) || f < 1e-28;
      res.message = "no acceptable step (stationary point within rounding)";
      break;
    }
    x += step;
    obj.residuals(x, r, &J);
    ++res.evaluations;
    f = 0.5 * r.squaredNorm();
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
