// optimizer_test.cpp -- the trust-region optimizer's box constraints and
// stopping rules, and the parameter transforms that feed it the box.
#include <gtest/gtest.h>

#include <cmath>

#include "identify/optimizer.h"
#include "identify/param_transform.h"

namespace {

using namespace rtb;

// r(theta) = A theta - b: linear least squares with a known constrained
// solution.
Objective linear_ls(const Eigen::MatrixXd &A, const Eigen::VectorXd &b) {
  Objective o;
  o.residuals = [A, b](const Eigen::VectorXd &th, Eigen::VectorXd &r, Eigen::MatrixXd *J) {
    r = A * th - b;
    if (J) *J = A;
  };
  return o;
}

TEST(TrustRegionBox, OptimumOutsideTheBoxLandsExactlyOnTheBound) {
  // Unconstrained optimum (-1, 2); with theta_0 >= 0 it is (0, 2) exactly.
  const Eigen::MatrixXd A = Eigen::MatrixXd::Identity(2, 2);
  const Eigen::VectorXd b = (Eigen::VectorXd(2) << -1.0, 2.0).finished();
  OptOptions o;
  o.lower = (Eigen::VectorXd(2) << 0.0, -INFINITY).finished();
  o.upper = Eigen::VectorXd::Constant(2, INFINITY);
  const OptResult r = minimize_trust_region(linear_ls(A, b), Eigen::VectorXd::Constant(2, 5.0), o);
  EXPECT_TRUE(r.converged) << r.message;
  EXPECT_EQ(r.theta[0], 0.0);
  EXPECT_NEAR(r.theta[1], 2.0, 1e-6);
  EXPECT_LE(r.iterations, 10);
}

TEST(TrustRegionBox, CoupledProblemHeldCoordinateFreesTheOther) {
  // Coupled columns: with theta_0 held at its upper bound 0.5 the other
  // coordinate must move to its conditional optimum, not its free one.
  Eigen::MatrixXd A(3, 2);
  A << 1.0, 1.0, 1.0, -1.0, 2.0, 0.5;
  const Eigen::VectorXd b = (Eigen::VectorXd(3) << 3.0, 1.0, 5.0).finished();
  OptOptions o;
  o.lower = Eigen::VectorXd::Constant(2, -INFINITY);
  o.upper = (Eigen::VectorXd(2) << 0.5, INFINITY).finished();
  const OptResult r = minimize_trust_region(linear_ls(A, b), Eigen::VectorXd::Zero(2), o);
  ASSERT_TRUE(r.converged) << r.message;
  // Unconstrained theta_0 is above 0.5 here, so the bound is active.
  const Eigen::VectorXd free = A.colPivHouseholderQr().solve(b);
  ASSERT_GT(free[0], 0.5);
  EXPECT_EQ(r.theta[0], 0.5);
  const Eigen::VectorXd rest = b - A.col(0) * 0.5;
  EXPECT_NEAR(r.theta[1], A.col(1).dot(rest) / A.col(1).squaredNorm(), 1e-8);
}

TEST(TrustRegionBox, StartOutsideTheBoxIsProjected) {
  const Eigen::MatrixXd A = Eigen::MatrixXd::Identity(1, 1);
  const Eigen::VectorXd b = Eigen::VectorXd::Constant(1, 0.3);
  OptOptions o;
  o.lower = Eigen::VectorXd::Constant(1, 0.0);
  o.upper = Eigen::VectorXd::Constant(1, 1.0);
  const OptResult r = minimize_trust_region(linear_ls(A, b), Eigen::VectorXd::Constant(1, -4.0), o);
  EXPECT_NEAR(r.theta[0], 0.3, 1e-10);
}

TEST(TrustRegionStop, CrawlTowardsALimitStopsOnTheNoiseScale) {
  // m noise-like residuals plus one that vanishes only as theta -> infinity:
  // the minimum is never reached, each Gauss-Newton step halves the last
  // residual. Without chi2_tol the run uses its whole budget; with it the
  // run stops once a step gains less than 0.01 noise-variance units.
  const int m = 1000;
  Objective o;
  o.residuals = [m](const Eigen::VectorXd &th, Eigen::VectorXd &r, Eigen::MatrixXd *J) {
    r = Eigen::VectorXd::Constant(m + 1, 0.01);
    r[m] = 1.0 / th[0];
    if (J) {
      J->setZero(m + 1, 1);
      (*J)(m, 0) = -1.0 / (th[0] * th[0]);
    }
  };
  OptOptions loose;
  loose.max_iter = 500;
  loose.lower = Eigen::VectorXd::Constant(1, 1e-3);
  loose.xtol = 0.0;
  OptOptions noise = loose;
  noise.chi2_tol = 0.01;
  const Eigen::VectorXd th0 = Eigen::VectorXd::Constant(1, 1.0);
  const OptResult a = minimize_trust_region(o, th0, loose);
  const OptResult b = minimize_trust_region(o, th0, noise);
  EXPECT_TRUE(b.converged) << b.message;
  EXPECT_EQ(a.iterations, loose.max_iter) << a.message;
  EXPECT_LT(b.iterations, a.iterations / 4);
  // Stopped where the remaining gain is negligible against the noise:
  // f - f_inf below one noise unit f/m (a few steps' worth of 0.01).
  const double f_inf = 0.5 * m * 0.01 * 0.01;
  EXPECT_LT(b.f - f_inf, b.f / m);
}

// Two basins along the least determined coordinate x (a stiff y beside it):
// r = (10 y, x^2 - 0.04, 0.05 (x - 0.3)). The basin near x = -0.2 holds
// f ~ 3e-4, the one near x = +0.2 f ~ 1e-5; between them a barrier at x = 0.
Objective two_basins_on_a_ridge() {
  Objective o;
  o.residuals = [](const Eigen::VectorXd &th, Eigen::VectorXd &r, Eigen::MatrixXd *J) {
    const double x = th[0], y = th[1];
    r = (Eigen::VectorXd(3) << 10.0 * y, x * x - 0.04, 0.05 * (x - 0.3)).finished();
    if (J) *J = (Eigen::MatrixXd(3, 2) << 0.0, 10.0, 2.0 * x, 0.0, 0.05, 0.0).finished();
  };
  return o;
}

// A point whose Jacobian is not finite is refused like a failed step: the
// tangent sweeps of a limit model can overflow where the misfit itself is
// finite (a baseline whose dashpots vanished: a NaN gradient stopped it at
// 26% misfit, where it ends at 17.5%). Here r = atan(theta - 1): the
// Gauss-Newton step from 0 overshoots to 1.57, past 1.2, where the
// Jacobian is NaN; the optimizer must still reach the minimum at 1. Before,
// it took that point and stopped there ("no acceptable step").
TEST(TrustRegionStop, APointWithANonFiniteJacobianIsRefused) {
  Objective o;
  o.residuals = [](const Eigen::VectorXd &th, Eigen::VectorXd &r, Eigen::MatrixXd *J) {
    r = Eigen::VectorXd::Constant(1, std::atan(th[0] - 1.0));
    if (J) *J = Eigen::MatrixXd::Constant(1, 1, th[0] > 1.2 ? NAN : 1.0 / (1.0 + std::pow(th[0] - 1.0, 2)));
  };
  OptOptions opt;
  const OptResult r = minimize_trust_region(o, Eigen::VectorXd::Zero(1), opt);
  EXPECT_TRUE(r.converged) << r.message;
  EXPECT_NEAR(r.theta[0], 1.0, 1e-6);
}

TEST(SloppyRestarts, ARestartAlongTheRidgeFindsTheLowerBasin) {
  const Objective o = two_basins_on_a_ridge();
  const RunFrom run = [&](const Eigen::VectorXd &t, const OptOptions &op) {
    return minimize_trust_region(o, t, op);
  };
  const OptOptions oo;
  OptResult r = run((Eigen::VectorXd(2) << -0.25, 1.0).finished(), oo);
  ASSERT_TRUE(r.converged) << r.message;
  ASSERT_NEAR(r.theta[0], -0.2, 0.02);  // the higher basin
  const double f_first = r.f;
  const int its = r.iterations;
  EXPECT_EQ(restart_sloppy(o, run, oo, 2, r), 1);
  EXPECT_NEAR(r.theta[0], 0.2, 0.02);
  EXPECT_NEAR(r.theta[1], 0.0, 1e-8);
  EXPECT_LT(r.f, 0.1 * f_first);
  EXPECT_GT(r.iterations, its);  // the restarts' iterations are counted
  // From the lower basin no restart improves, and r stays.
  const Eigen::VectorXd at = r.theta;
  EXPECT_EQ(restart_sloppy(o, run, oo, 2, r), 0);
  EXPECT_EQ(r.theta, at);
}

TEST(SloppyRestarts, AnUnconvergedRunIsNotRestarted) {
  // A run stopped by its iteration limit is still descending: restarts
  // around it would only continue the crawl.
  const Objective o = two_basins_on_a_ridge();
  const RunFrom run = [&](const Eigen::VectorXd &t, const OptOptions &op) {
    return minimize_trust_region(o, t, op);
  };
  OptOptions one;
  one.max_iter = 1;
  OptResult r = run((Eigen::VectorXd(2) << -0.25, 1.0).finished(), one);
  ASSERT_FALSE(r.converged);
  const Eigen::VectorXd at = r.theta;
  EXPECT_EQ(restart_sloppy(o, run, one, 2, r), 0);
  EXPECT_EQ(r.theta, at);
}

TEST(RampTransform, ZeroAdmissibleParametersAreLinearInABox) {
  rtb_params p;
  rtb_params_default(&p, RTB_MODEL_RT);
  p.K0 = 250.0;
  p.viscous_c = 0.0;
  p.mullins = 0.2;
  const double cap = 1e6;
  ParamTransform tf({P_K0, P_Kpa, P_viscous_c, P_mullins}, p, cap);
  tf.scale[P_viscous_c] = 3.0;  // what candidate_spec gives a size started at 0
  const Eigen::VectorXd th = tf.to_theta(p);
  EXPECT_DOUBLE_EQ(th[0], 250.0 / tf.scale[P_K0]);
  EXPECT_EQ(th[2], 0.0);
  const rtb_params q = tf.to_params(th, p);
  EXPECT_NEAR(q.K0, 250.0, 1e-12);
  EXPECT_EQ(q.viscous_c, 0.0);
  EXPECT_NEAR(q.mullins, 0.2, 1e-15);
  // The box: [0, cap] for the stiffness, [0, 0.95] for mullins, unbounded
  // for the log-mapped Kpa.
  const Eigen::VectorXd lo = tf.lower(), hi = tf.upper();
  EXPECT_EQ(lo[0], 0.0);
  EXPECT_DOUBLE_EQ(hi[0] * tf.scale[P_K0], cap);
  EXPECT_TRUE(std::isinf(lo[1]) && lo[1] < 0 && std::isinf(hi[1]));
  EXPECT_EQ(lo[2], 0.0);
  EXPECT_DOUBLE_EQ(hi[3] * tf.scale[P_mullins], 0.95);
  // Outside the box (an unbounded optimizer, BFGS) the value is clamped and
  // stays admissible; the slope is one-sided at the bound, 0 beyond it.
  Eigen::VectorXd out = th;
  out[2] = -2.0;
  out[3] = 100.0;
  const rtb_params c = tf.to_params(out, p);
  EXPECT_EQ(c.viscous_c, 0.0);
  EXPECT_EQ(c.mullins, 0.95);
  EXPECT_EQ(rtb_params_validate(&c), RTB_OK);
  EXPECT_EQ(tf.dp_dtheta(th)[2], 3.0);
  EXPECT_EQ(tf.dp_dtheta(out)[2], 0.0);
  EXPECT_TRUE(is_ramp(P_K0) && is_ramp(P_mass) && !is_ramp(P_Kpa) && !is_ramp(P_backlash));
}

TEST(RampTransform, StiffnessStartedNearZeroStepsOnTheSecantScale) {
  // A K0 started at 1e-6 must not be stuck with a step unit of 1e-6: its
  // scale is at least the secant stiffness cap / kStiffnessCapFactor.
  rtb_params p;
  rtb_params_default(&p, RTB_MODEL_RT);
  p.K0 = 1e-6;
  const ParamTransform tf({P_K0}, p, 2e6);
  EXPECT_DOUBLE_EQ(tf.scale[P_K0], 2e6 / kStiffnessCapFactor);
}

}  // namespace
