// new_extensions_test.cpp -- issue #10's extensions of the element against
// closed forms: the relaxation spectrum's exact branch response, the friction
// asymmetry's steady-creep overstress, a held clearance's static limit and a
// slack specimen that never pushes. The adjoint of each is checked in
// adjoint_test.cpp; validation and JSON round trips in io_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "rt_bushing.h"

namespace {

rtb_params rt_default() {
  rtb_params p;
  rtb_params_default(&p, RTB_MODEL_RT);
  return p;
}

// Force history for a displacement history x(t_i), t_i = i dt.
std::vector<double> run(const rtb_params &p, const std::vector<double> &x, double dt,
                        rtb_state *end = nullptr) {
  rtb_state s;
  EXPECT_EQ(rtb_state_init(&s, &p, 0.0), RTB_OK);
  std::vector<double> F(x.size(), 0.0);
  for (size_t i = 1; i < x.size(); ++i) EXPECT_GE(rtb_step(&s, &p, nullptr, x[i], dt, &F[i]), 0);
  if (end) *end = s;
  return F;
}

}  // namespace

// The spectrum adds sum_j k_j (x - z_j) to the force without touching the
// cells; for a ramp to x0 over one step then a hold, each branch is known in
// closed form: z_j(dt) = x0 - x0 tau_j/dt (1 - e^{-dt/tau_j}), then it decays
// towards x0 with e^{-(t-dt)/tau_j}.
TEST(RelaxationSpectrum, StepResponseIsTheExactSumOfBranches) {
  rtb_params p = rt_default();
  rtb_params q = p;
  q.spec_k = 500.0;
  q.spec_exp = 0.4;
  q.spec_tau_min = 1e-3;
  q.spec_tau_max = 10.0;  // four decades: 9 branches
  ASSERT_EQ(rtb_params_validate(&q), RTB_OK);
  const double dt = 1e-3, x0 = 0.5;
  std::vector<double> x(3001, x0);
  x[0] = 0.0;
  const std::vector<double> F0 = run(p, x, dt), F1 = run(q, x, dt);
  // Branch layout: log-spaced, two per decade, weights tau^-beta normalized.
  const int M = 9;
  double w[M], tau[M], sum = 0.0;
  for (int j = 0; j < M; ++j) {
    tau[j] = 1e-3 * std::pow(10.0, j / 2.0);
    w[j] = std::pow(tau[j], -q.spec_exp);
    sum += w[j];
  }
  for (size_t i : {1u, 2u, 10u, 100u, 1000u, 3000u}) {
    const double t = i * dt;
    double expect = 0.0;
    for (int j = 0; j < M; ++j) {
      const double z1 = x0 - x0 * tau[j] / dt * (1.0 - std::exp(-dt / tau[j]));
      const double z = x0 - (x0 - z1) * std::exp(-(t - dt) / tau[j]);
      expect += q.spec_k * w[j] / sum * (x0 - z);
    }
    EXPECT_NEAR(F1[i] - F0[i], expect, 1e-9 * q.spec_k * x0) << "t = " << t;
  }
  // Long memory: at t = 3 s the slow branches still hold a visible force.
  EXPECT_GT(F1[3000] - F0[3000], 0.01 * q.spec_k * x0);
}

// Steady creep under x = v t: each DOF y_k of eq. (2) follows the static
// profile y_k = s_k x (K s = Kpa e1) at velocity v s_k plus a constant lag
// delta with K delta = -f, f_k = C0 (1 +- a) (v s_k)^alpha. The force then
// exceeds the static one by Kpa (K^-1 f)_1 -- larger in the direction of the
// stronger dashpot by exactly (1 + a)/(1 - a). K is solved here by its own
// Thomas sweep, independent of the stepper.
std::vector<double> chain_solve(const rtb_params &p, std::vector<double> r) {
  const int n = p.cells;
  std::vector<double> c(n), d(n);
  for (int k = 0; k < n; ++k) {
    const double di = k == 0 ? p.Kpa + p.Kr : 2.0 * p.Kr, lo = k > 0 ? -p.Kr : 0.0;
    const double den = di - lo * (k > 0 ? c[k - 1] : 0.0);
    c[k] = -p.Kr / den;
    d[k] = (r[k] - lo * (k > 0 ? d[k - 1] : 0.0)) / den;
  }
  for (int k = n - 2; k >= 0; --k) d[k] -= c[k] * d[k + 1];
  return d;
}

TEST(FrictionAsymmetry, SteadyCreepOverstressClosedForm) {
  rtb_params p = rt_default();
  p.fric_asym = 0.4;
  p.alpha = 0.6;  // a chain that settles into steady creep within the record
  ASSERT_EQ(rtb_params_validate(&p), RTB_OK);
  const double v = 0.5, dt = 1e-3;  // mm/s
  const int n = 20000;              // 20 s
  std::vector<double> e1(p.cells, 0.0);
  e1[0] = p.Kpa;
  const std::vector<double> s = chain_solve(p, e1);
  double over[2];
  for (int d = 0; d < 2; ++d) {
    const double dir = d == 0 ? 1.0 : -1.0;
    std::vector<double> x(n + 1);
    for (int i = 0; i <= n; ++i) x[i] = dir * v * i * dt;
    const std::vector<double> F = run(p, x, dt);
    std::vector<double> f(p.cells);
    for (int k = 0; k < p.cells; ++k)
      f[k] = p.C0 * (1.0 + dir * p.fric_asym) * std::pow(v * s[k], p.alpha);
    const double expect = p.Kpa * chain_solve(p, f)[0];
    over[d] = dir * (F[n] - rtb_static_force(&p, x[n]));
    EXPECT_NEAR(over[d], expect, 2e-3 * expect) << "direction " << dir;
  }
  EXPECT_NEAR(over[0] / over[1], 1.4 / 0.6, 1e-2);
}

// A held clearance: after contact the end stays where it was inside the gap,
// and the force relaxes to the static force at that frozen position.
TEST(HeldBacklash, FrozenEndRelaxesToStaticForce) {
  rtb_params p = rt_default();
  p.backlash = 0.2;
  p.backlash_held = 1;
  p.alpha = 0.8;  // relaxes within the hold (alpha = 0.2 would take hours)
  ASSERT_EQ(rtb_params_validate(&p), RTB_OK);
  const double dt = 1e-3;
  std::vector<double> x;
  for (int i = 0; i <= 500; ++i) x.push_back(1.0 * i / 500.0);   // push to 1 mm: contact at x - g/2
  for (int i = 1; i <= 20; ++i) x.push_back(1.0 - 0.1 * i / 20.0);  // back 0.1 mm: inside the gap
  const size_t turn = x.size();
  for (int i = 0; i < 30000; ++i) x.push_back(0.9);                // hold 30 s inside the gap
  rtb_state s;
  const std::vector<double> F = run(p, x, dt, &s);
  EXPECT_EQ(s.contact, 3);
  EXPECT_DOUBLE_EQ(s.xb, 1.0 - 0.5 * p.backlash);  // frozen at the last contact position
  EXPECT_GT(F[turn], 1.02 * rtb_static_force(&p, s.xb));  // still relaxing after the reversal
  EXPECT_NEAR(F.back(), rtb_static_force(&p, s.xb), 1e-4 * F.back());
}

// A slack specimen never pushes: from rest, compression gives zero force;
// in tension it is the plain element until the plain element would push.
TEST(Slack, NeverPushesAndMatchesPlainElementWhileTaut) {
  rtb_params plain = rt_default();
  rtb_params p = plain;
  p.slack = 1;
  ASSERT_EQ(rtb_params_validate(&p), RTB_OK);
  const double dt = 1e-3;
  std::vector<double> x;
  for (int i = 0; i <= 2000; ++i) x.push_back(2.0 * std::sin(2 * M_PI * 1.0 * i * dt));
  rtb_state s;
  const std::vector<double> F = run(p, x, dt, &s), Fp = run(plain, x, dt);
  double most_negative = 0.0;
  int slack_steps = 0;
  const double tiny = 1e-9 * 2.0 * (p.K0 + p.Kpa);  // the free end's root, solved to rounding
  for (size_t i = 1; i < x.size(); ++i) {
    most_negative = std::fmin(most_negative, F[i]);
    slack_steps += std::fabs(F[i]) <= tiny;
  }
  EXPECT_GE(most_negative, -tiny);
  EXPECT_GT(slack_steps, 800);  // the compressive halves and the unloading tails
  // Until the plain element first pushes, the specimen is the plain element.
  size_t i = 1;
  for (; i < x.size() && Fp[i] > 0.0; ++i) EXPECT_EQ(F[i], Fp[i]) << i;
  EXPECT_GT(i, 300u);
  // Second cycle: taut again only once the input has caught up with the
  // floating end (xb >= x while slack).
  EXPECT_GT(F[1250], 0.0);
  // From rest, pure compression: always zero force.
  std::vector<double> xc;
  for (int k = 0; k <= 200; ++k) xc.push_back(-0.001 * k);
  for (double f : run(p, xc, dt)) EXPECT_LE(std::fabs(f), tiny);
}

// A softening spring that takes more than K0 (K0 < 0): the static law
// (K0 + chain) x + Fs tanh(x / d) softens from K0 + chain + Fs/d to
// K0 + chain, and a hold relaxes to it; a slack strip with it floats free and
// never pushes. K0 below -(chain + Fs/d), a negative stiffness at x = 0, is
// refused, naming K0; a large-strain tangent below 0 is allowed, except for
// a slack strip.
TEST(SofteningPastK0, HoldRelaxesToTheStaticLawAndSlackStaysFinite) {
  rtb_params p = rt_default();
  const double chain = 1.0 / (1.0 / p.Kpa + p.cells / p.Kr);  // 160 N/mm
  p.sat_force = 300.0;
  p.sat_disp = 0.5;
  p.alpha = 0.8;  // relaxes within the hold
  for (double K0 : {-0.6 * chain, -1.5 * chain}) {
    p.K0 = K0;
    ASSERT_EQ(rtb_params_validate(&p), RTB_OK);
    const double dt = 1e-3;
    for (double x0 : {2.0, -2.0}) {
      SCOPED_TRACE(x0);
      const double closed = (p.K0 + chain) * x0 + p.sat_force * std::tanh(x0 / p.sat_disp);
      EXPECT_NEAR(rtb_static_force(&p, x0), closed, 1e-12 * std::fabs(closed));
      std::vector<double> x;
      for (int i = 0; i <= 1000; ++i) x.push_back(x0 * i / 1000.0);
      x.resize(x.size() + 30000, x0);
      const std::vector<double> F = run(p, x, dt);
      EXPECT_NEAR(F.back(), closed, 1e-4 * std::fabs(closed));
    }
    // Large-strain tangent of the static law: K0 + chain.
    const double h = 1e-3, X = 5.0;
    EXPECT_NEAR((rtb_static_force(&p, X + h) - rtb_static_force(&p, X - h)) / (2 * h), p.K0 + chain,
                1e-6 * chain);
    rtb_params q = p;
    q.slack = 1;
    if (K0 < -chain) {  // a slack end needs K0 + chain >= 0: a law that rises again
      const char *field = nullptr;
      EXPECT_EQ(rtb_params_check(&q, &field), RTB_ERR_PARAM_RANGE);
      EXPECT_STREQ(field, "K0");
      continue;
    }
    ASSERT_EQ(rtb_params_validate(&q), RTB_OK);
    std::vector<double> x;
    for (int i = 0; i <= 3000; ++i) x.push_back(1.0 * std::sin(2 * M_PI * 1.0 * i * dt));
    // Slack: F >= 0 to the Newton tolerance of its solve (NULL settings).
    rtb_settings set;
    rtb_settings_default(&set);
    const double tiny = std::fmax(1e-9, 2.0 * set.tol) * 2.0 * (std::fabs(q.K0) + q.Kpa);
    for (double f : run(q, x, dt)) {
      ASSERT_TRUE(std::isfinite(f));
      EXPECT_GE(f, -tiny);
    }
  }
  const char *field = nullptr;
  p.K0 = -(chain + p.sat_force / p.sat_disp) * (1.0 + 1e-9);
  EXPECT_EQ(rtb_params_check(&p, &field), RTB_ERR_PARAM_RANGE);
  EXPECT_STREQ(field, "K0");
  p.sat_force = 0.0;
  p.K0 = -0.99 * chain;
  EXPECT_EQ(rtb_params_check(&p, &field), RTB_OK) << field;
}

// Relaxation weakening with stretch (ABI 9). Eq. (2) is homogeneous in
// (Kpa, Kr, C0) and the branches follow xb alone, so along ANY history the
// element with relax_width w gives F_w = K0 x + g(x) (F_0 - K0 x), F_0 the
// element without it, g = 1/sqrt(1 + (x/w)^2). A hold then relaxes to the
// static law K0 x + chain x g(x), and the relaxed fraction F(inf)/F(0+) of a
// fast ramp-and-hold grows with the stretch (VHB 4910's relaxations).
TEST(StretchRelaxation, RelaxingForceScaledAlongAnyHistory) {
  rtb_params p = rt_default();
  p.K0 = 150.0;
  p.alpha = 0.6;  // relaxes within the hold
  p.maxwell_k = 200.0;
  p.maxwell_tau = 0.05;
  p.spec_k = 300.0;
  p.spec_exp = 0.3;
  p.spec_tau_min = 0.002;
  p.spec_tau_max = 2.0;
  rtb_params q = p;
  q.relax_width = 0.4;
  ASSERT_EQ(rtb_params_validate(&q), RTB_OK);
  const double dt = 1e-3;
  auto g = [&](double x) { return 1.0 / std::sqrt(1.0 + (x / q.relax_width) * (x / q.relax_width)); };
  std::vector<double> x;
  for (int i = 0; i <= 4000; ++i) x.push_back(1.2 * std::sin(2 * M_PI * 1.5 * i * dt) * (0.3 + 0.7 * i / 4000.0));
  const std::vector<double> F0 = run(p, x, dt), F1 = run(q, x, dt);
  for (size_t i = 1; i < x.size(); i += 37) {
    const double expect = p.K0 * x[i] + g(x[i]) * (F0[i] - p.K0 * x[i]);
    ASSERT_NEAR(F1[i], expect, 1e-9 * (std::fabs(F0[i]) + 1.0)) << "step " << i;
  }
  // Ramp in 10 ms and hold 40 s (a near-linear dashpot, so the hold relaxes
  // within it): the static law, and a relaxed fraction that grows with the
  // stretch much more than without relax_width.
  p.alpha = q.alpha = 0.95;
  const double chain = 1.0 / (1.0 / p.Kpa + p.cells / p.Kr);
  double frac_w[2], frac_0[2];
  const double amps[2] = {0.2, 1.6};
  for (int k = 0; k < 2; ++k) {
    const double x0 = amps[k];
    std::vector<double> h;
    for (int i = 0; i <= 10; ++i) h.push_back(x0 * i / 10.0);
    h.resize(h.size() + 40000, x0);
    const std::vector<double> H0 = run(p, h, dt), H1 = run(q, h, dt);
    const double closed = p.K0 * x0 + chain * x0 * g(x0);
    EXPECT_NEAR(rtb_static_force(&q, x0), closed, 1e-12 * closed);
    EXPECT_NEAR(H1.back(), closed, 2e-3 * closed);
    frac_w[k] = H1.back() / H1[10];
    frac_0[k] = H0.back() / H0[10];
  }
  std::printf("relaxed fraction at x0 = 0.2, 1.6 mm: %.4f %.4f (w = 0: %.4f %.4f)\n", frac_w[0],
              frac_w[1], frac_0[0], frac_0[1]);
  EXPECT_NEAR(frac_0[1], frac_0[0], 0.05 * frac_0[0]);  // near-linear: about the same
  EXPECT_GT(frac_w[1], 1.5 * frac_w[0]);
}

TEST(NewExtensions, ValidationNamesTheField) {
  rtb_params p = rt_default();
  const char *field = nullptr;
  p.slack = 0.5;
  EXPECT_EQ(rtb_params_check(&p, &field), RTB_ERR_PARAM_RANGE);
  EXPECT_STREQ(field, "slack");
  p = rt_default();
  p.fric_asym = 1.0;
  EXPECT_EQ(rtb_params_check(&p, &field), RTB_ERR_PARAM_RANGE);
  EXPECT_STREQ(field, "fric_asym");
  p = rt_default();
  p.spec_k = 10;
  EXPECT_EQ(rtb_params_check(&p, &field), RTB_ERR_PARAM_RANGE);
  EXPECT_STREQ(field, "spec_tau_min");
  p.spec_tau_min = 1.0;
  p.spec_tau_max = 0.5;
  EXPECT_EQ(rtb_params_check(&p, &field), RTB_ERR_PARAM_RANGE);
  EXPECT_STREQ(field, "spec_tau_max");
  p = rt_default();
  p.Kpa = -1;
  EXPECT_EQ(rtb_params_check(&p, &field), RTB_ERR_PARAM_RANGE);
  EXPECT_STREQ(field, "Kpa");
  p = rt_default();
  p.relax_width = -1.0;
  EXPECT_EQ(rtb_params_check(&p, &field), RTB_ERR_PARAM_RANGE);
  EXPECT_STREQ(field, "relax_width");
  // a slack strip with a bounded relaxing force needs K0 >= 0 (a law that rises again)
  p = rt_default();
  p.relax_width = 1.0;
  p.slack = 1;
  p.K0 = -1.0;
  EXPECT_EQ(rtb_params_check(&p, &field), RTB_ERR_PARAM_RANGE);
  EXPECT_STREQ(field, "K0");
  p.slack = 0;
  EXPECT_EQ(rtb_params_check(&p, &field), RTB_OK) << field;
  p = rt_default();
  EXPECT_EQ(rtb_params_check(&p, &field), RTB_OK);
  EXPECT_STREQ(field, "");
  p.slack = 1;
  p.backlash = 0.1;
  p.backlash_held = 1;
  EXPECT_EQ(rtb_params_check(&p, &field), RTB_ERR_PARAM_RANGE);
  EXPECT_STREQ(field, "backlash_held");
  rtb_params_default(&p, RTB_MODEL_STS);
  p.fric_asym = 0.2;
  EXPECT_EQ(rtb_params_check(&p, &field), RTB_ERR_PARAM_RANGE);
  EXPECT_STREQ(field, "fric_asym");
}

// A kink k_asym |x| may soften one side below K0 alone, K0 < 0 included,
// while the chain holds the static tangent up: |k_asym| <= K0 + chain (+
// sat_force/sat_disp). A hold on either side relaxes to the closed-form
// static law (K0 + chain +- k_asym) x; past the bound the check names
// k_asym; a slack strip and a floating clearance with the softest side at
// the bound stay finite, and the slack one never pushes.
TEST(KinkPastK0, HoldRelaxesToEachSidesStaticTangent) {
  rtb_params p = rt_default();
  const double chain = 1.0 / (1.0 / p.Kpa + p.cells / p.Kr);  // 160 N/mm
  p.alpha = 0.8;  // relaxes within the hold
  p.K0 = -0.5 * chain;
  p.k_asym = -(p.K0 + chain) * 0.999;  // tension tangent ~0, below K0 = -80 alone
  ASSERT_EQ(rtb_params_validate(&p), RTB_OK);
  const double dt = 1e-3;
  for (double x0 : {1.5, -1.5}) {
    SCOPED_TRACE(x0);
    const double closed = (p.K0 + chain) * x0 + p.k_asym * std::fabs(x0);
    EXPECT_NEAR(rtb_static_force(&p, x0), closed, 1e-12 * chain * std::fabs(x0));
    std::vector<double> x;
    for (int i = 0; i <= 1000; ++i) x.push_back(x0 * i / 1000.0);
    x.resize(x.size() + 30000, x0);
    const std::vector<double> F = run(p, x, dt);
    EXPECT_NEAR(F.back(), closed, 1e-4 * chain * std::fabs(x0));
  }
  const char *field = nullptr;
  rtb_params q = p;
  q.k_asym = -(p.K0 + chain) * (1.0 + 1e-9);
  EXPECT_EQ(rtb_params_check(&q, &field), RTB_ERR_PARAM_RANGE);
  EXPECT_STREQ(field, "k_asym");
  q.sat_force = 100.0, q.sat_disp = 0.5;  // the softening spring's tangent counts too
  EXPECT_EQ(rtb_params_check(&q, &field), RTB_OK) << field;
  q = p;
  q.slack = 1, q.relax_width = 1.0;  // with a bounded relaxing force: |k_asym| <= K0 >= 0
  q.K0 = 0.25 * chain, q.k_asym = -0.3 * chain;
  EXPECT_EQ(rtb_params_check(&q, &field), RTB_ERR_PARAM_RANGE);
  EXPECT_STREQ(field, "k_asym");
  std::vector<double> x;
  for (int i = 0; i <= 3000; ++i) x.push_back(1.0 * std::sin(2 * M_PI * 1.0 * i * dt));
  for (int mode = 0; mode < 2; ++mode) {
    q = p;
    if (mode == 0) q.slack = 1;
    else q.backlash = 0.2;  // the end floats inside the gap
    ASSERT_EQ(rtb_params_validate(&q), RTB_OK);
    for (double f : run(q, x, dt)) {
      ASSERT_TRUE(std::isfinite(f));
      if (mode == 0) EXPECT_GE(f, -1e-6 * chain);
    }
  }
}
