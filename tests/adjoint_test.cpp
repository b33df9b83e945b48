// adjoint_test.cpp -- the gradient is the exact adjoint of the discrete
// stepper: against central finite differences of the same discrete misfit
// (relative 1e-6 or better) and by the dot-product test of eq. (15)-(16)
// (1e-10 or better), on smooth and hysteretic data, for both integrators,
// with every extension, and at the paper's Table 1 set-up, also with the
// optional sigmoid smoothing of eq. (14) (Table 1's trend, docs/smoothing.md).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "offline/adjoint/step_linearization.h"
#include "offline/identify/gradcheck.h"
#include "offline/identify/identify.h"
#include "offline/io/params_json.h"
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

// A relaxation spectrum of stiffness k and weight exponent beta over [t0, t1].
void set_spectrum(rtb_params &p, double k, double beta, double t0, double t1) {
  p.spec_k = k;
  p.spec_exp = beta;
  p.spec_tau_min = t0;
  p.spec_tau_max = t1;
}

void expect_exact(const rtb_params &p, const std::vector<Record> &recs) {
  const GradcheckResult g = gradcheck(p, recs, MisfitOptions());
  ASSERT_FALSE(g.rows.empty());
  for (const GradcheckRow &r : g.rows)
    EXPECT_LT(r.rel, 1e-6) << param_name(r.id) << " adjoint " << r.adjoint << " fd " << r.fd;
  EXPECT_LT(g.dot_product_rel_mismatch, 1e-10);
}

}  // namespace

// The section 3.4 element as truth, with the integrator under test, and the
// paper's records made with it.
class AdjointIntegrators : public ::testing::TestWithParam<int> {
 protected:
  void SetUp() override {
    rtb_params_default(&truth, RTB_MODEL_RT);
    truth.integrator = GetParam();
    recs = rtb_test::paper_records(truth, 1.0);
  }
  rtb_params truth;
  std::vector<Record> recs;
};

TEST_P(AdjointIntegrators, Table1PointOnHystereticData) {
  expect_exact(table1_point(truth), recs);
}

TEST_P(AdjointIntegrators, SmoothDataNearTruthWithAllExtensions) {
  rtb_params p = truth;
  p.K0 *= 1.01;  // near the optimum the gradient is small: the hard case for FD
  p.k3 = 50;
  p.k_asym = 100;
  p.k2 = 60;
  p.maxwell_k = 200;
  p.maxwell_tau = 0.05;
  p.viscous_c = 0.5;
  p.mass = 1e-3;
  p.mullins = 0.2;
  p.sat_force = 300;  // N; saturates beyond ~0.2 mm of the 1 mm records
  p.sat_disp = 0.2;
  expect_exact(p, recs);
}

TEST_P(AdjointIntegrators, ClearanceContactAndFreePhases) {
  rtb_params p = table1_point(truth);
  p.backlash = 0.05;
  p.maxwell_k = 100;
  p.maxwell_tau = 0.1;
  p.viscous_c = 0.3;
  expect_exact(p, recs);
}

// Issue #10's extensions: a held clearance (xb frozen inside the gap), the
// friction asymmetry of the dashpot level and the relaxation spectrum.
TEST_P(AdjointIntegrators, HeldClearanceAsymmetryAndSpectrum) {
  rtb_params p = table1_point(truth);
  // Not 0.05: the triangle record would then put x + g/2 exactly on the held
  // position at a sample, a kink of the discrete map that FD straddles.
  p.backlash = 0.0517;
  p.backlash_held = 1;
  p.fric_asym = 0.3;
  set_spectrum(p, 300, 0.4, 0.002, 2.0);
  expect_exact(p, recs);
}

// A slack specimen floats free when it would push: the free phase's implicit
// root and the taut phase (xb = x) alternate on every cycle of the records.
TEST_P(AdjointIntegrators, SlackSpecimen) {
  rtb_params p = table1_point(truth);
  p.slack = 1;
  p.maxwell_k = 100;
  p.maxwell_tau = 0.1;
  set_spectrum(p, 200, -0.2, 0.01, 1.0);
  expect_exact(p, recs);
}

// The Mullins softening of the whole RT force (ABI 7): the force's y1
// partial is -eta Kpa, and a slack end's floating root goes through it.
TEST_P(AdjointIntegrators, WholeForceMullinsAlsoWhenSlack) {
  rtb_params p = table1_point(truth);
  p.mullins = 0.3;
  p.mullins_whole = 1;
  p.k3 = 50;
  expect_exact(p, recs);
  p.slack = 1;
  expect_exact(p, recs);
}

// Ogden-Roxburgh's erf shape of the Mullins loss (ABI 8): the width w is a
// fitted parameter, and the prior max enters through erf's argument.
TEST_P(AdjointIntegrators, ErfShapedMullinsOnK0AndOnTheWholeForce) {
  rtb_params p = table1_point(truth);
  p.mullins = 0.3;
  p.mullins_width = 0.4;
  expect_exact(p, recs);
  p.mullins_whole = 1;
  expect_exact(p, recs);
}

// Relaxation weakening with stretch (ABI 9): the relaxing force (chain,
// Maxwell branch, spectrum) scaled by g(xb) = 1/sqrt(1 + (xb/w)^2), w fitted;
// with the whole-force Mullins factor on top, and on a slack strip (the free
// phase's implicit xb goes through g too).
TEST_P(AdjointIntegrators, StretchDependentRelaxation) {
  rtb_params p = table1_point(truth);
  p.relax_width = 0.4;  // mm, within the 1 mm records
  p.maxwell_k = 150;
  p.maxwell_tau = 0.05;
  set_spectrum(p, 200, 0.3, 0.005, 1.0);
  expect_exact(p, recs);
  p.mullins = 0.2;
  p.mullins_whole = 1;
  expect_exact(p, recs);
  p.mullins = 0.0;
  p.mullins_whole = 0;
  p.slack = 1;
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

// ------------------------------------------------------------------------
// Table 1 with the optional smoothing of eq. (14) (docs/smoothing.md).

namespace {

// Eq. (15)-(16) exactly as the paper ran it: a = (1 ... 1) on every cell DOF
// of every step, b = L a (tangent sweep of the discrete stepper), c = L^T b
// (adjoint sweep); a^T c = b^T b holds when the adjoint is the transpose.
struct PaperDot {
  double aTc = 0.0, bTb = 0.0;
};
void paper_dot_test(const rtb_params &p, const Record &rec, PaperDot &out) {
  SimOptions sim;
  sim.tol = 1e-15;
  const DriveGrid g = make_drive_grid(rec, sim);
  const Trajectory tr = run_forward(p, g, true, sim.tol);
  const size_t n = g.x.size();
  const int N = p.cells;
  const double dp[P_COUNT] = {0};
  double pbar[P_COUNT] = {0};
  auto sq = [&](const StateDual &u) {
    double s = u.z * u.z + u.xb * u.xb + u.m * u.m;
    for (int k = 0; k < N; ++k) s += u.y[k] * u.y[k];
    return s;
  };
  std::vector<StateDual> b(n);
  b[0].clear();
  for (int k = 0; k < N; ++k) b[0].y[k] = 1.0;
  for (size_t i = 1; i < n; ++i) {
    b[i].clear();
    step_jvp(tr.step(p, g, i), b[i - 1], dp, b[i]);
    for (int k = 0; k < N; ++k) b[i].y[k] += 1.0;
  }
  for (size_t i = 0; i < n; ++i) out.bTb += sq(b[i]);
  StateDual c = b[n - 1];
  for (size_t i = n - 1;; --i) {
    for (int k = 0; k < N; ++k) out.aTc += c.y[k];
    if (i == 0) break;
    StateDual prev = b[i - 1];  // c_{i-1} = b_{i-1} + L_i^T c_i
    step_vjp(tr.step(p, g, i), c, 0.0, prev, pbar);
    c = prev;
  }
}

struct Table1Row {
  double s;  // 0 = none
  GradcheckResult g;
  PaperDot dot;
};

}  // namespace

// Data from the unsmoothed truth (N = 15, section 3.4 values; records of 1 s:
// 1 mm / 0.5 Hz triangle, 0.5 mm / 1 Hz and 0.2 mm / 10 Hz sines, input
// speeds up to 12.6 mm/s). The model is evaluated at the Table 1 point with
// smoothing s in s/mm, unscaled: the cell speeds are 0.1 to 9 mm/s (median to
// max), so s = 0.1 smooths every cell all the time and s = 100 only below
// ~0.04 mm/s (s|v| < 4): the paper's values span the whole transition.
// Set RTB_TABLE1_DIR=DIR to also write the records and the parameter file
// for `rtb gradcheck --smoothing S` (docs/smoothing.md).
TEST(AdjointSmoothing, Table1TrendExactAtEverySmoothing) {
  rtb_params truth;
  rtb_params_default(&truth, RTB_MODEL_RT);
  const std::vector<Record> recs = rtb_test::paper_records(truth, 1.0);
  const rtb_params p0 = table1_point(truth);
  if (const char *dir = std::getenv("RTB_TABLE1_DIR")) {
    for (size_t r = 0; r < recs.size(); ++r)
      write_record_csv(std::string(dir) + "/table1_rec" + std::to_string(r) + ".csv", recs[r].t,
                       recs[r].x, recs[r].F, recs[r].units);
    write_file_atomic(std::string(dir) + "/table1_point.json", params_to_json_text(p0));
  }
  const std::vector<ParamId> core = {P_K0, P_Kpa, P_Kr, P_C0, P_alpha};
  std::vector<Table1Row> rows;
  for (double s : {0.1, 1.0, 10.0, 100.0, 0.0}) {
    rtb_params p = p0;
    p.smoothing = s;
    Table1Row row{s, gradcheck(p, recs, MisfitOptions(), core), {}};
    for (const Record &rec : recs) paper_dot_test(p, rec, row.dot);
    // (a) exact discrete adjoint at every s, unlike the paper's Table 1.
    for (const GradcheckRow &r : row.g.rows)
      EXPECT_LT(r.rel, 1e-6) << "s " << s << " " << param_name(r.id) << " adjoint " << r.adjoint
                             << " fd " << r.fd;
    EXPECT_LT(row.g.dot_product_rel_mismatch, 1e-10) << "s " << s;
    EXPECT_LT(std::fabs(row.dot.aTc - row.dot.bTb), 1e-10 * row.dot.bTb) << "s " << s;
    rows.push_back(row);
  }
  // The table of docs/smoothing.md.
  std::printf("| smoothing | J | dJ/dK0 | dJ/dKpa | dJ/dKr | dJ/dC0 | dJ/dalpha | max rel. diff. "
              "to FD | a^T c | b^T b | rel. mismatch |\n|---|---|---|---|---|---|---|---|---|---|---|\n");
  for (const Table1Row &r : rows) {
    char label[32];
    std::snprintf(label, sizeof label, r.s > 0 ? "s = %g" : "none", r.s);
    std::printf("| %s | %.9g |", label, r.g.J);
    for (const GradcheckRow &gr : r.g.rows) std::printf(" %.7g |", gr.adjoint);
    std::printf(" %.1e | %.12g | %.12g | %.1e |\n", r.g.max_rel_diff, r.dot.aTc, r.dot.bTb,
                std::fabs(r.dot.aTc - r.dot.bTb) / r.dot.bTb);
  }
  // (b) J_s and grad J_s tend to the unsmoothed values as s grows: the
  // distances (gradient in the scaled variables p_i dJ/dp_i) decrease
  // monotonically and are small at s = 100 relative to s = 0.1.
  const Table1Row &none = rows.back();
  std::vector<double> dJ, dg;
  for (size_t i = 0; i + 1 < rows.size(); ++i) {
    dJ.push_back(std::fabs(rows[i].g.J - none.g.J));
    double d2 = 0.0;
    for (size_t k = 0; k < core.size(); ++k) {
      const double e = (rows[i].g.rows[k].adjoint - none.g.rows[k].adjoint) * param_get(p0, core[k]);
      d2 += e * e;
    }
    dg.push_back(std::sqrt(d2));
    std::printf("s = %g: |J_s - J| / J = %.3e, |grad_s - grad| (scaled) = %.3e\n", rows[i].s,
                dJ.back() / none.g.J, dg.back());
  }
  for (size_t i = 1; i < dJ.size(); ++i) {
    EXPECT_LT(dJ[i], dJ[i - 1]) << "s " << rows[i].s;
    EXPECT_LT(dg[i], dg[i - 1]) << "s " << rows[i].s;
  }
  EXPECT_LT(dJ.back(), 0.01 * dJ.front());
  EXPECT_LT(dg.back(), 0.01 * dg.front());
}

TEST(AdjointSmoothing, BackwardEulerAndExtensionsExactWithSmoothing) {
  rtb_params truth;
  rtb_params_default(&truth, RTB_MODEL_RT);
  truth.integrator = RTB_INTEGRATOR_BE;
  const std::vector<Record> recs = rtb_test::paper_records(truth, 0.5);
  for (double s : {0.3, 30.0}) {
    rtb_params p = table1_point(truth);  // as ClearanceContactAndFreePhases
    p.smoothing = s;
    p.backlash = 0.05;
    p.maxwell_k = 100;
    p.maxwell_tau = 0.1;
    p.viscous_c = 0.3;
    expect_exact(p, recs);
  }
}
