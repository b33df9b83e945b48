// param_transform_test.cpp -- the Jacobian dp/dtheta of the optimizers'
// parameter map (offline/identify/param_transform.h) against central finite
// differences of the map itself, in particular at the k_asym clamp (|k_asym|
// <= K0 + chain + sat_force/sat_disp, the static tangent), where k_asym
// follows K0, Kpa and Kr and no longer its own coordinate (the gradient used
// to be taken through the unclamped slope there: wrong at the clamp).
#include <gtest/gtest.h>

#include <cmath>

#include "identify/param_transform.h"

namespace {

using namespace rtb;

// Central differences of to_params, column by column.
Eigen::MatrixXd fd_jacobian(const ParamTransform &tf, const Eigen::VectorXd &th,
                            const rtb_params &base) {
  const Eigen::Index n = th.size();
  Eigen::MatrixXd J(n, n);
  for (Eigen::Index j = 0; j < n; ++j) {
    const double h = 1e-6 * std::fmax(1.0, std::fabs(th[j]));
    Eigen::VectorXd a = th, b = th;
    a[j] += h;
    b[j] -= h;
    const rtb_params pa = tf.to_params(a, base), pb = tf.to_params(b, base);
    for (Eigen::Index i = 0; i < n; ++i) {
      const ParamId id = tf.free[(size_t)i];
      J(i, j) = (param_get(pa, id) - param_get(pb, id)) / (2 * h);
    }
  }
  return J;
}

void expect_close(const Eigen::MatrixXd &A, const Eigen::MatrixXd &B, const char *what) {
  ASSERT_EQ(A.rows(), B.rows());
  for (Eigen::Index i = 0; i < A.rows(); ++i)
    for (Eigen::Index j = 0; j < A.cols(); ++j)
      EXPECT_NEAR(A(i, j), B(i, j), 1e-6 * (std::fabs(B(i, j)) + 1.0))
          << what << " (" << i << "," << j << ")";
}

rtb_params base_params() {
  rtb_params p;
  rtb_params_default(&p, RTB_MODEL_RT);
  p.K0 = 250.0;
  p.k_asym = 100.0;
  return p;
}

TEST(ParamTransformJacobian, InsideTheClampItIsTheDiagonal) {
  const rtb_params p = base_params();
  const ParamTransform tf({P_K0, P_Kpa, P_k_asym}, p, 1e6);
  const Eigen::VectorXd th = tf.to_theta(p);
  const Eigen::MatrixXd J = tf.jacobian(th, p);
  expect_close(J, fd_jacobian(tf, th, p), "inside");
  expect_close(J, Eigen::MatrixXd(tf.dp_dtheta(th).asDiagonal()), "diagonal");
}

// The clamp is the library's static tangent, K0 + chain (+ sat_force /
// sat_disp): at it k_asym follows K0, Kpa and Kr, not its own coordinate.
TEST(ParamTransformJacobian, AtTheClampKasymFollowsTheStaticTangent) {
  const rtb_params p = base_params();
  const ParamTransform tf({P_K0, P_Kpa, P_k_asym}, p, 1e6);
  const double chain = 1.0 / (1.0 / p.Kpa + p.cells / p.Kr);
  for (double ratio : {1.3, -1.3}) {
    SCOPED_TRACE(ratio);
    Eigen::VectorXd th = tf.to_theta(p);
    th[2] = ratio * (p.K0 + chain) / tf.scale[P_k_asym];  // raw k_asym beyond the tangent
    const rtb_params q = tf.to_params(th, p);
    ASSERT_EQ(q.k_asym, std::copysign(k_asym_bound(q), ratio)) << "the map clamps";
    EXPECT_NEAR(std::fabs(q.k_asym), q.K0 + chain, 1e-6 * chain) << "at the library's bound";
    EXPECT_GT(std::fabs(q.k_asym), q.K0) << "past K0 alone";
    const char *bad = "";
    EXPECT_EQ(rtb_params_check(&q, &bad), RTB_OK) << bad;
    const Eigen::MatrixXd J = tf.jacobian(th, p);
    expect_close(J, fd_jacobian(tf, th, p), "clamped");
    EXPECT_EQ(J(2, 2), 0.0);
    EXPECT_EQ(J(2, 0), std::copysign(tf.dp_dtheta(th)[0], ratio));
    EXPECT_GT(J(2, 1) * ratio, 0.0) << "a stiffer Kpa raises the bound";
  }
}

TEST(ParamTransformJacobian, ClampAgainstAFixedK0) {
  const rtb_params p = base_params();
  const ParamTransform tf({P_Kpa, P_k_asym}, p, 1e6);  // K0 not free
  Eigen::VectorXd th = tf.to_theta(p);
  th[1] = 2.0 * (p.K0 + 1.0 / (1.0 / p.Kpa + p.cells / p.Kr)) / tf.scale[P_k_asym];
  const Eigen::MatrixXd J = tf.jacobian(th, p);
  expect_close(J, fd_jacobian(tf, th, p), "fixed K0");
  EXPECT_EQ(J(1, 1), 0.0);
  EXPECT_GT(J(1, 0), 0.0);
}

// Next to a softening spring K0 may go negative, down to -(chain +
// sat_force/sat_disp) (rtb_params_check); below that the map holds it there
// and K0 follows Kpa, Kr and the softening spring. Without the softening
// spring K0's box still starts at 0.
TEST(ParamTransformJacobian, SignedK0HeldAtItsFloor) {
  rtb_params p = base_params();
  p.k_asym = 0.0;
  p.sat_force = 50.0;
  p.sat_disp = 0.5;
  const ParamTransform plain({P_K0, P_Kpa, P_Kr}, p, 1e6);
  EXPECT_FALSE(plain.signed_K0);
  EXPECT_EQ(plain.lower()[0], 0.0);
  const ParamTransform tf({P_K0, P_Kpa, P_Kr, P_sat_force, P_sat_disp, P_k_asym}, p, 1e6);
  ASSERT_TRUE(tf.signed_K0);
  const double floor = -(1.0 / (1.0 / p.Kpa + p.cells / p.Kr) + p.sat_force / p.sat_disp);
  for (double K0 : {0.5 * floor, 3.0 * floor}) {
    SCOPED_TRACE(K0);
    Eigen::VectorXd th = tf.to_theta(p);
    th[0] = K0 / tf.scale[P_K0];
    th[5] = -0.3 * floor / tf.scale[P_k_asym];  // raw k_asym: kept while K0 - floor exceeds it
    const rtb_params q = tf.to_params(th, p);
    const char *bad = "";
    EXPECT_EQ(rtb_params_check(&q, &bad), RTB_OK) << bad;
    if (K0 > floor) EXPECT_NEAR(q.k_asym, -0.3 * floor, 1e-9 * -floor);
    else EXPECT_EQ(q.k_asym, 0.0) << "K0 at its floor leaves no tangent for a kink";
    if (K0 > floor) EXPECT_EQ(q.K0, K0);
    else EXPECT_NEAR(q.K0, floor, -1e-6 * floor);
    const Eigen::MatrixXd J = tf.jacobian(th, p);
    expect_close(J, fd_jacobian(tf, th, p), "signed K0");
    if (K0 < floor) {
      EXPECT_EQ(J(0, 0), 0.0);
      EXPECT_LT(J(0, 1), 0.0) << "a stiffer Kpa lowers the floor";
      EXPECT_LT(J(0, 3), 0.0) << "a stronger softening spring lowers the floor";
    }
  }
}

// A kink without a softening spring: K0 may go below zero, but not below
// -|k_asym| (kink_floor), so the stiffer side keeps a spring of its own and
// the kink cannot free the core instead (blindgen maxwell_s35: K0 = -7578
// beside k_asym = -7).
TEST(ParamTransformJacobian, KinkHoldsK0AboveMinusItsSize) {
  rtb_params p = base_params();
  const ParamTransform tf({P_K0, P_Kpa, P_Kr, P_k_asym}, p, 1e6);
  ASSERT_TRUE(tf.signed_K0);
  ASSERT_TRUE(tf.kink_floor);
  const double chain = 1.0 / (1.0 / p.Kpa + p.cells / p.Kr);  // 160
  struct Case { double K0, k_asym, K0_mapped; };
  const Case cases[] = {
      {-50.0, -70.0, -50.0},    // inside both floors: kept
      {-90.0, 60.0, -60.0},     // below -|k_asym|: held there
      {-90.0, -60.0, -60.0},    // either sign of the kink
      {-300.0, -150.0, -150.0}, // the kink floor above the chain's -160
      {-300.0, 0.0, 0.0},       // no kink: K0 >= 0 as a plain core
  };
  for (const Case &c : cases) {
    SCOPED_TRACE(testing::Message() << "K0 " << c.K0 << " k_asym " << c.k_asym);
    Eigen::VectorXd th = tf.to_theta(p);
    th[0] = c.K0 / tf.scale[P_K0];
    th[3] = c.k_asym / tf.scale[P_k_asym];
    const rtb_params q = tf.to_params(th, p);
    EXPECT_NEAR(q.K0, c.K0_mapped, 1e-9 * chain);
    const char *bad = "";
    EXPECT_EQ(rtb_params_check(&q, &bad), RTB_OK) << bad;
    if (c.k_asym != 0.0) expect_close(tf.jacobian(th, p), fd_jacobian(tf, th, p), "kink floor");
  }
  // With a softening spring free too, the spring is the reason for K0 < 0:
  // only the static tangent's floor applies.
  const ParamTransform soft({P_K0, P_Kpa, P_Kr, P_k_asym, P_sat_force, P_sat_disp}, p, 1e6);
  EXPECT_TRUE(soft.signed_K0);
  EXPECT_FALSE(soft.kink_floor);
}

}  // namespace
