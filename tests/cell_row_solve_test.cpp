// cell_row_solve_test.cpp -- the stage solver's repair of a blown-up Newton
// step (stage_newton.cpp, cell_row_solve.h, issue #11): each cell's own row
// of the stage equation, f + a phi(f) = b, solved alone; and near-friction
// elements driven by large displacement jumps, which never converged before
// the repair (every step stopped at the work budget with a relative residual
// near 1, i.e. a wrong force), now converge within the default budget.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "cell_row_solve.h"
#include "rt_bushing/rt_bushing.h"
#include "random_configs.h"

namespace {

using rtb_test::log_uniform;

// Over the whole admissible range of the law (alpha down to RTB_ALPHA_MIN,
// with and without the eq. (14) smoothing and the friction asymmetry) and of
// the row (a = h K_kk and b over ten decades): the returned pair is on the
// dashpot curve, inside the a-priori velocity bracket, and, with eq. (1),
// solves its row to RTB_ROW_SOLVE_TOL within RTB_ROW_SOLVE_EVALS evaluations
// (measured: every draw). A smoothed row takes several psi_s evaluations per
// step in f (its inverse) and keeps one to close a last step in f on the
// curve, so ~15% stop at the cap short of the tolerance (measured 84.9%): a
// weaker repair, which the line search's merit test still judges.
TEST(CellRowSolve, SolvesItsRowOnTheCurve) {
  std::mt19937 g(22);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  int draws[2] = {0, 0}, solved[2] = {0, 0};
  for (int i = 0; i < 20000; ++i) {
    const double C0 = log_uniform(g, 0.1, 1e3);
    const double alpha = log_uniform(g, RTB_ALPHA_MIN, 0.99);
    const double s = u01(g) < 0.5 ? 0.0 : log_uniform(g, 1e-2, 1e4);
    const double asym = u01(g) < 0.7 ? 0.0 : 0.9 * (2.0 * u01(g) - 1.0);
    rtb_law L;
    rtb_law_init(&L, C0, alpha, s, asym);
    const double a = log_uniform(g, 1e-4, 1e5);
    const double b = (u01(g) < 0.5 ? -1.0 : 1.0) * log_uniform(g, 1e-6, 1e6);
    double f, D;
    int evals;
    const double v = rtb_cell_row_solve(&L, a, b, RTB_ROW_SOLVE_EVALS, &f, &D, &evals);
    SCOPED_TRACE(testing::Message() << "C0 " << C0 << " alpha " << alpha << " s " << s
                                    << " asym " << asym << " a " << a << " b " << b);
    ASSERT_GE(evals, 1);
    ASSERT_LE(evals, RTB_ROW_SOLVE_EVALS);
    ASSERT_TRUE(std::isfinite(v) && std::isfinite(f) && std::isfinite(D));
    // b's sign, and the velocity bracket |v| <= |b| / a (psi >= 0 on b's side).
    EXPECT_GE(f * b, 0.0);
    EXPECT_GE(v * b, 0.0);
    EXPECT_LE(std::fabs(v), std::fabs(b) / a * (1.0 + 1e-12));
    // On the curve: f = psi(v) (steps in v) or v = phi(f) (steps in f; a
    // force far below the level has v = 0 to the last subnormal) to
    // rounding, with the level of b's sign.
    const double level = b < 0.0 ? C0 * (1.0 - asym) : C0 * (1.0 + asym);
    const double psi = rtb_dashpot_force(v, level, alpha, s);
    const double phi = rtb_dashpot_velocity(f, level, alpha, s, v);
    const bool on_curve = std::fabs(psi - f) <= 1e-9 * std::fabs(f) ||
                          std::fabs(phi - v) <= 1e-9 * std::fabs(v);
    EXPECT_TRUE(on_curve) << "psi(v) " << psi << " f " << f << " phi(f) " << phi
                                       << " v " << v;
    const bool ok = std::fabs(f + a * v - b) <= RTB_ROW_SOLVE_TOL * std::fabs(b);
    draws[s > 0.0] += 1;
    solved[s > 0.0] += ok;
  }
  EXPECT_EQ(solved[0], draws[0]) << "eq. (1) rows solved";
  EXPECT_GE(solved[1], 0.8 * draws[1]) << solved[1] << " of " << draws[1] << " smoothed rows";
}

struct JumpCase {
  const char *name;
  int cells;
  double alpha, C0, Kr, smoothing, amp;
};

// Elements whose dashpots are near friction (alpha ~ 0.01, or smoothed with
// a level C0 thousands of times below the springs' forces), driven by random
// displacement jumps of +-amp every 1 ms (the inputs of BM_RandomConfigs that
// set its worst cases). Before the repair, the first three never converged:
// 64-200 of 200 steps stopped at the default budget (4096 units) with a
// relative residual ~1, spending 1500-4080 units per step.
TEST(CellRowSolve, NearFrictionJumpsConvergeWithinTheDefaultBudget) {
  const JumpCase cases[] = {
      {"smoothed, alpha 0.06, C0 0.11", 19, 0.06, 0.109, 6.4, 5.83, 971.0},
      {"smoothed, alpha 0.009, C0 2.15", 29, 0.009, 2.15, 3070.0, 95.0, 51.0},
      {"smoothed, alpha 0.0068, C0 0.24", 28, 0.0068, 0.239, 1.73e4, 1150.0, 14.8},
      {"alpha 0.0014", 25, 0.00139, 3.63, 1.31e4, 0.0, 10.0},
  };
  rtb_settings set;
  rtb_settings_default(&set);
  for (const JumpCase &c : cases) {
    for (int integrator : {RTB_INTEGRATOR_SDIRK2, RTB_INTEGRATOR_BE}) {
      SCOPED_TRACE(testing::Message() << c.name << ", integrator " << integrator);
      rtb_params p;
      rtb_params_default(&p, RTB_MODEL_RT);
      p.cells = c.cells;
      p.alpha = c.alpha;
      p.C0 = c.C0;
      p.Kr = c.Kr;
      p.smoothing = c.smoothing;
      p.integrator = integrator;
      rtb_state s;
      ASSERT_EQ(rtb_state_init(&s, &p, 0.0), RTB_OK);
      std::mt19937 g(7);
      std::uniform_real_distribution<double> u(-1.0, 1.0);
      const int steps = 200;
      int not_converged = 0;
      long work = 0;
      for (int i = 0; i < steps; ++i) {
        double F;
        rtb_step_info info;
        const rtb_status st = rtb_step_ex(&s, &p, &set, c.amp * u(g), 1e-3, &F, &info);
        ASSERT_GE(st, 0);
        ASSERT_TRUE(std::isfinite(F));
        not_converged += st == RTB_NOT_CONVERGED;
        if (st == RTB_OK) EXPECT_LE(info.residual, set.tol);
        work += info.work;
      }
      EXPECT_LE(not_converged, 6);               // was 64-200 for the smoothed cases
      EXPECT_LE(work / steps, 600);              // was 1500-4080 units per step
    }
  }
}

}  // namespace
