// physics_test.cpp -- the behaviours of the RT and STS models that Puel,
// Bourgeteau & Aubry (2013) describe in sections 3 to 5, checked against
// closed forms from the paper (or derived here from eq. (2)) and against
// converged references.
//
// Every test prints the numbers it measures ("[phys] ...") so that a run of
//   rtb_tests --gtest_filter='Physics*'
// documents the model's behaviour.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "tests/physics_helpers.h"

using namespace rtbtest;

namespace {

// Tolerance of the comparisons with the paper's closed forms (1 %).
constexpr double kPaperTol = 0.01;

::testing::AssertionResult RelNear(double measured, double expected, double tol) {
  const double err = std::fabs(measured - expected) / std::fabs(expected);
  if (err <= tol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "measured " << measured << " expected " << expected
                                       << " (relative error " << err << " > " << tol << ")";
}

// ------------------------------------------------------------------ STS loops

struct StsLoop {
  Trace tr;
  Window w;
  rtbtest::LoopFeatures L;
  double tg1_top, tg2_top, tg1_bottom, tg2_bottom;  // chords next to both cusps
};

// Stabilised loop of the STS model under a triangular displacement of
// amplitude X (3 cycles, the last one measured). The STS step is
// rate-independent, so the sampling only has to put the tips on the grid
// (samples_per_cycle divisible by 4) and keep one sample step inside the
// first (all-stuck) segment after a cusp.
StsLoop run_sts_loop(const rtb_params &p, double X, int samples_per_cycle = 4000) {
  StsLoop r;
  const double f = 1.0, dt = 1.0 / (f * samples_per_cycle);
  r.tr = simulate(p, Triangle{X, f}, dt, 3L * samples_per_cycle);
  r.w = last_cycle(r.tr, samples_per_cycle);
  r.L = loop_features(r.tr, r.w);
  std::size_t itop = r.w.first, ibot = r.w.first;
  for (std::size_t i = r.w.first; i <= r.w.last; ++i) {
    if (r.tr.x[i] > r.tr.x[itop]) itop = i;
    if (r.tr.x[i] < r.tr.x[ibot]) ibot = i;
  }
  // The tips are interior samples of the last cycle (it starts and ends at x=0).
  r.tg2_top = chord(r.tr, itop - 1, itop);
  r.tg1_top = chord(r.tr, itop, itop + 1);
  r.tg2_bottom = chord(r.tr, ibot - 1, ibot);
  r.tg1_bottom = chord(r.tr, ibot, ibot + 1);
  return r;
}

}  // namespace

// Hand calculation for N = 3 (K0=1000, Kpa=800, Kr=3000 N/mm, Ff=40 N).
// Virgin loading of the ladder of eq. (2) with friction elements: DOF 1 slips
// when the Kpa spring load P exceeds Ff, DOF 2 when the spring Kr between
// DOFs 1 and 2 carries more than Ff, i.e. P > 2 Ff, DOF 3 when P > 3 Ff.
// At P = 3 Ff = 120 N (DOFs 1, 2 slipping, DOF 3 just at its threshold):
//   spring loads 120, 80, 40, 0 N  ->  y1 = 0.04, y2 = 0.04 - 80/3000,
//   y3 = 0, x = 120/800 + 0.04 = 0.19 mm, F = K0 x + P = 190 + 120 = 310 N.
// Eq. (20) (with K0 = K0^S) gives 620 N = 2 x 310 N: it is the peak-to-peak
// force of the loop of amplitude 0.19 mm, which is what the code produces.
TEST(PhysicsSts, HandCheckThreeCells) {
  const rtb_params p = sts_params(3, 1000.0, 800.0, 3000.0, 40.0);
  const StsClosedForm c = sts_closed_form(p);
  EXPECT_DOUBLE_EQ(c.X_star, 0.19);
  EXPECT_DOUBLE_EQ(c.F_max, 310.0);
  EXPECT_DOUBLE_EQ(c.eq20, 620.0);

  // Virgin ramp to x = 0.19 mm in small steps.
  rtb_state s;
  ASSERT_EQ(rtb_state_init(&s, &p, 0.0), RTB_OK);
  double F = 0.0;
  const int n = 1900;
  for (int i = 1; i <= n; ++i) ASSERT_GE(rtb_step(&s, &p, nullptr, 0.19 * i / n, 1e-3, &F), 0);
  double y[3];
  ASSERT_EQ(rtb_cell_states(&s, y, 3), 3);
  EXPECT_NEAR(F, 310.0, 1e-9);
  EXPECT_NEAR(y[0], 0.04, 1e-12);
  EXPECT_NEAR(y[1], 0.04 - 80.0 / 3000.0, 1e-12);
  EXPECT_NEAR(y[2], 0.0, 1e-12);

  // Stabilised loop at that amplitude: F(+X) = 310 N, F(-X) = -310 N.
  const StsLoop r = run_sts_loop(p, c.X_star);
  ASSERT_TRUE(r.tr.ok());
  EXPECT_NEAR(r.L.F_at_xmax, 310.0, 1e-9);
  EXPECT_NEAR(r.L.F_at_xmin, -310.0, 1e-9);
  EXPECT_NEAR(r.L.F_max - r.L.F_min, 620.0, 1e-9);
}

// Section 5.4, eq. (17)-(20): features of the stabilised STS loop when exactly
// N-1 cells are loaded, for N = 15 and N = 9, under a triangular displacement
// (and N = 10: the "N odd" proviso of eq. (17) is not needed for this chain).
// "Exactly N-1 cells loaded" is the largest amplitude before DOF N slips:
// X* = N Ff/Kpa + N(N-1) Ff/(2 Kr) (derivation in physics_helpers.h), where
// Fmax = K0 X* + N Ff = Ksec X*.
TEST(PhysicsSts, LoopFeaturesMatchEq17To20) {
  for (int N : {15, 9, 10}) {
    SCOPED_TRACE(testing::Message() << "N = " << N);
    const rtb_params p = sts_params(N, 1000.0, 800.0, 3000.0, 40.0);
    const StsClosedForm c = sts_closed_form(p);
    const StsLoop r = run_sts_loop(p, c.X_star);
    ASSERT_TRUE(r.tr.ok()) << rtb_status_message(r.tr.worst);
    ASSERT_EQ(r.tr.not_converged, 0);

    std::printf("[phys] STS N=%d X*=%.4f mm: Tg1 %.3f/%.3f (eq.18) Tg2 %.3f/%.3f (eq.19) "
                "Ksec %.3f/%.3f (eq.17) Fmax %.3f/%.3f (K0 X*+N Ff), range %.3f/%.3f (eq.20)\n",
                N, c.X_star, r.tg1_top, c.Tg1, r.tg2_top, c.Tg2, r.L.secant_loop, c.Ksec,
                r.L.F_max, c.F_max, r.L.F_max - r.L.F_min, c.eq20);

    // Tangent just after a cusp (both cusps), eq. (18).
    EXPECT_TRUE(RelNear(r.tg1_top, c.Tg1, kPaperTol));
    EXPECT_TRUE(RelNear(r.tg1_bottom, c.Tg1, kPaperTol));
    // Tangent just before a cusp, eq. (19).
    EXPECT_TRUE(RelNear(r.tg2_top, c.Tg2, kPaperTol));
    EXPECT_TRUE(RelNear(r.tg2_bottom, c.Tg2, kPaperTol));
    // Secant stiffness through the two extreme points, eq. (17).
    EXPECT_TRUE(RelNear(r.L.secant_loop, c.Ksec, kPaperTol));
    // Maximal force: K0 X* + N Ff, which is Ksec X*, i.e. F_max = K_sec X_max.
    EXPECT_TRUE(RelNear(r.L.F_max, c.F_max, kPaperTol));
    EXPECT_TRUE(RelNear(c.F_max, c.Ksec * c.X_star, 1e-12));
    EXPECT_TRUE(RelNear(r.L.F_max, c.Ksec * r.L.x_max, kPaperTol));
    // Eq. (20) literally (K0 read as K0^S) is the peak-to-peak force.
    EXPECT_TRUE(RelNear(r.L.F_max - r.L.F_min, c.eq20, kPaperTol));
    EXPECT_TRUE(RelNear(c.eq20, 2.0 * c.F_max, 1e-12));
  }
}

// The amplitude matters: reading eq. (20) as the force at amplitude
// X = eq20/Ksec (= 2 X*) overloads the chain, all N cells slip, and the loop
// no longer has the features of eq. (17)/(19)/(20); the tangent before the
// cusp becomes the fully relaxed stiffness K0 + 1/(1/Kpa + N/Kr). Below X*
// (0.9 X*) the tangents still follow eq. (18)/(19) but Ksec exceeds eq. (17).
TEST(PhysicsSts, FeaturesRequireExactlyNMinus1CellsLoaded) {
  const int N = 15;
  const rtb_params p = sts_params(N, 1000.0, 800.0, 3000.0, 40.0);
  const StsClosedForm c = sts_closed_form(p);

  const StsLoop over = run_sts_loop(p, c.eq20 / c.Ksec);
  ASSERT_TRUE(over.tr.ok());
  EXPECT_NEAR(c.eq20 / c.Ksec, 2.0 * c.X_star, 1e-12);
  EXPECT_TRUE(RelNear(over.tg2_top, static_force_closed_form(p, 1.0), 1e-9));
  EXPECT_LT(over.L.F_max, 0.97 * c.eq20);           // 5244 N, not 5500 N
  EXPECT_LT(over.L.secant_loop, 0.97 * c.Ksec);      // 1219.5, not 1279.1 N/mm

  const StsLoop under = run_sts_loop(p, 0.9 * c.X_star);
  ASSERT_TRUE(under.tr.ok());
  EXPECT_TRUE(RelNear(under.tg1_top, c.Tg1, kPaperTol));
  EXPECT_TRUE(RelNear(under.tg2_top, c.Tg2, kPaperTol));
  EXPECT_GT(under.L.secant_loop, 1.005 * c.Ksec);
  std::printf("[phys] STS N=15 at 2X*: Fmax %.1f (eq.20 %.1f) Ksec %.2f (eq.17 %.2f) Tg2 %.2f;"
              " at 0.9X*: Ksec %.2f\n",
              over.L.F_max, c.eq20, over.L.secant_loop, c.Ksec, over.tg2_top,
              under.L.secant_loop);
}

// Eq. (21)-(24) invert the features. Fed with the measured Tg1, Tg2 and the
// peak-to-peak force and displacement (the reading under which eq. (20) holds)
// they return the simulated STS parameters; fed with the amplitudes (Fmax, X*)
// instead, (21)-(23) are unchanged (homogeneous of degree 0) but (24) returns
// Ff/2. A second STS model built from the inverted parameters for another N
// reproduces the same loop features (the basis of the Figure 5 scaling).
TEST(PhysicsSts, InversionEq21To24RoundTrip) {
  const rtb_params p = sts_params(15, 1000.0, 800.0, 3000.0, 40.0);
  const StsClosedForm c = sts_closed_form(p);
  const StsLoop r = run_sts_loop(p, c.X_star);
  ASSERT_TRUE(r.tr.ok());
  const double range_F = r.L.F_at_xmax - r.L.F_at_xmin, range_x = r.L.x_max - r.L.x_min;

  const rtbtest::StsParams inv = sts_invert(r.tg1_top, r.tg2_top, range_F, range_x, 15);
  EXPECT_TRUE(RelNear(inv.K0, p.K0, kPaperTol));
  EXPECT_TRUE(RelNear(inv.Kpa, p.Kpa, kPaperTol));
  EXPECT_TRUE(RelNear(inv.Kr, p.Kr, kPaperTol));
  EXPECT_TRUE(RelNear(inv.Ff, p.Ff, kPaperTol));

  const rtbtest::StsParams amp = sts_invert(r.tg1_top, r.tg2_top, r.L.F_at_xmax, r.L.x_max, 15);
  EXPECT_TRUE(RelNear(amp.Kr, p.Kr, kPaperTol));
  EXPECT_TRUE(RelNear(amp.Ff, 0.5 * p.Ff, kPaperTol));

  // Same features with N = 9.
  const rtbtest::StsParams inv9 = sts_invert(r.tg1_top, r.tg2_top, range_F, range_x, 9);
  const rtb_params p9 = sts_params(9, inv9.K0, inv9.Kpa, inv9.Kr, inv9.Ff);
  const StsClosedForm c9 = sts_closed_form(p9);
  EXPECT_TRUE(RelNear(c9.X_star, c.X_star, 1e-9));
  const StsLoop r9 = run_sts_loop(p9, c9.X_star);
  ASSERT_TRUE(r9.tr.ok());
  EXPECT_TRUE(RelNear(r9.tg1_top, r.tg1_top, kPaperTol));
  EXPECT_TRUE(RelNear(r9.tg2_top, r.tg2_top, kPaperTol));
  EXPECT_TRUE(RelNear(r9.L.secant_loop, r.L.secant_loop, kPaperTol));
  EXPECT_TRUE(RelNear(r9.L.F_max, r.L.F_max, kPaperTol));
}

// ------------------------------------------------------------------ relaxation

// Section 3.4 / 5.5, Figure 6 (right): a 1 mm step with a 0.1 s rise, then a
// hold. The force decays monotonically toward the static limit
// K0 x + x/(1/Kpa + N/Kr) and never crosses it. With the dashpot law (1),
// v = (f/C0)^(1/alpha), the relaxation is a power law, not an exponential:
// the chain equations are homogeneous of degree 1/alpha in the dashpot
// forces, so the excess force decays as t^(-alpha/(1-alpha)) = t^(-1/4) for
// alpha = 0.2. The test checks that rate (which pins the limit: an excess
// measured against a wrong limit would not halve every factor 16 in time) and
// that after 10^6 s of hold the force is within 1 % of the static force.
// The hold is integrated with steps growing geometrically (2 % of the
// elapsed hold time, at most 500 s < RTB_DT_MAX), which the L-stable SDIRK2
// allows.
TEST(PhysicsRelaxation, RtDecaysMonotonicallyToStaticLimit) {
  const rtb_params p = paper_params(RTB_MODEL_RT);
  const double X = 1.0, rise = 0.1, t_end = 1e6;
  const double F_static = static_force_closed_form(p, X);
  EXPECT_NEAR(rtb_static_force(&p, X), F_static, 1e-12 * F_static);
  EXPECT_DOUBLE_EQ(F_static, 1160.0);

  std::vector<double> grid;
  const double dt_rise = 1e-4;
  for (long i = 0; i <= steps_for(rise, dt_rise); ++i) grid.push_back(i * dt_rise);
  grid.back() = rise;
  while (grid.back() < t_end) {
    const double t = grid.back();
    const double h = std::min(std::max(dt_rise, 0.02 * (t - rise)), 500.0);
    grid.push_back(std::min(t + h, t_end));
  }
  const Trace tr = simulate_on_grid(p, RampHold{X, rise}, grid);
  ASSERT_TRUE(tr.ok()) << rtb_status_message(tr.worst);
  ASSERT_EQ(tr.t.size(), grid.size());

  const std::size_t i_rise = static_cast<std::size_t>(steps_for(rise, dt_rise));
  const double F_peak = tr.F[i_rise];
  EXPECT_GT(F_peak, F_static + 200.0);  // 1418 N: strongly rate-dependent
  bool monotone = true, above = true;
  for (std::size_t i = i_rise + 1; i < tr.F.size(); ++i) {
    if (tr.F[i] > tr.F[i - 1] + 1e-9 * F_static) monotone = false;
    if (!(tr.F[i] > F_static)) above = false;
  }
  EXPECT_TRUE(monotone) << "force increased during the hold";
  EXPECT_TRUE(above) << "force undershot the static limit";

  // Power-law tail: excess(16 t) / excess(t) -> 16^(-alpha/(1-alpha)) = 1/2.
  const double expo = p.alpha / (1.0 - p.alpha);
  const double ex_a = force_at(tr, 1e4) - F_static, ex_b = force_at(tr, 1.6e5) - F_static;
  const double ratio = ex_b / ex_a, expected = std::pow(16.0, -expo);
  EXPECT_TRUE(RelNear(ratio, expected, 0.02));

  const double ex_end = tr.F.back() - F_static;
  EXPECT_LT(ex_end, 0.01 * F_static);
  EXPECT_GT(ex_end, 0.0);
  std::printf("[phys] RT relaxation 1 mm: F(0.1 s)=%.2f F(1 s)=%.2f F(100 s)=%.2f F(1e6 s)=%.2f "
              "static=%.2f; excess ratio 1.6e5 s/1e4 s = %.4f (16^-%.2f = %.4f); %ld steps, "
              "%ld not converged\n",
              F_peak, force_at(tr, 1.0), force_at(tr, 100.0), tr.F.back(), F_static, ratio, expo,
              expected, tr.steps, tr.not_converged);
}

// Figure 8: the STS model under the same input shows no relaxation at all;
// the load reached at the end of the rise is held exactly (rate-independent
// friction), while the RT load drops. The STS load is above the static force
// (friction holds part of the load in the cells).
TEST(PhysicsRelaxation, StsShowsNoRelaxation) {
  const double X = 1.0, rise = 0.1, dt = 1e-3, T = 10.0;
  const rtb_params sts = paper_params(RTB_MODEL_STS);
  const rtb_params rt = paper_params(RTB_MODEL_RT);
  const Trace ts = simulate(sts, RampHold{X, rise}, dt, steps_for(T, dt));
  const Trace tr = simulate(rt, RampHold{X, rise}, dt, steps_for(T, dt));
  ASSERT_TRUE(ts.ok());
  ASSERT_TRUE(tr.ok());
  const std::size_t i_rise = static_cast<std::size_t>(steps_for(rise, dt));
  const double Fs0 = ts.F[i_rise];
  double drift = 0.0;
  for (std::size_t i = i_rise; i < ts.F.size(); ++i) drift = std::max(drift, std::fabs(ts.F[i] - Fs0));
  EXPECT_LE(drift, 1e-9 * Fs0);
  EXPECT_GT(Fs0, static_force_closed_form(sts, X) + 100.0);

  // Normalised by their maximum load (as in Figure 8): RT loses > 10 % within
  // 10 s, STS nothing.
  const double rt_norm_end = tr.F.back() / tr.F[i_rise];
  EXPECT_LT(rt_norm_end, 0.90);
  EXPECT_DOUBLE_EQ(ts.F.back() / Fs0, 1.0);
  std::printf("[phys] Figure 8: normalised load at 10 s: RT %.4f, STS %.4f (STS load %.2f N)\n",
              rt_norm_end, ts.F.back() / Fs0, Fs0);
}

// ------------------------------------------------------------------ frequency / amplitude

namespace {

// Secant stiffness (max load / max displacement, section 3.4) on the last of
// 4 cycles of x = A sin(2 pi f t), spc samples per cycle.
double sine_secant(const rtb_params &p, double A, double f, int spc, Trace *out = nullptr) {
  Trace tr = simulate(p, Sine{A, f}, 1.0 / (f * spc), 4L * spc);
  EXPECT_TRUE(tr.ok()) << rtb_status_message(tr.worst);
  const double k = loop_features(tr, last_cycle(tr, spc)).secant_paper;
  if (out) *out = std::move(tr);
  return k;
}

}  // namespace

// Section 3.4, Figure 6 (left): dynamic stiffening. K0=1000, Kpa=800,
// Kr=3000 N/mm, C0=40 N (s/mm)^0.2, alpha=0.2, N=15, 1 mm sines at 1, 10 and
// 100 Hz. The paper reports +4 % (1 -> 10 Hz) and +4.5 % (10 -> 100 Hz).
// Band [3 %, 7 %] per decade: it contains the paper's values, and it rejects
// a dashpot exponent off by a factor of two (alpha = 0.1 gives 2.4 % per
// decade, alpha = 0.4 gives 8-9.5 %; the increase per decade is roughly
// proportional to alpha since the dashpot force scales as (omega A)^alpha).
// Time step: 1000 samples per cycle, checked against 2000.
TEST(PhysicsDynamicStiffening, SecantGrowsFourToFivePercentPerDecade) {
  const rtb_params p = paper_params(RTB_MODEL_RT);
  std::vector<double> k;
  for (double f : {1.0, 10.0, 100.0}) {
    const double k1 = sine_secant(p, 1.0, f, 1000), k2 = sine_secant(p, 1.0, f, 2000);
    EXPECT_TRUE(RelNear(k1, k2, 1e-5)) << "not converged in dt at " << f << " Hz";
    k.push_back(k2);
  }
  const double inc1 = k[1] / k[0] - 1.0, inc2 = k[2] / k[1] - 1.0;
  std::printf("[phys] dynamic stiffening: Ksec(1 Hz)=%.3f Ksec(10 Hz)=%.3f Ksec(100 Hz)=%.3f N/mm;"
              " +%.2f %% and +%.2f %% per decade (paper: 4 %% and 4.5 %%)\n",
              k[0], k[1], k[2], 100 * inc1, 100 * inc2);
  EXPECT_GT(k[1], k[0]);
  EXPECT_GT(k[2], k[1]);
  EXPECT_GE(inc1, 0.03);
  EXPECT_LE(inc1, 0.07);
  EXPECT_GE(inc2, 0.03);
  EXPECT_LE(inc2, 0.07);
}

// Section 2.2 / 3.4: Payne effect. At 1 Hz the secant stiffness drops as the
// amplitude grows (0.01, 0.03, 0.1, 0.3 mm), by at least 1 % per step. The
// limits are closed forms: for a vanishing amplitude the dashpots are rigid
// (psi'(0) is infinite in eq. (1)), so the secant tends to K0 + Kpa; it never
// goes below the fully relaxed static stiffness K0 + 1/(1/Kpa + N/Kr).
TEST(PhysicsPayne, SecantDecreasesWithAmplitude) {
  const rtb_params p = paper_params(RTB_MODEL_RT);
  const double k_small_limit = p.K0 + p.Kpa;
  const double k_static = static_force_closed_form(p, 1.0);
  std::vector<double> k;
  for (double A : {0.01, 0.03, 0.1, 0.3}) k.push_back(sine_secant(p, A, 1.0, 1000));
  std::printf("[phys] Payne 1 Hz: Ksec(0.01)=%.2f Ksec(0.03)=%.2f Ksec(0.1)=%.2f Ksec(0.3)=%.2f"
              " N/mm (limits %.0f and %.0f)\n",
              k[0], k[1], k[2], k[3], k_small_limit, k_static);
  for (std::size_t i = 1; i < k.size(); ++i) EXPECT_LT(k[i], 0.99 * k[i - 1]) << "step " << i;
  EXPECT_TRUE(RelNear(k[0], k_small_limit, 0.005));
  for (double ki : k) {
    EXPECT_LE(ki, k_small_limit * (1.0 + 1e-9));
    EXPECT_GT(ki, k_static);
  }
}

// ------------------------------------------------------------------ number of cells

// Section 3.4, Figure 5: loops for different N with parameters chosen so the
// loops have the same features. The STS inversion (21)-(24) shows how: for
// fixed Tg1, Tg2, Fmax, Xmax, K0 and Kpa do not depend on N, Kr scales with
// N-1 and Ff with 1/N. The RT chains use the same scaling (Kr_N =
// Kr (N-1)/14, C0_N = C0 15/N, from the N = 15 example; eq. (26) maps Ff to
// C0). Under a quasi-static 1 mm triangle (0.5 Hz) the loops for N = 10, 15,
// 20 agree within 1 % of Fmax, and the spread among them is below a fifth of
// the N = 2 vs N = 5 difference; the differences shrink as N grows.
TEST(PhysicsCellCount, LoopsConvergeForTenCellsOrMore) {
  const rtb_params s15 = sts_params(15, 1000.0, 800.0, 3000.0, 40.0);
  const StsClosedForm c = sts_closed_form(s15);
  const int spc = 2000;
  const double f = 0.5, A = 1.0;
  const std::vector<int> Ns = {2, 5, 10, 15, 20};
  std::vector<Trace> tr;
  for (int N : Ns) {
    const rtbtest::StsParams inv = sts_invert(c.Tg1, c.Tg2, 2.0 * c.F_max, 2.0 * c.X_star, N);
    EXPECT_TRUE(RelNear(inv.K0, 1000.0, 1e-9));
    EXPECT_TRUE(RelNear(inv.Kpa, 800.0, 1e-9));
    EXPECT_TRUE(RelNear(inv.Kr, 3000.0 * (N - 1) / 14.0, 1e-9));
    EXPECT_TRUE(RelNear(inv.Ff, 40.0 * 15.0 / N, 1e-9));
    rtb_params p = paper_params(RTB_MODEL_RT, N);
    p.K0 = inv.K0;
    p.Kpa = inv.Kpa;
    p.Kr = inv.Kr;
    p.C0 = 40.0 * 15.0 / N;
    tr.push_back(simulate(p, Triangle{A, f}, 1.0 / (f * spc), 3L * spc));
    ASSERT_TRUE(tr.back().ok()) << "N = " << N;
  }
  const Window w = last_cycle(tr[0], spc);
  auto diff = [&](int a, int b) { return max_abs_diff(tr[a], tr[b], w); };
  const double Fmax = loop_features(tr[3], w).F_max;
  const double d2_5 = diff(0, 1), d5_10 = diff(1, 2), d10_15 = diff(2, 3), d15_20 = diff(3, 4),
               d10_20 = diff(2, 4);
  std::printf("[phys] Figure 5: Fmax(N=15)=%.1f N; max |dF|: N2-N5 %.2f, N5-N10 %.2f, "
              "N10-N15 %.2f, N15-N20 %.2f, N10-N20 %.2f N\n",
              Fmax, d2_5, d5_10, d10_15, d15_20, d10_20);
  const double spread = std::max({d10_15, d15_20, d10_20});
  EXPECT_LT(spread, 0.01 * Fmax);
  EXPECT_LT(spread, 0.2 * d2_5);
  EXPECT_LT(d15_20, d10_15);
  EXPECT_LT(d10_15, d5_10);
}

// ------------------------------------------------------------------ memory

// Section 3.5, Figure 9 (evanescent memory): two successive 0.1 s-rise steps,
// the second at t = 2 s, in the same direction (0 -> 1 -> 2 mm) or in the
// opposite direction (0 -> 1 -> 0 mm, and 0 -> 1 -> -1 mm). The paper plots
// the load normalised by its value at the start of the second hold and finds
// the relaxation "stronger" for opposite rotations. Measure: the fraction of
// the load lost during the 4 s of the second hold,
//   R = (F(t2 + rise) - F(t2 + rise + 4 s)) / F(t2 + rise).
// Measured: 8.1 % (same), 61 % (back to 0), 14.6 % (to -1 mm). Asserted with
// margin: R_back > 3 R_same, R_reverse > 1.4 R_same. The first step leaves a
// memory: returning to x = 0 leaves a load of opposite sign that decays
// toward the static value 0 without changing sign. Converged in dt (1e-3 s
// and 5e-4 s agree to 1e-5 in R).
TEST(PhysicsMemory, OppositeSecondStepRelaxesMore) {
  const rtb_params p = paper_params(RTB_MODEL_RT);
  const double dt = 1e-3, rise = 0.1, t2 = 2.0, T = t2 + rise + 4.0;
  struct Case {
    double X2;
    double F_start, F_end, R;
  };
  std::vector<Case> cases = {{1.0, 0, 0, 0}, {-1.0, 0, 0, 0}, {-2.0, 0, 0, 0}};
  for (Case &c : cases) {
    const Trace tr = simulate(p, TwoSteps{1.0, c.X2, rise, t2}, dt, steps_for(T, dt));
    ASSERT_TRUE(tr.ok());
    c.F_start = tr.F[static_cast<std::size_t>(steps_for(t2 + rise, dt))];
    c.F_end = tr.F.back();
    c.R = (c.F_start - c.F_end) / c.F_start;
    // Monotone relaxation during the second hold, toward the static load.
    const double Fs = static_force_closed_form(p, 1.0 + c.X2);
    EXPECT_GT(c.R, 0.0);
    EXPECT_GT((c.F_end - Fs) * (c.F_start - Fs), 0.0) << "crossed the static load";
  }
  const Case &same = cases[0], &back = cases[1], &rev = cases[2];
  std::printf("[phys] Figure 9: relative relaxation in the 2nd hold: same %.2f %%, back to 0 "
              "%.2f %%, reversed %.2f %% (loads %.1f->%.1f, %.1f->%.1f, %.1f->%.1f N)\n",
              100 * same.R, 100 * back.R, 100 * rev.R, same.F_start, same.F_end, back.F_start,
              back.F_end, rev.F_start, rev.F_end);
  EXPECT_GT(back.R, 3.0 * same.R);
  EXPECT_GT(rev.R, 1.4 * same.R);
  // Memory of the first step: back at x = 0 the load is negative (hysteresis)
  // and still non-zero 4 s later.
  EXPECT_LT(back.F_start, -100.0);
  EXPECT_LT(back.F_end, -20.0);
}

// ------------------------------------------------------------------ static limit

// Quasi-static loading: 1 mm triangles at 1, 0.1, 0.01 and 0.001 Hz. The
// force follows the static line K0 x + x/(1/Kpa + N/Kr) plus a hysteresis
// offset (max |F - F_static(x)| over the stabilised loop) that shrinks as the
// rate drops. Closed form of the limit: slowing the input by a factor s is
// the same as keeping the rate and multiplying C0 by s^alpha (eq. (1) is
// homogeneous of degree alpha in the velocity), and for C0 -> 0 the offset is
// proportional to C0; hence offset ~ rate^alpha and the ratio per decade
// tends to 10^-alpha = 0.631 (measured 0.742, 0.662, 0.631).
TEST(PhysicsQuasiStatic, HysteresisOffsetShrinksAsRateToTheAlpha) {
  const rtb_params p = paper_params(RTB_MODEL_RT);
  const int spc = 2000;
  std::vector<double> offset;
  for (double f : {1.0, 0.1, 0.01, 0.001}) {
    const Trace tr = simulate(p, Triangle{1.0, f}, 1.0 / (f * spc), 3L * spc);
    ASSERT_TRUE(tr.ok());
    const Window w = last_cycle(tr, spc);
    double off = 0.0;
    for (std::size_t i = w.first; i <= w.last; ++i)
      off = std::max(off, std::fabs(tr.F[i] - static_force_closed_form(p, tr.x[i])));
    offset.push_back(off);
  }
  const double expected = std::pow(10.0, -p.alpha);
  std::printf("[phys] quasi-static offsets (1, 0.1, 0.01, 0.001 Hz): %.2f %.2f %.2f %.2f N;"
              " ratios %.4f %.4f %.4f (10^-alpha = %.4f)\n",
              offset[0], offset[1], offset[2], offset[3], offset[1] / offset[0],
              offset[2] / offset[1], offset[3] / offset[2], expected);
  for (std::size_t i = 1; i < offset.size(); ++i) EXPECT_LT(offset[i], 0.8 * offset[i - 1]);
  EXPECT_TRUE(RelNear(offset[3] / offset[2], expected, 0.05));
  EXPECT_LT(offset[3], 0.07 * static_force_closed_form(p, 1.0));
}

// rtb_state_init(x0) is the relaxed equilibrium: its force is
// rtb_static_force(x0) = K0 x0 + x0/(1/Kpa + N/Kr), the cell DOFs follow the
// static profile (Kpa spring then N springs Kr in series to ground, all
// carrying P = x0/(1/Kpa + N/Kr)), and holding x0 keeps the force there for
// both integrators.
TEST(PhysicsQuasiStatic, StateInitIsTheStaticEquilibrium) {
  for (int integ : {RTB_INTEGRATOR_SDIRK2, RTB_INTEGRATOR_BE}) {
    const rtb_params p = paper_params(RTB_MODEL_RT, RTB_DEFAULT_CELLS, integ);
    for (double x0 : {-0.7, 0.3, 2.0}) {
      SCOPED_TRACE(testing::Message() << "integrator " << integ << " x0 " << x0);
      rtb_state s;
      ASSERT_EQ(rtb_state_init(&s, &p, x0), RTB_OK);
      const double Fs = static_force_closed_form(p, x0);
      EXPECT_NEAR(s.force, Fs, 1e-12 * std::fabs(Fs));
      EXPECT_NEAR(rtb_static_force(&p, x0), Fs, 1e-12 * std::fabs(Fs));

      const double P = x0 / (1.0 / p.Kpa + p.cells / p.Kr);
      double y[RTB_MAX_CELLS];
      ASSERT_EQ(rtb_cell_states(&s, y, RTB_MAX_CELLS), p.cells);
      double yk = x0 - P / p.Kpa;
      for (int k = 0; k < p.cells; ++k, yk -= P / p.Kr)
        EXPECT_NEAR(y[k], yk, 1e-12 * std::fabs(x0)) << "DOF " << k + 1;

      double F = 0.0;
      for (int i = 0; i < 1000; ++i) ASSERT_EQ(rtb_step(&s, &p, nullptr, x0, 1e-3, &F), RTB_OK);
      EXPECT_NEAR(F, Fs, 1e-9 * std::fabs(Fs));
    }
  }
}
