// adjoint_test.cpp -- the gradient is the exact adjoint of the discrete
// stepper: against central finite differences of the same discrete misfit
// (relative 1e-6 or better) and by the dot-product test of eq. (15)-(16)
// (1e-10 or better), on smooth and hysteretic data, for both integrators,
// with every extension, and at the paper's Table 1 set-up.
#include <gtest/gtest.h>

#include "offline/identify/gradcheck.h"
#include "offline/identify/identify.h"
#include "offline_test_records.h"

using namespace rtb;

namespace {

rtb_params table1_point(const rtb_params &truth) {
  rtb_params p = truth;  // (K0/2, 2Kpa, Kr/2, C0/2, 2 alpha), section 5.2
  p.K0 /= 2;
  p.Kpa *= 2;
  p.Kr /= 2;
  p.C0 /= 2;
  p.alpha *= 2;
  return p;
}

void expect_exact(const rtb_params &p, const std::vector<Record> &recs) {
  const GradcheckResult g = gradcheck(p, recs, MisfitOptions());
  ASSERT_FALSE(g.rows.empty());
  for (const GradcheckRow &r : g.rows)
    EXPECT_LT(r.rel, 1e-6) << param_name(r.id) << " adjoint " << r.adjoint << " fd " << r.fd;
  EXPECT_LT(g.dot_product_rel_mismatch, 1e-10);
}

}  // namespace

class AdjointIntegrators : public ::testing::TestWithParam<int> {};

TEST_P(AdjointIntegrators, Table1PointOnHystereticData) {
  rtb_params truth;
  rtb_params_default(&truth, RTB_MODEL_RT);
  truth.integrator = GetParam();
  const std::vector<Record> recs = rtb_test::paper_records(truth, 1.0);
  expect_exact(table1_point(truth), recs);
}

TEST_P(AdjointIntegrators, SmoothDataNearTruthWithAllExtensions) {
  rtb_params truth;
  rtb_params_default(&truth, RTB_MODEL_RT);
  truth.integrator = GetParam();
  std::vector<Record> recs = rtb_test::paper_records(truth, 1.0);
  rtb_params p = truth;
  p.K0 *= 1.01;  // near the optimum the gradient is small: the hard case for FD
  p.k3 = 50;
  p.k_asym = 100;
  p.maxwell_k = 200;
  p.maxwell_tau = 0.05;
  p.viscous_c = 0.5;
  p.mass = 1e-3;
  p.mullins = 0.2;
  expect_exact(p, recs);
}

TEST_P(AdjointIntegrators, ClearanceContactAndFreePhases) {
  rtb_params truth;
  rtb_params_default(&truth, RTB_MODEL_RT);
  truth.integrator = GetParam();
  std::vector<Record> recs = rtb_test::paper_records(truth, 1.0);
  rtb_params p = table1_point(truth);
  p.backlash = 0.05;
  p.maxwell_k = 100;
  p.maxwell_tau = 0.1;
  p.viscous_c = 0.3;
  expect_exact(p, recs);
}

INSTANTIATE_TEST_SUITE_P(Both, AdjointIntegrators,
                         ::testing::Values((int)RTB_INTEGRATOR_SDIRK2, (int)RTB_INTEGRATOR_BE));

TEST(Adjoint, NearFrictionDashpot) {
  // alpha -> 0 is the friction limit; the dual formulation stays smooth.
  rtb_params truth;
  rtb_params_default(&truth, RTB_MODEL_RT);
  truth.alpha = 0.02;
  std::vector<Record> recs = rtb_test::paper_records(truth, 1.0);
  rtb_params p = truth;
  p.alpha = 0.03;
  p.Kr *= 0.8;
  expect_exact(p, recs);
}

TEST(Adjoint, GaussNewtonGradientEqualsAdjointGradient) {
  // The trust-region method's gradient J^T r comes from tangent sweeps; it
  // must be the adjoint gradient (two independent linearizations).
  rtb_params truth;
  rtb_params_default(&truth, RTB_MODEL_RT);
  std::vector<Record> recs = rtb_test::paper_records(truth, 1.0);
  const rtb_params p = table1_point(truth);
  const MisfitValue m = misfit(p, recs, MisfitOptions(), true);
  Eigen::VectorXd r;
  Eigen::MatrixXd J;
  residual_jacobian(p, recs, MisfitOptions(), core_params(), r, &J);
  const Eigen::VectorXd g = J.transpose() * r;
  for (int i = 0; i < 5; ++i)
    EXPECT_NEAR(g[i], m.grad[i], 1e-10 * std::fabs(m.grad[i])) << param_name(ParamId(i));
  EXPECT_NEAR(0.5 * r.squaredNorm(), m.J, 1e-12 * m.J);
}

TEST(Adjoint, TikhonovTermOfEq11) {
  rtb_params truth;
  rtb_params_default(&truth, RTB_MODEL_RT);
  std::vector<Record> recs = rtb_test::paper_records(truth, 0.5);
  MisfitOptions o;
  o.R[P_K0] = 0.3;
  o.p0[P_K0] = 900;
  const rtb_params p = table1_point(truth);
  const MisfitValue a = misfit(p, recs, MisfitOptions(), true), b = misfit(p, recs, o, true);
  EXPECT_NEAR(b.J - a.J, 0.5 * 0.09 * (p.K0 - 900) * (p.K0 - 900), 1e-9 * b.J);
  EXPECT_NEAR(b.grad[P_K0] - a.grad[P_K0], 0.09 * (p.K0 - 900), 1e-9 * std::fabs(b.grad[P_K0]));
}
