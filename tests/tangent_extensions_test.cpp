// tangent_extensions_test.cpp -- rtb_evaluate's analytic tangent dF/dx
// against central finite differences of its own force, for the extensions
// whose tangent has its own code path: the clearance (contact: dF/dxb; free
// end: 0), Mullins softening (eta(|xb|) below the prior maximum) and the
// softening spring (sat_force/sat_disp sech^2). Along a sine history, at
// every 7th step. A central difference across a kink (contact onset, the
// Mullins maximum, xb = 0 with k_asym) is not a derivative: such points are
// recognised by their one-sided differences disagreeing and skipped, and the
// test requires that they stay a small minority.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "rt_bushing/rt_bushing.h"
#include "test_numbers.h"

namespace {


struct Tally {
  int checked = 0, kinks = 0, free_end = 0, contact = 0;
};

Tally check_tangent(const rtb_params &p, double amp, double freq) {
  Tally t;
  rtb_settings set;
  rtb_settings_default(&set);
  set.tol = 1e-15;  // the FD must not see the Newton residual
  const double dt = 1e-3;
  rtb_state s;
  EXPECT_EQ(rtb_state_init(&s, &p, 0.0), RTB_OK);
  for (int i = 1; i <= 600; ++i) {
    // growing amplitude: Mullins reloads below and beyond its prior maximum
    const double x = amp * (0.4 + 0.6 * i / 600.0) * std::sin(kTwoPi * freq * i * dt);
    if (i % 7 == 3) {
      rtb_state trial;
      double f0, df, fp, fm, d;
      EXPECT_GE(rtb_evaluate(&s, &p, &set, x, dt, &trial, &f0, &df), 0);
      const double h = 1e-6 * std::fmax(1.0, std::fabs(x));
      EXPECT_GE(rtb_evaluate(&s, &p, &set, x + h, dt, &trial, &fp, &d), 0);
      EXPECT_GE(rtb_evaluate(&s, &p, &set, x - h, dt, &trial, &fm, &d), 0);
      const double fwd = (fp - f0) / h, bwd = (f0 - fm) / h, fd = (fp - fm) / (2 * h);
      // Scale of the force-displacement slope for absolute tolerances.
      const double k = p.K0 + p.Kpa;
      if (std::fabs(fwd - bwd) > 1e-4 * k) {
        ++t.kinks;
      } else {
        EXPECT_NEAR(df, fd, 1e-6 * std::fabs(fd) + 1e-7 * k)
            << "step " << i << " x " << x << " analytic " << df << " FD " << fd;
        ++t.checked;
      }
      rtb_state tr;
      EXPECT_GE(rtb_evaluate(&s, &p, &set, x, dt, &tr, &f0, &d), 0);
      if (p.backlash > 0.0) {
        const bool contact = tr.xb == x - 0.5 * p.backlash || tr.xb == x + 0.5 * p.backlash;
        contact ? ++t.contact : ++t.free_end;
      }
    }
    double f;
    EXPECT_GE(rtb_step(&s, &p, &set, x, dt, &f), 0);
  }
  return t;
}

rtb_params paper() {
  rtb_params p;
  rtb_params_default(&p, RTB_MODEL_RT);
  return p;
}

TEST(TangentExtensions, Clearance) {
  for (int integ : {RTB_INTEGRATOR_SDIRK2, RTB_INTEGRATOR_BE}) {
    rtb_params p = paper();
    p.integrator = integ;
    p.backlash = 0.15;
    SCOPED_TRACE(integ);
    const Tally t = check_tangent(p, 1.0, 3.0);
    EXPECT_GE(t.checked, 70);
    EXPECT_LE(t.kinks, 6);
    EXPECT_GE(t.contact, 40) << "the history must load the bushing through the clearance";
    EXPECT_GE(t.free_end, 5) << "the history must cross the gap";
  }
}

// Linear shape with both integrators; Ogden-Roxburgh's erf shape (ABI 8)
// on K0 and on the whole force: smooth below the max, so no more kinks than
// the linear shape.
TEST(TangentExtensions, Mullins) {
  const struct { int integ; double width, whole; } cases[] = {
      {RTB_INTEGRATOR_SDIRK2, 0.0, 0.0}, {RTB_INTEGRATOR_BE, 0.0, 0.0},
      {RTB_INTEGRATOR_SDIRK2, 0.3, 0.0}, {RTB_INTEGRATOR_SDIRK2, 0.3, 1.0}};
  for (const auto &c : cases) {
    rtb_params p = paper();
    p.integrator = c.integ;
    p.mullins = 0.4;
    p.mullins_width = c.width;
    p.mullins_whole = c.whole;
    SCOPED_TRACE(testing::Message() << c.integ << " w " << c.width << " whole " << c.whole);
    const Tally t = check_tangent(p, 1.0, 3.0);
    EXPECT_GE(t.checked, 75);
    EXPECT_LE(t.kinks, 6);
  }
}

// Relaxation weakening with stretch (ABI 9): g(xb) and its slope enter the
// tangent with the chain's and the branches' own dependence on xb; smooth.
TEST(TangentExtensions, StretchDependentRelaxation) {
  rtb_params p = paper();
  p.relax_width = 0.5;
  p.maxwell_k = 200;
  p.maxwell_tau = 0.02;
  p.spec_k = 300;
  p.spec_exp = 0.2;
  p.spec_tau_min = 0.002;
  p.spec_tau_max = 2.0;
  const Tally t = check_tangent(p, 1.0, 3.0);
  EXPECT_GE(t.checked, 80);
  EXPECT_LE(t.kinks, 2);
}

TEST(TangentExtensions, WholeForceMullins) {
  for (int model : {RTB_MODEL_RT, RTB_MODEL_STS}) {
    rtb_params p;
    rtb_params_default(&p, model);
    p.mullins = 0.4;
    p.mullins_whole = 1.0;
    SCOPED_TRACE(model);
    const Tally t = check_tangent(p, 1.0, 3.0);
    EXPECT_GE(t.checked, model == RTB_MODEL_RT ? 75 : 40);
    EXPECT_LE(t.kinks, model == RTB_MODEL_RT ? 6 : 45);
  }
}

TEST(TangentExtensions, SofteningSpring) {
  for (int integ : {RTB_INTEGRATOR_SDIRK2, RTB_INTEGRATOR_BE}) {
    rtb_params p = paper();
    p.integrator = integ;
    p.sat_force = 400.0;
    p.sat_disp = 0.25;
    SCOPED_TRACE(integ);
    const Tally t = check_tangent(p, 1.0, 3.0);
    EXPECT_EQ(t.kinks, 0) << "the softening spring is smooth";
    EXPECT_GE(t.checked, 80);
  }
}

TEST(TangentExtensions, AllTogetherWithStsToo) {
  for (int model : {RTB_MODEL_RT, RTB_MODEL_STS}) {
    rtb_params p;
    rtb_params_default(&p, model);
    p.backlash = 0.1;
    p.mullins = 0.3;
    p.sat_force = 300.0;
    p.sat_disp = 0.3;
    p.k3 = 20.0;
    p.k2 = 40.0;
    p.maxwell_k = 200.0;
    p.maxwell_tau = 0.02;
    SCOPED_TRACE(model);
    const Tally t = check_tangent(p, 1.0, 3.0);
    // STS is piecewise linear: slip onsets are kinks too.
    EXPECT_GE(t.checked, model == RTB_MODEL_RT ? 70 : 40);
    EXPECT_LE(t.kinks, model == RTB_MODEL_RT ? 10 : 45);
  }
}

}  // namespace
