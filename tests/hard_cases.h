// hard_cases.h -- parameter sets and inputs where the stepper's bounded loops
// run out of iterations (found by random search over the fuzzers' ranges),
// shared by the tests of the give-up paths and of the settings.
#ifndef RTB_TESTS_HARD_CASES_H
#define RTB_TESTS_HARD_CASES_H

#include "rt_bushing/rt_bushing.h"

namespace rtb_test {

// Near-friction dashpots (alpha = 0.0092), 25 cells, backward Euler: a jump
// of kHardJump from rest in kHardJumpDt needs more than the default 40
// Newton iterations, with backtracking (45 iterations and 3997 units since
// session 22's Gauss-Seidel repair, stage_newton.cpp; half this jump, the
// case until then, now converges in 39 iterations and 2070 units, where it
// took 56 and 2937).
constexpr double kHardJump = -76.6278;   // [mm]
constexpr double kHardJumpDt = 1.05089e-05;  // [s]
inline rtb_params hard_jump_params() {
  rtb_params p;
  rtb_params_default(&p, RTB_MODEL_RT);
  p.integrator = RTB_INTEGRATOR_BE;
  p.cells = 25;
  p.K0 = 3763.64;
  p.Kpa = 285.836;
  p.Kr = 33137.1;
  p.C0 = 568.134;
  p.alpha = 0.0091973;
  return p;
}

}  // namespace rtb_test

#endif
