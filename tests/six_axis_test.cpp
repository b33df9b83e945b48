// six_axis_test.cpp -- the six-axis bushing (rt_bushing.h, "Six-axis bushing")
// against six independent single-axis elements: bit-for-bit forces and
// tangents per channel, zero on an off axis, all-or-nothing commit on an
// error in any one axis.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "rt_bushing/rt_bushing.h"

namespace {

// Six different channels: RT SDIRK2, RT BE, STS, RT with extensions, RT N = 5,
// and the last one off (its parameters deliberately invalid: ignored).
rtb_bushing6_params mixed_params() {
  rtb_bushing6_params p;
  EXPECT_EQ(rtb_bushing6_params_default(&p, RTB_MODEL_RT), RTB_OK);
  p.axis[RTB_AXIS_Y].integrator = RTB_INTEGRATOR_BE;
  rtb_params_default(&p.axis[RTB_AXIS_Z], RTB_MODEL_STS);
  p.axis[RTB_AXIS_RX].k3 = 50.0;
  p.axis[RTB_AXIS_RX].viscous_c = 2.0;
  p.axis[RTB_AXIS_RX].backlash = 0.01;
  p.axis[RTB_AXIS_RY].cells = 5;
  p.axis[RTB_AXIS_RY].Kpa = 2e4;
  p.active[RTB_AXIS_RZ] = 0;
  p.axis[RTB_AXIS_RZ].alpha = 7.0;
  return p;
}

double axis_input(int axis, int i) {
  return (0.2 + 0.1 * axis) * std::sin(2.0 * M_PI * (1.0 + axis) * i * 1e-3);
}

TEST(SixAxis, EachChannelIsTheSingleAxisElementBitForBit) {
  const rtb_bushing6_params p = mixed_params();
  rtb_bushing6_state s;
  int bad = 99;
  ASSERT_EQ(rtb_bushing6_init(&s, &p, nullptr, &bad), RTB_OK);
  EXPECT_EQ(bad, -1);
  rtb_state one[RTB_AXES];
  for (int a = 0; a < RTB_AXES - 1; ++a) ASSERT_EQ(rtb_state_init(&one[a], &p.axis[a], 0.0), RTB_OK);

  for (int i = 1; i <= 300; ++i) {
    const double dt = i % 3 ? 1e-3 : 0.5e-3;  // variable step sizes
    double x[RTB_AXES], F[RTB_AXES], K[RTB_AXES];
    for (int a = 0; a < RTB_AXES; ++a) x[a] = axis_input(a, i);
    rtb_bushing6_state trial;
    ASSERT_GE(rtb_bushing6_evaluate(&s, &p, nullptr, x, dt, &trial, F, K, &bad), 0);
    ASSERT_EQ(rtb_bushing6_commit(&s, &trial), RTB_OK);
    for (int a = 0; a < RTB_AXES - 1; ++a) {
      rtb_state t;
      double f1, k1;
      ASSERT_GE(rtb_evaluate(&one[a], &p.axis[a], nullptr, x[a], dt, &t, &f1, &k1), 0);
      one[a] = t;
      ASSERT_EQ(F[a], f1) << rtb_axis_name(a) << " step " << i;
      ASSERT_EQ(K[a], k1) << rtb_axis_name(a) << " step " << i;
      ASSERT_EQ(std::memcmp(&s.axis[a], &one[a], sizeof one[a]), 0);
    }
    EXPECT_EQ(F[RTB_AXIS_RZ], 0.0);
    EXPECT_EQ(K[RTB_AXIS_RZ], 0.0);
  }
  // The channels really differ (the comparison above is not of six copies).
  EXPECT_NE(s.axis[RTB_AXIS_Z].model, s.axis[RTB_AXIS_X].model);
  EXPECT_NE(s.axis[RTB_AXIS_X].force, 0.0);
}

TEST(SixAxis, StepEqualsEvaluateThenCommit) {
  const rtb_bushing6_params p = mixed_params();
  rtb_bushing6_state a, b;
  ASSERT_EQ(rtb_bushing6_init(&a, &p, nullptr, nullptr), RTB_OK);
  b = a;
  for (int i = 1; i <= 50; ++i) {
    double x[RTB_AXES], Fa[RTB_AXES], Fb[RTB_AXES];
    for (int k = 0; k < RTB_AXES; ++k) x[k] = axis_input(k, i);
    rtb_bushing6_state t;
    ASSERT_GE(rtb_bushing6_step(&a, &p, nullptr, x, 1e-3, Fa, nullptr), 0);
    ASSERT_GE(rtb_bushing6_evaluate(&b, &p, nullptr, x, 1e-3, &t, Fb, nullptr, nullptr), 0);
    rtb_bushing6_commit(&b, &t);
    ASSERT_EQ(std::memcmp(Fa, Fb, sizeof Fa), 0);
  }
  EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0);
}

TEST(SixAxis, ErrorOnAnyAxisLeavesEverythingUnchanged) {
  const rtb_bushing6_params p = mixed_params();
  rtb_bushing6_state s;
  ASSERT_EQ(rtb_bushing6_init(&s, &p, nullptr, nullptr), RTB_OK);
  double x[RTB_AXES] = {0.1, 0.1, 0.1, 0.1, 0.1, 0.1}, F[RTB_AXES];
  ASSERT_GE(rtb_bushing6_step(&s, &p, nullptr, x, 1e-3, F, nullptr), 0);
  for (int a = 0; a < RTB_AXES - 1; ++a) {
    const rtb_bushing6_state before = s;
    double y[RTB_AXES] = {0.2, 0.2, 0.2, 0.2, 0.2, 0.2};
    y[a] = NAN;
    double G[RTB_AXES] = {7, 7, 7, 7, 7, 7};
    int bad = -7;
    EXPECT_EQ(rtb_bushing6_step(&s, &p, nullptr, y, 1e-3, G, &bad), RTB_ERR_INPUT);
    EXPECT_EQ(bad, a);
    EXPECT_EQ(std::memcmp(&s, &before, sizeof s), 0) << rtb_axis_name(a);
    for (double g : G) EXPECT_EQ(g, 7.0);
  }
  // The off axis ignores its input, even a NaN.
  double y[RTB_AXES] = {0.2, 0.2, 0.2, 0.2, 0.2, NAN};
  EXPECT_GE(rtb_bushing6_step(&s, &p, nullptr, y, 1e-3, F, nullptr), 0);
  EXPECT_EQ(F[RTB_AXIS_RZ], 0.0);
}

TEST(SixAxis, BadParametersNameTheAxis) {
  rtb_bushing6_params p = mixed_params();
  rtb_bushing6_state s;
  ASSERT_EQ(rtb_bushing6_init(&s, &p, nullptr, nullptr), RTB_OK);
  const rtb_bushing6_state before = s;
  int bad = -7;
  p.axis[RTB_AXIS_RY].Kr = -1.0;
  EXPECT_EQ(rtb_bushing6_validate(&p, &bad), RTB_ERR_PARAM_RANGE);
  EXPECT_EQ(bad, RTB_AXIS_RY);
  double x[RTB_AXES] = {0}, F[RTB_AXES];
  EXPECT_EQ(rtb_bushing6_step(&s, &p, nullptr, x, 1e-3, F, &bad), RTB_ERR_PARAM_RANGE);
  EXPECT_EQ(bad, RTB_AXIS_RY);
  EXPECT_EQ(std::memcmp(&s, &before, sizeof s), 0);

  p = mixed_params();
  p.active[RTB_AXIS_Y] = 2;
  EXPECT_EQ(rtb_bushing6_validate(&p, &bad), RTB_ERR_MODEL);
  EXPECT_EQ(bad, RTB_AXIS_Y);
  // Switching an axis on or off needs a new state.
  p = mixed_params();
  p.active[RTB_AXIS_RZ] = 1;
  p.axis[RTB_AXIS_RZ].alpha = 0.2;
  EXPECT_EQ(rtb_bushing6_step(&s, &p, nullptr, x, 1e-3, F, &bad), RTB_ERR_STATE);
  EXPECT_EQ(bad, RTB_AXIS_RZ);
  const rtb_bushing6_params good = mixed_params();
  EXPECT_EQ(rtb_bushing6_step(&s, &good, nullptr, x, -1e-3, F, &bad), RTB_ERR_DT);
  EXPECT_EQ(bad, -1);
  EXPECT_EQ(std::memcmp(&s, &before, sizeof s), 0);
}

TEST(SixAxis, NullPointersAndNames) {
  rtb_bushing6_params p = mixed_params();
  rtb_bushing6_state s, t;
  double x[RTB_AXES] = {0}, F[RTB_AXES];
  EXPECT_EQ(rtb_bushing6_params_default(nullptr, RTB_MODEL_RT), RTB_ERR_NULL);
  EXPECT_EQ(rtb_bushing6_params_default(&p, 9), RTB_ERR_MODEL);
  EXPECT_EQ(rtb_bushing6_init(nullptr, &p, nullptr, nullptr), RTB_ERR_NULL);
  p = mixed_params();
  ASSERT_EQ(rtb_bushing6_init(&s, &p, nullptr, nullptr), RTB_OK);
  EXPECT_EQ(rtb_bushing6_step(&s, &p, nullptr, nullptr, 1e-3, F, nullptr), RTB_ERR_NULL);
  EXPECT_EQ(rtb_bushing6_step(&s, &p, nullptr, x, 1e-3, nullptr, nullptr), RTB_ERR_NULL);
  EXPECT_EQ(rtb_bushing6_evaluate(&s, &p, nullptr, x, 1e-3, &s, F, nullptr, nullptr), RTB_ERR_NULL);
  EXPECT_EQ(rtb_bushing6_evaluate(&s, nullptr, nullptr, x, 1e-3, &t, F, nullptr, nullptr),
            RTB_ERR_NULL);
  EXPECT_EQ(rtb_bushing6_commit(nullptr, &t), RTB_ERR_NULL);
  EXPECT_STREQ(rtb_axis_name(RTB_AXIS_RY), "ry");
  EXPECT_EQ(rtb_axis_name(6), nullptr);
  // A nonzero start: every on axis starts relaxed at its x0.
  const double x0[RTB_AXES] = {0.1, -0.2, 0.3, 0.01, 0.02, 5.0};
  ASSERT_EQ(rtb_bushing6_init(&s, &p, x0, nullptr), RTB_OK);
  EXPECT_EQ(s.axis[RTB_AXIS_X].force, rtb_static_force(&p.axis[RTB_AXIS_X], 0.1));
  EXPECT_EQ(s.axis[RTB_AXIS_RZ].initialised, 0);
}

}  // namespace
