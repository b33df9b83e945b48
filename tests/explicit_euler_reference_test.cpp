// explicit_euler_reference_test.cpp -- the library's SDIRK2 stepper against an
// independent integrator: the seed paper's explicit Euler on the primal form
// y' = phi(b - K y) (bench/reference_explicit_euler.h, section 3.5), which
// shares no code with the library (its own phi, its own force assembly, no
// Newton solve). Explicit Euler is first order in its substep h, so with h
// and h/2 its own error is estimated as |F_h - F_h/2| and the Richardson
// combination 2 F_h/2 - F_h is second order. SDIRK2 at dt = 1e-5 s has a
// relative error near 1e-8 (docs/accuracy.md); the converged explicit
// reference must agree with it to within its own error estimate, and the
// extrapolated one far more closely.
//
// Case: N = 15, K0 = 1000, Kpa = 800, Kr = 3000 N/mm, C0 = 40 N (s/mm)^0.5,
// alpha = 0.5 (the stable substep of explicit Euler shrinks like |f|^-(1/alpha-1),
// so alpha = 0.5 keeps the reference cheap), 1 mm, 10 Hz sine for one cycle,
// host step 1e-5 s, 10 and 20 explicit substeps per host step.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "bench/reference_explicit_euler.h"
#include "rt_bushing/rt_bushing.h"
#include "test_numbers.h"

namespace {

constexpr double kEeDt = 1e-5, kEeFreq = 10.0, kEeAmp = 1.0;
constexpr int kSteps = 10000;  // one cycle

double ee_input(int i) { return kEeAmp * std::sin(kTwoPi * kEeFreq * i * kEeDt); }

std::vector<double> explicit_euler(const rtb_params &p, int substeps, bool *stable) {
  rtb_ref::ExplicitEuler ee;
  ee.init(p);
  std::vector<double> F(kSteps + 1, 0.0);
  for (int i = 1; i <= kSteps; ++i) F[i] = ee.step(ee_input(i), kEeDt, substeps);
  *stable = ee.finite;
  return F;
}

TEST(ExplicitEulerReference, Sdirk2AgreesWithAConvergedIndependentIntegrator) {
  rtb_params p;
  rtb_params_default(&p, RTB_MODEL_RT);
  p.alpha = 0.5;
  rtb_state s;
  ASSERT_EQ(rtb_state_init(&s, &p, 0.0), RTB_OK);
  std::vector<double> lib(kSteps + 1, 0.0);
  for (int i = 1; i <= kSteps; ++i) ASSERT_EQ(rtb_step(&s, &p, nullptr, ee_input(i), kEeDt, &lib[i]), RTB_OK);

  bool stable1 = false, stable2 = false;
  const std::vector<double> e1 = explicit_euler(p, 10, &stable1);
  const std::vector<double> e2 = explicit_euler(p, 20, &stable2);
  ASSERT_TRUE(stable1 && stable2);

  double fmax = 0, est = 0, d_ee = 0, d_rich = 0;
  for (int i = 1; i <= kSteps; ++i) {
    fmax = std::fmax(fmax, std::fabs(lib[i]));
    est = std::fmax(est, std::fabs(e1[i] - e2[i]));                   // EE error at h/2
    d_ee = std::fmax(d_ee, std::fabs(lib[i] - e2[i]));
    d_rich = std::fmax(d_rich, std::fabs(lib[i] - (2.0 * e2[i] - e1[i])));
  }
  est /= fmax;
  d_ee /= fmax;
  d_rich /= fmax;
  std::printf("[ee] peak %.6g N; explicit Euler error estimate %.3e; |SDIRK2 - EE(h/2)| %.3e; "
              "|SDIRK2 - Richardson| %.3e (relative to the peak)\n",
              fmax, est, d_ee, d_rich);
  // The reference is converged far beyond what is being compared ...
  EXPECT_LT(est, 1e-4);
  // ... SDIRK2 agrees with it within its own first-order error (the
  // difference IS that error: est is its estimate) ...
  EXPECT_NEAR(d_ee, est, 0.25 * est);
  // ... and with the second-order extrapolation an order of magnitude closer.
  EXPECT_LT(d_rich, 0.1 * est);
}

}  // namespace
