// optimizer.h -- the two minimizers of section 5.3, on unconstrained
// coordinates theta (param_transform.h):
//  * minimize_bfgs: line-search quasi-Newton (BFGS, Wolfe line search), one
//    forward + one adjoint solve per evaluation (Nocedal & Wright, ch. 6);
//  * minimize_trust_region: Gauss-Newton trust region (Levenberg-Marquardt
//    with Moré's scaling), with the exact tangent Jacobian of the discrete
//    stepper; its gradient J^T r is the adjoint gradient (checked in tests).
#ifndef RTB_OFFLINE_OPTIMIZER_H
#define RTB_OFFLINE_OPTIMIZER_H

#include <Eigen/Dense>
#include <functional>
#include <string>

namespace rtb {

struct Objective {
  // f(theta) and, if grad != nullptr, its gradient (adjoint).
  std::function<double(const Eigen::VectorXd &, Eigen::VectorXd *)> value_grad;
  // Residual vector with f = 1/2 |r|^2 and, if jac != nullptr, dr/dtheta.
  std::function<void(const Eigen::VectorXd &, Eigen::VectorXd &, Eigen::MatrixXd *)> residuals;
};

struct OptOptions {
  int max_iter = 200;
  double ftol = 1e-10;   // stop when the (predicted) relative decrease of f is below
  double xtol = 1e-10;   // stop when |step| is below (theta units ~ relative)
  // Trust region: also stop when the predicted decrease is below chi2_tol
  // noise-variance units, the noise variance estimated as 2 f / m from the m
  // residuals. 0.01 leaves the parameters within ~0.1 standard deviation of
  // the exact minimum, where an ftol of 1e-10 spent dozens of iterations on
  // decreases of 1e-9 f (alpha rattling against its floor, e.g.).
  double chi2_tol = 0.0;
  // Box on theta (empty or +-inf: unbounded); enforced by projection in
  // minimize_trust_region (minimize_bfgs ignores it: the transforms clamp).
  Eigen::VectorXd lower, upper;
  std::function<void(int iter, double f, double gnorm)> progress;  // may be empty
};

struct OptResult {
  Eigen::VectorXd theta;
  double f = 0.0;
  int iterations = 0;
  int evaluations = 0;   // f (+gradient or Jacobian) evaluations
  bool converged = false;
  std::string message;
};

OptResult minimize_bfgs(const Objective &obj, const Eigen::VectorXd &theta0, const OptOptions &opt);
OptResult minimize_trust_region(const Objective &obj, const Eigen::VectorXd &theta0,
                                const OptOptions &opt);

// One minimization of the caller's objective from theta0 with options opt.
using RunFrom = std::function<OptResult(const Eigen::VectorXd &theta0, const OptOptions &opt)>;

// Restarts of a converged result r from r.theta +-0.4, +-0.8, ... along the
// least determined direction of the Gauss-Newton Hessian J^T J at r (its
// smallest eigenvalue's eigenvector), each converged loosely (ftol 1e-6); a
// lower one is polished with `oo` and replaces r. With noise the misfit has
// secondary minima along such ridges (the RT model's Kr-C0 ridge; a Maxwell
// branch's time). Returns the number of restarts that improved r; r's
// iterations and evaluations count all of them.
int restart_sloppy(const Objective &obj, const RunFrom &run, OptOptions oo, int restarts,
                   OptResult &r);

}  // namespace rtb

#endif
