// robustness_test.cpp -- contract of the public C API under bad and unusual
// inputs: every error code, "state untouched / output not written" on error,
// finite output for finite input, determinism, evaluate/commit/rollback, the
// analytic tangent dF/dx, and the inspection functions.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <functional>
#include <limits>
#include <random>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "rt_bushing/rt_bushing.h"
#include "tests/random_configs.h"
#include "test_numbers.h"

namespace {

constexpr double kSentinel = -12345.678;

using ::same_bits;  // the doubles' (test_numbers.h), beside the state's below
bool same_bits(const rtb_state &a, const rtb_state &b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

rtb_params defaults(int model = RTB_MODEL_RT) {
  rtb_params p;
  EXPECT_EQ(rtb_params_default(&p, model), RTB_OK);
  return p;
}

rtb_params with_extensions(rtb_params p) {
  p.k3 = 40.0;
  p.k_asym = 150.0;
  p.k2 = 30.0;
  p.maxwell_k = 250.0;
  p.maxwell_tau = 0.03;
  p.viscous_c = 1.5;
  p.mass = 2e-4;
  return p;
}

// A state that has seen some history (non-trivial y, v, x, z, vx ...).
rtb_state stepped_state(const rtb_params &p, int steps = 50) {
  rtb_state s;
  EXPECT_EQ(rtb_state_init(&s, &p, 0.0), RTB_OK);
  for (int i = 1; i <= steps; ++i) {
    double f;
    EXPECT_GE(rtb_step(&s, &p, nullptr, 0.8 * std::sin(kTwoPi * 4.0 * i * 1e-3), 1e-3, &f),
              RTB_OK);
  }
  return s;
}

// ---------------------------------------------------------------- errors
// Calls rtb_step and rtb_evaluate with (p, set, x, dt) on a stepped state
// built from `good`, expects `code` from both, and checks that nothing was
// written: committed state bit-identical, force/dforce untouched.
void expect_rejected(const rtb_params &good, const rtb_params &p, const rtb_settings *set,
                     double x, double dt, rtb_status code, const std::string &what) {
  SCOPED_TRACE(what);
  rtb_state s = stepped_state(good);
  const rtb_state before = s;
  double f = kSentinel;
  EXPECT_EQ(rtb_step(&s, &p, set, x, dt, &f), code);
  EXPECT_TRUE(same_bits(s, before)) << "rtb_step changed the state on error";
  EXPECT_TRUE(same_bits(f, kSentinel)) << "rtb_step wrote the force on error";

  rtb_state trial;
  std::memset(&trial, 0x5a, sizeof trial);
  double df = kSentinel;
  f = kSentinel;
  EXPECT_EQ(rtb_evaluate(&s, &p, set, x, dt, &trial, &f, &df), code);
  EXPECT_TRUE(same_bits(s, before)) << "rtb_evaluate changed the state on error";
  EXPECT_TRUE(same_bits(f, kSentinel)) << "rtb_evaluate wrote the force on error";
  EXPECT_TRUE(same_bits(df, kSentinel)) << "rtb_evaluate wrote dF/dx on error";
}

// A bad parameter set: rejected by validate, by state_init (state untouched)
// and by step/evaluate.
void expect_bad_params(const rtb_params &good, const rtb_params &bad, rtb_status code,
                       const std::string &what) {
  SCOPED_TRACE(what);
  EXPECT_EQ(rtb_params_validate(&bad), code);
  rtb_state s;
  std::memset(&s, 0x33, sizeof s);
  const rtb_state before = s;
  EXPECT_EQ(rtb_state_init(&s, &bad, 0.0), code);
  EXPECT_TRUE(same_bits(s, before)) << "rtb_state_init wrote the state on error";
  expect_rejected(good, bad, nullptr, 0.1, 1e-3, code, what);
}

TEST(RobustErrors, NullPointers) {
  const rtb_params p = defaults();
  rtb_state s = stepped_state(p);
  const rtb_state before = s;
  rtb_state trial;
  double f = kSentinel, df = kSentinel;

  EXPECT_EQ(rtb_params_default(nullptr, RTB_MODEL_RT), RTB_ERR_NULL);
  EXPECT_EQ(rtb_params_validate(nullptr), RTB_ERR_NULL);
  EXPECT_EQ(rtb_state_init(nullptr, &p, 0.0), RTB_ERR_NULL);
  rtb_state s2 = s;
  EXPECT_EQ(rtb_state_init(&s2, nullptr, 0.0), RTB_ERR_NULL);
  EXPECT_TRUE(same_bits(s2, before));

  EXPECT_EQ(rtb_step(nullptr, &p, nullptr, 0.1, 1e-3, &f), RTB_ERR_NULL);
  EXPECT_EQ(rtb_step(&s, nullptr, nullptr, 0.1, 1e-3, &f), RTB_ERR_NULL);
  EXPECT_EQ(rtb_step(&s, &p, nullptr, 0.1, 1e-3, nullptr), RTB_ERR_NULL);
  EXPECT_TRUE(same_bits(s, before));
  EXPECT_TRUE(same_bits(f, kSentinel));

  EXPECT_EQ(rtb_evaluate(nullptr, &p, nullptr, 0.1, 1e-3, &trial, &f, &df), RTB_ERR_NULL);
  EXPECT_EQ(rtb_evaluate(&s, nullptr, nullptr, 0.1, 1e-3, &trial, &f, &df), RTB_ERR_NULL);
  EXPECT_EQ(rtb_evaluate(&s, &p, nullptr, 0.1, 1e-3, nullptr, &f, &df), RTB_ERR_NULL);
  EXPECT_EQ(rtb_evaluate(&s, &p, nullptr, 0.1, 1e-3, &trial, nullptr, &df), RTB_ERR_NULL);
  // trial may not alias the committed state: a status of its own, not "NULL"
  EXPECT_EQ(rtb_evaluate(&s, &p, nullptr, 0.1, 1e-3, &s, &f, &df), RTB_ERR_ALIAS);
  EXPECT_EQ(rtb_evaluate_ex(&s, &p, nullptr, 0.1, 1e-3, &s, &f, &df, nullptr), RTB_ERR_ALIAS);
  EXPECT_TRUE(same_bits(s, before));
  EXPECT_TRUE(same_bits(f, kSentinel));
  EXPECT_TRUE(same_bits(df, kSentinel));
  // dforce_dx may be NULL
  EXPECT_EQ(rtb_evaluate(&s, &p, nullptr, 0.1, 1e-3, &trial, &f, nullptr), RTB_OK);

  EXPECT_EQ(rtb_commit(nullptr, &trial), RTB_ERR_NULL);
  EXPECT_EQ(rtb_commit(&s, nullptr), RTB_ERR_NULL);
  EXPECT_TRUE(same_bits(s, before));

  double out[RTB_MAX_CELLS];
  EXPECT_EQ(rtb_cell_states(nullptr, out, RTB_MAX_CELLS), RTB_ERR_NULL);
  EXPECT_EQ(rtb_cell_states(&s, nullptr, RTB_MAX_CELLS), RTB_ERR_NULL);

  // void functions must tolerate NULL
  rtb_settings_default(nullptr);
  rtb_get_info(nullptr);
  EXPECT_EQ(rtb_static_force(nullptr, 1.0), 0.0);
}

TEST(RobustErrors, AbiVersion) {
  const rtb_params good = defaults();
  for (int abi : {0, RTB_ABI_VERSION - 1, RTB_ABI_VERSION + 1, -1}) {
    if (abi == RTB_ABI_VERSION) continue;
    rtb_params p = good;
    p.abi_version = abi;
    expect_bad_params(good, p, RTB_ERR_ABI, "abi_version " + std::to_string(abi));
  }
}

TEST(RobustErrors, ModelAndIntegrator) {
  const rtb_params good = defaults();
  rtb_params p;
  EXPECT_EQ(rtb_params_default(&p, 0), RTB_ERR_MODEL);
  EXPECT_EQ(rtb_params_default(&p, 3), RTB_ERR_MODEL);
  for (int m : {0, 3, -1, 99}) {
    p = good;
    p.model = m;
    expect_bad_params(good, p, RTB_ERR_MODEL, "model " + std::to_string(m));
  }
  for (int in : {-1, 2, 99}) {
    p = good;
    p.integrator = in;
    expect_bad_params(good, p, RTB_ERR_MODEL, "integrator " + std::to_string(in));
  }
}

TEST(RobustErrors, Cells) {
  const rtb_params good = defaults();
  for (int n : {0, -1, RTB_MAX_CELLS + 1, 1000}) {
    rtb_params p = good;
    p.cells = n;
    expect_bad_params(good, p, RTB_ERR_CELLS, "cells " + std::to_string(n));
  }
  // the limits themselves are valid
  for (int n : {1, RTB_MAX_CELLS}) {
    rtb_params p = good;
    p.cells = n;
    EXPECT_EQ(rtb_params_validate(&p), RTB_OK) << n;
  }
}

// Every floating-point parameter field, by name.
struct Field {
  const char *name;
  rtb_real rtb_params::*member;
};
const Field kFields[] = {
    {"K0", &rtb_params::K0},
    {"Kpa", &rtb_params::Kpa},
    {"Kr", &rtb_params::Kr},
    {"C0", &rtb_params::C0},
    {"alpha", &rtb_params::alpha},
    {"Ff", &rtb_params::Ff},
    {"k3", &rtb_params::k3},
    {"k_asym", &rtb_params::k_asym},
    {"k2", &rtb_params::k2},
    {"maxwell_k", &rtb_params::maxwell_k},
    {"maxwell_tau", &rtb_params::maxwell_tau},
    {"viscous_c", &rtb_params::viscous_c},
    {"mass", &rtb_params::mass},
    {"backlash", &rtb_params::backlash},
    {"mullins", &rtb_params::mullins},
};

TEST(RobustErrors, NonFiniteParameter) {
  for (int model : {RTB_MODEL_RT, RTB_MODEL_STS}) {
    const rtb_params good = defaults(model);
    for (const Field &fd : kFields) {
      for (double bad : {kNaN, kInf, -kInf}) {
        rtb_params p = good;
        p.*fd.member = bad;
        expect_bad_params(good, p, RTB_ERR_PARAM_NONFINITE,
                          std::string(fd.name) + " = " + std::to_string(bad) + " model " +
                              std::to_string(model));
      }
    }
  }
}

TEST(RobustErrors, ParameterRange) {
  const rtb_params good = defaults();
  const rtb_params good_sts = defaults(RTB_MODEL_STS);
  struct Case {
    const char *what;
    std::function<void(rtb_params &)> edit;
  };
  const Case cases[] = {
      {"Kpa < 0", [](rtb_params &p) { p.Kpa = -800.0; }},
      {"Kpa = 0", [](rtb_params &p) { p.Kpa = 0.0; }},
      {"Kr < 0", [](rtb_params &p) { p.Kr = -1.0; }},
      {"Kr = 0", [](rtb_params &p) { p.Kr = 0.0; }},
      {"K0 < -chain", [](rtb_params &p) { p.K0 = -161.0; }},  /* chain 1/(1/800 + 15/3000) = 160 */
      /* the static tangent K0 + chain - |k_asym| = -100 + 160 - 61 < 0 */
      {"|k_asym| > K0 + chain, K0 < 0", [](rtb_params &p) { p.K0 = -100.0; p.k_asym = 61.0; }},
      {"C0 = 0", [](rtb_params &p) { p.C0 = 0.0; }},
      {"C0 < 0", [](rtb_params &p) { p.C0 = -40.0; }},
      {"|k_asym| > K0", [](rtb_params &p) { p.k_asym = 1.5 * p.K0; }},
      {"-k_asym > K0", [](rtb_params &p) { p.k_asym = -1.5 * p.K0; }},
      {"maxwell_k < 0", [](rtb_params &p) { p.maxwell_k = -1.0; p.maxwell_tau = 0.1; }},
      {"maxwell_tau < 0", [](rtb_params &p) { p.maxwell_tau = -0.1; }},
      {"maxwell_k > 0, tau = 0", [](rtb_params &p) { p.maxwell_k = 100.0; p.maxwell_tau = 0.0; }},
      {"viscous_c < 0", [](rtb_params &p) { p.viscous_c = -1.0; }},
      {"mass < 0", [](rtb_params &p) { p.mass = -1.0; }},
      {"backlash < 0", [](rtb_params &p) { p.backlash = -0.1; }},
      {"mullins < 0", [](rtb_params &p) { p.mullins = -0.1; }},
      {"mullins = 1", [](rtb_params &p) { p.mullins = 1.0; }},
  };
  for (const Case &c : cases) {
    rtb_params p = good;
    c.edit(p);
    expect_bad_params(good, p, RTB_ERR_PARAM_RANGE, std::string("RT: ") + c.what);
  }
  for (double ff : {0.0, -40.0}) {
    rtb_params p = good_sts;
    p.Ff = ff;
    expect_bad_params(good_sts, p, RTB_ERR_PARAM_RANGE, "STS Ff " + std::to_string(ff));
  }
}

TEST(RobustErrors, Alpha) {
  const rtb_params good = defaults();
  for (double a : {0.0, 1.0, 1.5, RTB_ALPHA_MIN * 0.5, std::nextafter(RTB_ALPHA_MIN, 0.0), -0.2}) {
    rtb_params p = good;
    p.alpha = a;
    expect_bad_params(good, p, RTB_ERR_ALPHA, "alpha " + std::to_string(a));
  }
  for (double a : {RTB_ALPHA_MIN, 0.5, std::nextafter(1.0, 0.0)}) {
    rtb_params p = good;
    p.alpha = a;
    EXPECT_EQ(rtb_params_validate(&p), RTB_OK) << a;
  }
}

TEST(RobustErrors, ReservedSlots) {
  const rtb_params good = defaults();
  for (int i = 0; i < RTB_N_RESERVED; ++i) {
    for (double v : {1.0, -1e-300, kNaN}) {
      rtb_params p = good;
      p.reserved[i] = v;
      EXPECT_LT(rtb_params_validate(&p), 0) << "reserved[" << i << "] = " << v;
      if (!std::isnan(v))
        expect_bad_params(good, p, RTB_ERR_RESERVED, "reserved[" + std::to_string(i) + "]");
    }
  }
}

TEST(RobustErrors, BadDisplacement) {
  for (int model : {RTB_MODEL_RT, RTB_MODEL_STS}) {
    const rtb_params p = defaults(model);
    for (double x : {kNaN, kInf, -kInf, 1e13, -1e13, std::nextafter(RTB_X_MAX, kInf), 1e300}) {
      expect_rejected(p, p, nullptr, x, 1e-3, RTB_ERR_INPUT, "x = " + std::to_string(x));
    }
    rtb_state s;
    std::memset(&s, 0x11, sizeof s);
    const rtb_state before = s;
    for (double x0 : {kNaN, kInf, 1e13}) {
      EXPECT_EQ(rtb_state_init(&s, &p, x0), RTB_ERR_INPUT) << x0;
      EXPECT_TRUE(same_bits(s, before));
    }
  }
}

TEST(RobustErrors, BadDt) {
  for (int model : {RTB_MODEL_RT, RTB_MODEL_STS}) {
    const rtb_params p = defaults(model);
    for (double dt : {0.0, -0.0, -1e-3, kNaN, kInf, -kInf, RTB_DT_MAX * 2.0,
                      std::nextafter(RTB_DT_MAX, kInf), RTB_DT_MIN * 0.5}) {
      expect_rejected(p, p, nullptr, 0.1, dt, RTB_ERR_DT, "dt = " + std::to_string(dt));
    }
  }
}

TEST(RobustErrors, StateForOtherParameters) {
  const rtb_params rt = defaults(RTB_MODEL_RT);
  const rtb_params sts = defaults(RTB_MODEL_STS);
  rtb_params other_cells = rt;
  other_cells.cells = rt.cells + 1;
  // state of `rt` used with other cells / other model
  expect_rejected(rt, other_cells, nullptr, 0.1, 1e-3, RTB_ERR_STATE, "other cells");
  expect_rejected(rt, sts, nullptr, 0.1, 1e-3, RTB_ERR_STATE, "RT state, STS params");
  expect_rejected(sts, rt, nullptr, 0.1, 1e-3, RTB_ERR_STATE, "STS state, RT params");

  // never initialised
  rtb_state s;
  std::memset(&s, 0, sizeof s);
  const rtb_state before = s;
  double f = kSentinel;
  EXPECT_EQ(rtb_step(&s, &rt, nullptr, 0.1, 1e-3, &f), RTB_ERR_STATE);
  EXPECT_TRUE(same_bits(s, before));
  EXPECT_TRUE(same_bits(f, kSentinel));
  double out[RTB_MAX_CELLS];
  EXPECT_EQ(rtb_cell_states(&s, out, RTB_MAX_CELLS), RTB_ERR_STATE);
  rtb_state trial = s;
  EXPECT_EQ(rtb_commit(&s, &trial), RTB_ERR_STATE);

  // a state whose own abi_version is wrong
  rtb_state t = stepped_state(rt);
  t.abi_version = RTB_ABI_VERSION + 1;
  const rtb_state tb = t;
  EXPECT_EQ(rtb_step(&t, &rt, nullptr, 0.1, 1e-3, &f), RTB_ERR_STATE);
  EXPECT_TRUE(same_bits(t, tb));
  EXPECT_TRUE(same_bits(f, kSentinel));
}

TEST(RobustErrors, BadSettings) {
  const rtb_params p = defaults();
  rtb_settings def;
  rtb_settings_default(&def);
  EXPECT_GE(def.tol, 1e-16);
  EXPECT_GE(def.max_iter, 1);
  EXPECT_LE(def.max_iter, 100);
  struct Case {
    const char *what;
    std::function<void(rtb_settings &)> edit;
  };
  const Case cases[] = {
      {"tol 0", [](rtb_settings &s) { s.tol = 0.0; }},
      {"tol < 0", [](rtb_settings &s) { s.tol = -1e-12; }},
      {"tol NaN", [](rtb_settings &s) { s.tol = kNaN; }},
      {"tol Inf", [](rtb_settings &s) { s.tol = kInf; }},
      {"tol 1", [](rtb_settings &s) { s.tol = 1.0; }},
      {"max_iter 0", [](rtb_settings &s) { s.max_iter = 0; }},
      {"max_iter -5", [](rtb_settings &s) { s.max_iter = -5; }},
      {"max_iter 101", [](rtb_settings &s) { s.max_iter = 101; }},
      {"max_backtrack -1", [](rtb_settings &s) { s.max_backtrack = -1; }},
      {"max_backtrack 61", [](rtb_settings &s) { s.max_backtrack = 61; }},
      {"max_work 0", [](rtb_settings &s) { s.max_work = 0; }},
      {"max_work -1", [](rtb_settings &s) { s.max_work = -1; }},
      {"max_work > RTB_MAX_WORK", [](rtb_settings &s) { s.max_work = RTB_MAX_WORK + 1; }},
  };
  for (int model : {RTB_MODEL_RT, RTB_MODEL_STS}) {
    const rtb_params pm = defaults(model);
    for (const Case &c : cases) {
      rtb_settings set = def;
      c.edit(set);
      expect_rejected(pm, pm, &set, 0.1, 1e-3, RTB_ERR_SETTINGS, c.what);
    }
  }
  // the defaults, passed explicitly, equal NULL
  rtb_state a = stepped_state(p), b = a;
  double fa, fb;
  EXPECT_EQ(rtb_step(&a, &p, nullptr, 0.3, 1e-3, &fa), RTB_OK);
  EXPECT_EQ(rtb_step(&b, &p, &def, 0.3, 1e-3, &fb), RTB_OK);
  EXPECT_TRUE(same_bits(a, b));
  EXPECT_TRUE(same_bits(fa, fb));
}

TEST(RobustErrors, StatusMessages) {
  const int codes[] = {RTB_OK,
                       RTB_NOT_CONVERGED,
                       RTB_ERR_NULL,
                       RTB_ERR_ABI,
                       RTB_ERR_MODEL,
                       RTB_ERR_CELLS,
                       RTB_ERR_PARAM_NONFINITE,
                       RTB_ERR_PARAM_RANGE,
                       RTB_ERR_ALPHA,
                       RTB_ERR_RESERVED,
                       RTB_ERR_INPUT,
                       RTB_ERR_DT,
                       RTB_ERR_STATE,
                       RTB_ERR_OVERFLOW,
                       RTB_ERR_SETTINGS,
                       RTB_ERR_ALIAS,
                       RTB_ERR_CAPACITY};
  std::set<std::string> seen;
  const char *unknown = rtb_status_message(static_cast<rtb_status>(12345));
  ASSERT_NE(unknown, nullptr);
  EXPECT_NE(unknown[0], '\0');
  for (int c : codes) {
    const char *m = rtb_status_message(static_cast<rtb_status>(c));
    ASSERT_NE(m, nullptr) << c;
    EXPECT_GT(std::strlen(m), 0u) << c;
    EXPECT_STRNE(m, unknown) << "code " << c << " has no message of its own";
    EXPECT_TRUE(seen.insert(m).second) << "code " << c << " shares its message: " << m;
  }
  EXPECT_EQ(seen.size(), sizeof codes / sizeof codes[0]);
}

// ---------------------------------------------------------------- finite output
using rtb_test::log_uniform;
using rtb_test::random_params;

std::string describe(const rtb_params &p) {
  char buf[640];
  std::snprintf(buf, sizeof buf,
                "model=%d cells=%d integrator=%d K0=%.17g Kpa=%.17g Kr=%.17g C0=%.17g "
                "alpha=%.17g Ff=%.17g k3=%.17g k_asym=%.17g maxwell_k=%.17g maxwell_tau=%.17g "
                "viscous_c=%.17g mass=%.17g backlash=%.17g mullins=%.17g",
                p.model, p.cells, p.integrator, p.K0, p.Kpa, p.Kr, p.C0, p.alpha, p.Ff, p.k3,
                p.k_asym, p.maxwell_k, p.maxwell_tau, p.viscous_c, p.mass, p.backlash, p.mullins);
  return buf;
}

// Steps p through kSteps random inputs (smooth, random walk, jumps, any
// scale, dt 1e-5 .. 1e-2); a failure is reported with the input history.
void expect_finite_run(std::mt19937 &g, const rtb_params &p, int set, int *failures) {
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  const int kSteps = 400;
  ASSERT_EQ(rtb_params_validate(&p), RTB_OK) << describe(p);
  // Amplitude scale of this sequence: log-uniform over 1e-9 .. 1e3.
  const double amp = log_uniform(g, 1e-9, 1e3);
  rtb_state s;
  ASSERT_EQ(rtb_state_init(&s, &p, 0.0), RTB_OK);
  std::ostringstream history;
  history.precision(17);
  double x = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const double dt = log_uniform(g, 1e-5, 1e-2);
    const double kind = u01(g);
    if (kind < 0.4) {
      x = amp * std::sin(kTwoPi * 5.0 * s.time);  // smooth
    } else if (kind < 0.7) {
      x += amp * (2.0 * u01(g) - 1.0) * 0.1;       // random walk
    } else if (kind < 0.9) {
      x = amp * (2.0 * u01(g) - 1.0);              // jump
    } else {
      x = (u01(g) < 0.5 ? -1.0 : 1.0) * log_uniform(g, 1e-9, 1e3);  // any scale
    }
    history << "(" << x << "," << dt << ") ";
    double f = kSentinel;
    const rtb_status st = rtb_step(&s, &p, nullptr, x, dt, &f);
    if (st < 0 || !std::isfinite(f)) {
      ADD_FAILURE() << "set " << set << " step " << i << ": status " << st << " ("
                    << rtb_status_message(st) << "), force " << f << "\n  params: "
                    << describe(p) << " sat_force=" << p.sat_force << " sat_disp=" << p.sat_disp
                    << " slack=" << p.slack << "\n  (x, dt) history: " << history.str();
      ++*failures;
      return;
    }
  }
}

TEST(RobustFinite, RandomInputsGiveFiniteForce) {
  std::mt19937 g(20130601u);
  int failures = 0;
  for (int set = 0; set < 150 && failures < 5; ++set) expect_finite_run(g, random_params(g), set, &failures);
}

// K0 < 0 under a softening spring (down to the floor -(chain + Fs/d), or
// -chain with a slack end): the static law may fall at large |x|; a slack end
// or a clearance must still give a finite force.
TEST(RobustFinite, SofteningPastK0GivesFiniteForce) {
  std::mt19937 g(20261125u);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  int failures = 0;
  for (int set = 0; set < 80 && failures < 5; ++set) {
    rtb_params p = random_params(g);
    p.k_asym = 0.0;
    p.sat_force = log_uniform(g, 1.0, 1e3);
    p.sat_disp = log_uniform(g, 1e-3, 1.0);
    const double chain = 1.0 / (1.0 / p.Kpa + p.cells / p.Kr), share = u01(g), end = u01(g);
    p.K0 = -share * (chain + p.sat_force / p.sat_disp);
    if (end < 0.3) p.slack = 1.0, p.backlash_held = 0.0, p.K0 = -share * chain;  // floor of a slack end
    else if (end < 0.5 && p.backlash == 0.0) p.backlash = log_uniform(g, 1e-6, 1.0);
    expect_finite_run(g, p, set, &failures);
  }
}

// ---------------------------------------------------------------- determinism
std::vector<double> sine_inputs(int n, double amp, double freq, double dt) {
  std::vector<double> x(n);
  for (int i = 0; i < n; ++i) x[i] = amp * std::sin(kTwoPi * freq * (i + 1) * dt);
  return x;
}

TEST(RobustDeterminism, TwoRunsBitIdentical) {
  for (int model : {RTB_MODEL_RT, RTB_MODEL_STS}) {
    const rtb_params p = with_extensions(defaults(model));
    const std::vector<double> xs = sine_inputs(2000, 1.2, 7.0, 5e-4);
    rtb_state a, b;
    ASSERT_EQ(rtb_state_init(&a, &p, 0.0), RTB_OK);
    ASSERT_EQ(rtb_state_init(&b, &p, 0.0), RTB_OK);
    std::vector<double> fa, fb;
    for (double x : xs) {
      double f;
      ASSERT_GE(rtb_step(&a, &p, nullptr, x, 5e-4, &f), 0);
      fa.push_back(f);
    }
    for (double x : xs) {
      double f;
      ASSERT_GE(rtb_step(&b, &p, nullptr, x, 5e-4, &f), 0);
      fb.push_back(f);
    }
    EXPECT_TRUE(same_bits(a, b)) << model;
    ASSERT_EQ(fa.size(), fb.size());
    EXPECT_EQ(std::memcmp(fa.data(), fb.data(), fa.size() * sizeof(double)), 0) << model;
  }
}

TEST(RobustDeterminism, InterleavedStatesAreIndependent) {
  const rtb_params p1 = with_extensions(defaults(RTB_MODEL_RT));
  rtb_params p2 = defaults(RTB_MODEL_STS);
  p2.cells = 7;
  rtb_params p3 = defaults(RTB_MODEL_RT);
  p3.integrator = RTB_INTEGRATOR_BE;
  p3.alpha = 0.05;
  const std::vector<double> x1 = sine_inputs(1500, 1.0, 3.0, 1e-3);
  const std::vector<double> x2 = sine_inputs(1500, 0.4, 11.0, 1e-3);
  const std::vector<double> x3 = sine_inputs(1500, 2.0, 1.0, 1e-3);

  auto alone = [](const rtb_params &p, const std::vector<double> &xs, std::vector<double> *fs) {
    rtb_state s;
    EXPECT_EQ(rtb_state_init(&s, &p, 0.0), RTB_OK);
    for (double x : xs) {
      double f;
      EXPECT_GE(rtb_step(&s, &p, nullptr, x, 1e-3, &f), 0);
      fs->push_back(f);
    }
    return s;
  };
  std::vector<double> f1, f2, f3;
  const rtb_state a1 = alone(p1, x1, &f1);
  const rtb_state a2 = alone(p2, x2, &f2);
  const rtb_state a3 = alone(p3, x3, &f3);

  rtb_state s1, s2, s3;
  ASSERT_EQ(rtb_state_init(&s1, &p1, 0.0), RTB_OK);
  ASSERT_EQ(rtb_state_init(&s2, &p2, 0.0), RTB_OK);
  ASSERT_EQ(rtb_state_init(&s3, &p3, 0.0), RTB_OK);
  for (size_t i = 0; i < x1.size(); ++i) {
    double g1, g2, g3, df;
    rtb_state trial;
    ASSERT_GE(rtb_step(&s1, &p1, nullptr, x1[i], 1e-3, &g1), 0);
    // extra evaluations of other states in between must not matter
    ASSERT_GE(rtb_evaluate(&s3, &p3, nullptr, x3[i] + 0.5, 1e-3, &trial, &g3, &df), 0);
    ASSERT_GE(rtb_step(&s2, &p2, nullptr, x2[i], 1e-3, &g2), 0);
    ASSERT_GE(rtb_step(&s3, &p3, nullptr, x3[i], 1e-3, &g3), 0);
    ASSERT_TRUE(same_bits(g1, f1[i])) << i;
    ASSERT_TRUE(same_bits(g2, f2[i])) << i;
    ASSERT_TRUE(same_bits(g3, f3[i])) << i;
  }
  EXPECT_TRUE(same_bits(s1, a1));
  EXPECT_TRUE(same_bits(s2, a2));
  EXPECT_TRUE(same_bits(s3, a3));
}

// ---------------------------------------------------------------- evaluate / commit
struct Config {
  const char *name;
  rtb_params p;
};

std::vector<Config> configs() {
  rtb_params rt = defaults(RTB_MODEL_RT);
  rtb_params be = rt;
  be.integrator = RTB_INTEGRATOR_BE;
  rtb_params sts = defaults(RTB_MODEL_STS);
  rtb_params all = with_extensions(rt);
  all.backlash = 0.02;
  all.mullins = 0.25;
  rtb_params sts_all = with_extensions(sts);
  sts_all.backlash = 0.02;
  sts_all.mullins = 0.25;
  return {{"RT_SDIRK2", rt}, {"RT_BE", be}, {"STS", sts}, {"RT_all_ext", all},
          {"STS_all_ext", sts_all}};
}

TEST(RobustEvaluate, EvaluateMatchesStepAndLeavesStateAlone) {
  for (const Config &c : configs()) {
    SCOPED_TRACE(c.name);
    const rtb_params &p = c.p;
    rtb_state s, ref;
    ASSERT_EQ(rtb_state_init(&s, &p, 0.0), RTB_OK);
    ref = s;
    const std::vector<double> xs = sine_inputs(600, 0.9, 6.0, 1e-3);
    for (size_t i = 0; i < xs.size(); ++i) {
      const rtb_state before = s;
      rtb_state trial;
      double fe = kSentinel, df = kSentinel;
      // a few trial points first (a host's Newton loop), then the real one
      for (double dx : {0.05, -0.02, 0.0}) {
        const rtb_status se = rtb_evaluate(&s, &p, nullptr, xs[i] + dx, 1e-3, &trial, &fe, &df);
        ASSERT_GE(se, 0) << i;
        ASSERT_TRUE(same_bits(s, before)) << "rtb_evaluate modified the committed state, step " << i;
      }
      EXPECT_TRUE(std::isfinite(df));
      EXPECT_TRUE(same_bits(trial.force, fe));
      double fs = kSentinel;
      ASSERT_GE(rtb_step(&ref, &p, nullptr, xs[i], 1e-3, &fs), 0);
      ASSERT_TRUE(same_bits(fe, fs)) << "evaluate force " << fe << " != step force " << fs
                                     << " at step " << i;
      ASSERT_TRUE(same_bits(trial, ref)) << "evaluate trial state != stepped state, step " << i;
      ASSERT_EQ(rtb_commit(&s, &trial), RTB_OK);
      ASSERT_TRUE(same_bits(s, ref)) << "commit did not make the trial committed, step " << i;
    }
  }
}

TEST(RobustEvaluate, SaveRestoreReproducesFuture) {
  for (const Config &c : configs()) {
    SCOPED_TRACE(c.name);
    const rtb_params &p = c.p;
    const std::vector<double> xs = sine_inputs(800, 1.1, 4.0, 1e-3);
    rtb_state s;
    ASSERT_EQ(rtb_state_init(&s, &p, 0.0), RTB_OK);
    for (int i = 0; i < 300; ++i) {
      double f;
      ASSERT_GE(rtb_step(&s, &p, nullptr, xs[i], 1e-3, &f), 0);
    }
    const rtb_state saved = s;  // host rollback point: plain struct copy
    std::vector<double> first, second;
    for (size_t i = 300; i < xs.size(); ++i) {
      double f;
      ASSERT_GE(rtb_step(&s, &p, nullptr, xs[i], 1e-3, &f), 0);
      first.push_back(f);
    }
    const rtb_state end1 = s;
    s = saved;
    for (size_t i = 300; i < xs.size(); ++i) {
      double f;
      ASSERT_GE(rtb_step(&s, &p, nullptr, xs[i], 1e-3, &f), 0);
      second.push_back(f);
    }
    EXPECT_TRUE(same_bits(s, end1));
    ASSERT_EQ(first.size(), second.size());
    EXPECT_EQ(std::memcmp(first.data(), second.data(), first.size() * sizeof(double)), 0);
  }
}

// ---------------------------------------------------------------- tangent
// Central finite difference of rtb_evaluate's force in x around the trial
// point, against the analytic dF/dx. Tight solver tolerance so the FD is not
// polluted by the Newton residual.
void check_tangent_rt(const rtb_params &p, const char *name) {
  SCOPED_TRACE(name);
  rtb_settings set;
  rtb_settings_default(&set);
  set.tol = 1e-15;
  const double dt = 1e-3;
  const std::vector<double> xs = sine_inputs(400, 1.0, 5.0, dt);
  rtb_state s;
  ASSERT_EQ(rtb_state_init(&s, &p, 0.0), RTB_OK);
  int checked = 0;
  for (size_t i = 0; i + 1 < xs.size(); ++i) {
    if (i % 23 == 11) {
      const double x = xs[i];
      if (std::fabs(x) < 1e-2) continue;  // k_asym |x| has a kink at 0
      rtb_state trial;
      double f0, df;
      ASSERT_GE(rtb_evaluate(&s, &p, &set, x, dt, &trial, &f0, &df), 0);
      const double h = 1e-6 * std::fmax(1.0, std::fabs(x));
      double fp, fm, dummy;
      ASSERT_GE(rtb_evaluate(&s, &p, &set, x + h, dt, &trial, &fp, &dummy), 0);
      ASSERT_GE(rtb_evaluate(&s, &p, &set, x - h, dt, &trial, &fm, &dummy), 0);
      const double fd = (fp - fm) / (2.0 * h);
      EXPECT_NEAR(df, fd, 1e-6 * std::fabs(df))
          << "step " << i << " x " << x << " analytic " << df << " FD " << fd;
      ++checked;
    }
    double f;
    ASSERT_GE(rtb_step(&s, &p, &set, xs[i], dt, &f), 0);
  }
  EXPECT_GE(checked, 10);
}

TEST(RobustTangent, RtSdirk2) { check_tangent_rt(defaults(), "SDIRK2"); }

TEST(RobustTangent, RtBackwardEuler) {
  rtb_params p = defaults();
  p.integrator = RTB_INTEGRATOR_BE;
  check_tangent_rt(p, "BE");
}

TEST(RobustTangent, RtWithExtensions) {
  for (int integ : {RTB_INTEGRATOR_SDIRK2, RTB_INTEGRATOR_BE}) {
    rtb_params p = with_extensions(defaults());
    p.integrator = integ;
    check_tangent_rt(p, integ == RTB_INTEGRATOR_BE ? "BE + ext" : "SDIRK2 + ext");
  }
}

TEST(RobustTangent, RtOtherShapes) {
  rtb_params p = defaults();
  p.cells = 1;
  p.alpha = 0.6;
  check_tangent_rt(p, "N=1 alpha=0.6");
  p = defaults();
  p.cells = RTB_MAX_CELLS;
  p.alpha = 0.05;
  check_tangent_rt(p, "N=32 alpha=0.05");
}

// STS is piecewise linear in x: at a point the analytic tangent is the slope
// of one of the two adjacent linear pieces, so it must match the forward or
// the backward one-sided difference; away from a slip-onset both agree.
TEST(RobustTangent, StsOneSided) {
  for (bool ext : {false, true}) {
    rtb_params p = defaults(RTB_MODEL_STS);
    if (ext) {
      p.k3 = 40.0;
      p.viscous_c = 1.5;
      p.maxwell_k = 250.0;
      p.maxwell_tau = 0.03;
    }
    SCOPED_TRACE(ext ? "STS + ext" : "STS");
    const double dt = 1e-3;
    const std::vector<double> xs = sine_inputs(400, 1.0, 5.0, dt);
    rtb_state s;
    ASSERT_EQ(rtb_state_init(&s, &p, 0.0), RTB_OK);
    int checked = 0, both = 0;
    for (size_t i = 0; i + 1 < xs.size(); ++i) {
      if (i % 7 == 3) {
        const double x = xs[i];
        rtb_state trial;
        double f0, df;
        ASSERT_GE(rtb_evaluate(&s, &p, nullptr, x, dt, &trial, &f0, &df), 0);
        const double h = 1e-7 * std::fmax(1.0, std::fabs(x));
        double fp, fm, dummy;
        ASSERT_GE(rtb_evaluate(&s, &p, nullptr, x + h, dt, &trial, &fp, &dummy), 0);
        ASSERT_GE(rtb_evaluate(&s, &p, nullptr, x - h, dt, &trial, &fm, &dummy), 0);
        const double fwd = (fp - f0) / h, bwd = (f0 - fm) / h;
        const double tol = 1e-6 * std::fabs(df) + 1e-6;
        const bool ok_f = std::fabs(df - fwd) <= tol, ok_b = std::fabs(df - bwd) <= tol;
        EXPECT_TRUE(ok_f || ok_b) << "step " << i << " x " << x << " analytic " << df
                                  << " forward " << fwd << " backward " << bwd;
        both += ok_f && ok_b;
        ++checked;
      }
      double f;
      ASSERT_GE(rtb_step(&s, &p, nullptr, xs[i], dt, &f), 0);
    }
    EXPECT_GE(checked, 30);
    EXPECT_GE(both, checked / 2) << "the tangent should match both sides away from kinks";
  }
}

// ---------------------------------------------------------------- inspection
TEST(RobustInspect, CellStates) {
  for (int model : {RTB_MODEL_RT, RTB_MODEL_STS}) {
    rtb_params p = defaults(model);
    p.cells = 9;
    const rtb_state s = stepped_state(p, 80);
    double out[RTB_MAX_CELLS + 4];
    for (double &o : out) o = kSentinel;
    EXPECT_EQ(rtb_cell_states(&s, out, RTB_MAX_CELLS + 4), 9);
    for (int k = 0; k < 9; ++k) EXPECT_TRUE(same_bits(out[k], s.y[k])) << k;
    for (int k = 9; k < RTB_MAX_CELLS + 4; ++k) EXPECT_TRUE(same_bits(out[k], kSentinel)) << k;
    bool any_nonzero = false;
    for (int k = 0; k < 9; ++k) any_nonzero |= out[k] != 0.0;
    EXPECT_TRUE(any_nonzero) << "cells did not move";

    for (double &o : out) o = kSentinel;
    EXPECT_EQ(rtb_cell_states(&s, out, 4), 4);  // truncated to cap
    for (int k = 0; k < 4; ++k) EXPECT_TRUE(same_bits(out[k], s.y[k])) << k;
    EXPECT_TRUE(same_bits(out[4], kSentinel));
    for (double &o : out) o = kSentinel;
    EXPECT_EQ(rtb_cell_states(&s, out, 0), 0);
    EXPECT_TRUE(same_bits(out[0], kSentinel));
    // A negative capacity is a caller error of its own (not "NULL", not a count).
    EXPECT_EQ(rtb_cell_states(&s, out, -1), RTB_ERR_CAPACITY);
    EXPECT_EQ(rtb_cell_states(&s, out, -1000), RTB_ERR_CAPACITY);
    EXPECT_TRUE(same_bits(out[0], kSentinel));
  }
}

TEST(RobustInspect, Info) {
  rtb_info info;
  std::memset(&info, 0, sizeof info);
  rtb_get_info(&info);
  EXPECT_EQ(info.abi_version, RTB_ABI_VERSION);
  EXPECT_EQ(info.max_cells, RTB_MAX_CELLS);
  EXPECT_EQ(info.scalar_bytes, RTB_SCALAR_BYTES);
  EXPECT_EQ(info.scalar_bytes, static_cast<int>(sizeof(rtb_real)));
  // The library's struct sizes: a host compiled against another header sees
  // the mismatch at run time.
  EXPECT_EQ(info.params_bytes, static_cast<int>(sizeof(rtb_params)));
  EXPECT_EQ(info.state_bytes, static_cast<int>(sizeof(rtb_state)));
  EXPECT_EQ(info.settings_bytes, static_cast<int>(sizeof(rtb_settings)));
  ASSERT_NE(info.scalar, nullptr);
  EXPECT_STREQ(info.scalar, "double");
  ASSERT_NE(info.version, nullptr);
  unsigned major = 0, minor = 0, patch = 0;
  char tail = 0;
  EXPECT_EQ(std::sscanf(info.version, "%u.%u.%u%c", &major, &minor, &patch, &tail), 3)
      << "version '" << info.version << "' is not major.minor.patch";
}

// The relaxed state at x0, derived by hand (not from rtb_static_force, which
// rtb_state_init itself calls): with every dashpot force zero, Kpa and the N
// springs Kr are in series and carry the same force T = x0 / (1/Kpa + N/Kr);
// the last spring ties to ground, so y_k = (N - k) T / Kr (k = 0 .. N-1), and
// F = K0 x0 + T + k2 x0^2 + k3 x0^3 + k_asym |x0| + sat_force tanh(x0 / sat_disp).
double relaxed_force(const rtb_params &p, double x0) {
  const double T = x0 / (1.0 / p.Kpa + p.cells / p.Kr);
  const double sat = p.sat_force > 0.0 ? p.sat_force * std::tanh(x0 / p.sat_disp) : 0.0;
  return p.K0 * x0 + T + p.k2 * x0 * x0 + p.k3 * x0 * x0 * x0 + p.k_asym * std::fabs(x0) + sat;
}

void expect_relaxed_state(const rtb_params &p, const rtb_state &s, double x0) {
  const double T = x0 / (1.0 / p.Kpa + p.cells / p.Kr);
  double y[RTB_MAX_CELLS];
  ASSERT_EQ(rtb_cell_states(&s, y, RTB_MAX_CELLS), p.cells);
  for (int k = 0; k < p.cells; ++k)
    EXPECT_NEAR(y[k], (p.cells - k) * T / p.Kr, 1e-13 * std::fabs(x0)) << "cell " << k;
  EXPECT_NEAR(s.force, relaxed_force(p, x0), 1e-12 * std::fabs(relaxed_force(p, x0)));
}

TEST(RobustInspect, InitAtOffsetGivesStaticForce) {
  for (double x0 : {0.37, -1.25, 1e-6, 40.0}) {
    for (int variant = 0; variant < 4; ++variant) {
      rtb_params p = defaults();
      if (variant == 1) {
        p.k3 = 40.0;
        p.k_asym = 150.0;
        p.k2 = -25.0;
      }
      if (variant == 2) {
        p = with_extensions(p);
        p.integrator = RTB_INTEGRATOR_BE;
        p.cells = 3;
      }
      if (variant == 3) {  // softening spring
        p.sat_force = 300.0;
        p.sat_disp = 0.4;
      }
      SCOPED_TRACE("x0 " + std::to_string(x0) + " variant " + std::to_string(variant));
      rtb_state s;
      ASSERT_EQ(rtb_state_init(&s, &p, x0), RTB_OK);
      EXPECT_EQ(s.x, x0);
      EXPECT_EQ(s.steps, 0);
      expect_relaxed_state(p, s, x0);
      // rtb_static_force is the same closed form.
      const double fr = relaxed_force(p, x0);
      EXPECT_NEAR(rtb_static_force(&p, x0), fr, 1e-12 * std::fabs(fr));
      // relaxed: holding x0 keeps the static force
      double f = kSentinel;
      for (int i = 0; i < 20; ++i) ASSERT_GE(rtb_step(&s, &p, nullptr, x0, 1e-3, &f), 0);
      EXPECT_NEAR(f, fr, 1e-9 * std::fabs(fr)) << "the initial state was not at equilibrium";
    }
  }
  // STS: initialised at x0 every friction element is unloaded (the same
  // relaxed chain); holding x0 keeps them stuck and the force unchanged.
  rtb_params p = defaults(RTB_MODEL_STS);
  rtb_state s;
  ASSERT_EQ(rtb_state_init(&s, &p, 0.5), RTB_OK);
  expect_relaxed_state(p, s, 0.5);
  double f = kSentinel;
  ASSERT_GE(rtb_step(&s, &p, nullptr, 0.5, 1e-3, &f), 0);
  EXPECT_NEAR(f, relaxed_force(p, 0.5), 1e-12 * relaxed_force(p, 0.5));
}

}  // namespace
