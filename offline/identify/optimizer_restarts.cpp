// optimizer_restarts.cpp -- restarts of a converged minimization along its
// least determined direction (optimizer.h). Shared by identify() and the
// diagnosis's basin check of an accepted cause (fit_extended).
#include <cmath>

#include <Eigen/Eigenvalues>

#include "identify/optimizer.h"

namespace rtb {

int restart_sloppy(const Objective &obj, const RunFrom &run, OptOptions oo, int restarts,
                   OptResult &r) {
  if (restarts <= 0 || !r.converged || r.theta.size() < 2 || !(r.f > 1e-20)) return 0;
  Eigen::VectorXd res;
  Eigen::MatrixXd Jt;
  obj.residuals(r.theta, res, &Jt);
  if (!std::isfinite(res.squaredNorm()) || Jt.rows() == 0) return 0;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(Jt.transpose() * Jt);
  const Eigen::VectorXd dir = es.eigenvectors().col(0);  // smallest eigenvalue
  // A restart only has to reveal a lower basin: converge it loosely and
  // polish the winner at full tolerance.
  const OptOptions full = oo;
  oo.ftol = 1e-6;
  int improved = 0;
  for (int k = 0; k < restarts; ++k) {
    const double s = (k % 2 == 0 ? 0.4 : -0.4) * (1 + k / 2);
    Eigen::VectorXd t = r.theta + s * dir;
    if (oo.lower.size() == t.size()) t = t.cwiseMax(oo.lower);
    if (oo.upper.size() == t.size()) t = t.cwiseMin(oo.upper);
    OptResult q = run(t, oo);
    if (q.f < r.f * (1.0 - 1e-9)) {
      OptResult polished = run(q.theta, full);
      polished.iterations += r.iterations + q.iterations;
      polished.evaluations += r.evaluations + q.evaluations;
      r = polished;
      ++improved;
    } else {
      r.iterations += q.iterations;
      r.evaluations += q.evaluations;
    }
  }
  return improved;
}

}  // namespace rtb
