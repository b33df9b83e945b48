// stuck_cells_test.cpp -- the stage solve's locked cells (stage_newton.cpp,
// issue #11): a cell whose dashpot force keeps its velocity below v_lock is
// held at v = 0 and costs no law evaluation. What must hold is the stage
// equation of eq. (2) over all cells, with the exact law of eq. (1) even for
// the locked ones, to the solver's tolerance; and an element whose dashpots
// all stay below their level is the elastic closed form.
#include <gtest/gtest.h>

#include <cmath>

#include "rt_bushing/rt_bushing.h"
#include "rtb_internal.h"
#include "tests/physics_helpers.h"
#include "tests/stage_residual.h"
#include "test_numbers.h"

namespace {


// The section 3.4 element on the benchmark's 1 mm, 10 Hz sine: the deep
// cells lock (v ~ 1e-26 and below there), and every stage still solves the
// full eq. (2) with the exact law to the tolerance. A load ramp then drives
// the deformation deeper into a 25-cell chain, so that locked cells unlock
// during stages: the same must hold across those.
TEST(StuckCells, LockedStagesSolveTheFullStageEquation) {
  rtb_settings set;
  rtb_settings_default(&set);
  struct Case { int cells; double alpha; int integrator; bool ramp; };
  for (const Case c : {Case{15, 0.2, RTB_INTEGRATOR_SDIRK2, false},
                       Case{15, 0.05, RTB_INTEGRATOR_BE, false},
                       Case{25, 0.1, RTB_INTEGRATOR_SDIRK2, true}}) {
    rtb_params p = rtbtest::paper_params(RTB_MODEL_RT, c.cells, c.integrator);
    p.alpha = c.alpha;
    rtb_state s;
    ASSERT_EQ(rtb_state_init(&s, &p, 0.0), RTB_OK);
    int stages_with_lock = 0, fewer_locked = 0, last_locked = -1;
    double worst = 0.0;
    for (int i = 1; i <= 400; ++i) {
      const double t = i * 1e-3;
      const double x = c.ramp ? 20.0 * t : std::sin(kTwoPi * 10.0 * t);
      rtb_state out;
      rtb_stage st[2];
      double F, dF;
      ASSERT_EQ(rtb_step_detailed(&s, &p, &set, x, 1e-3, &out, &F, &dF, st), RTB_OK) << i;
      for (int j = 0; j < rtb_integrator_stages(&p); ++j) {
        int locked = 0, loaded = 0;
        worst = std::fmax(worst, rtbtest::full_residual(p, st[j], &locked, &loaded));
        stages_with_lock += loaded > 0;
        fewer_locked += last_locked >= 0 && locked < last_locked;
        last_locked = locked;
      }
      s = out;
    }
    EXPECT_LE(worst, 2.0 * set.tol) << c.cells << " cells, alpha " << c.alpha;
    EXPECT_GT(stages_with_lock, 100) << "no cell locked: the case does not test locking";
    if (c.ramp) EXPECT_GT(fewer_locked, 5) << "the ramp should unlock cells as it goes deeper";
  }
}

// Near-friction dashpots (alpha = 0.02) loaded to half their level: every
// cell stays locked, so the element is elastic with its short-time stiffness
// K0 + Kpa (y stays at the virgin 0) and a step evaluates no law at all.
TEST(StuckCells, BelowTheirLevelNearFrictionCellsAreElastic) {
  rtb_params p = rtbtest::paper_params(RTB_MODEL_RT, 15, RTB_INTEGRATOR_SDIRK2);
  p.alpha = 0.02;
  const double amp = 0.5 * p.C0 / p.Kpa;  // the first cell's force reaches C0 / 2
  rtb_state s;
  ASSERT_EQ(rtb_state_init(&s, &p, 0.0), RTB_OK);
  for (int i = 1; i <= 200; ++i) {
    const double x = amp * std::sin(kTwoPi * 10.0 * i * 1e-3);
    double F;
    rtb_step_info info;
    ASSERT_EQ(rtb_step_ex(&s, &p, nullptr, x, 1e-3, &F, &info), RTB_OK) << i;
    EXPECT_EQ(info.work, 0) << i;
    EXPECT_DOUBLE_EQ(F, (p.K0 + p.Kpa) * x) << i;
  }
}

}  // namespace
