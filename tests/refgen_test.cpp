// refgen_test.cpp -- the independent reference generator (tests/refgen/) is
// right where it can be checked without the element: its fine-step
// integration converges at order ~3, the relaxed force is the static law,
// the instantaneous and sliding tangents are those of the STS limit
// (eq. (18)), its effects have their closed-form signatures, and the tool's
// CSV reader reads every column convention it writes. Cheap: a few seconds.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>

#include "refgen.h"
#include "specimen_model.h"
#ifdef RTB_HAVE_OFFLINE
#include "offline/rtb_offline.h"
#include "temp_dir.h"
#endif

using namespace refgen;

namespace {

// A noise-free rig with a 2nd-order 40 Hz servo.
Chain clean_chain(int substeps = 10) {
  Chain c;
  c.force_noise = 0.0;
  c.disp_noise = 0.0;
  c.substeps = substeps;
  return c;
}

Command sine_command(double amp, double hz, double duration) {
  Command c;
  c.kind = Kind::sine;
  c.amp = amp;
  c.hz = hz;
  c.duration = duration;
  return c;
}

Command ramp_and_hold(double amp, double ramp_time, double duration) {
  Command c;
  c.kind = Kind::step;
  c.amp = amp;
  c.t_up = 0.0;
  c.ramp_time = ramp_time;
  c.t_down = 2.0 * duration;  // never comes back
  c.duration = duration;
  return c;
}

double max_abs_diff(const std::vector<double> &a, const std::vector<double> &b) {
  double m = 0.0;
  for (size_t k = 0; k < a.size(); ++k) m = std::fmax(m, std::fabs(a[k] - b[k]));
  return m;
}

double max_abs(const std::vector<double> &a) { return max_abs_diff(a, std::vector<double>(a.size())); }

}  // namespace

TEST(RefgenIntegration, ConvergesAtOrderThreeOnAFiveHertzSine) {
  Specimen s;  // the paper's section 3.4 set, N = 15
  const Command cmd = sine_command(1.0, 5.0, 0.6);
  const Samples ref = run_record(s, cmd, clean_chain(64));
  double err[3];
  const int m[3] = {2, 4, 8};
  for (int i = 0; i < 3; ++i) err[i] = max_abs_diff(run_record(s, cmd, clean_chain(m[i])).F_clean, ref.F_clean);
  const double Fmax = max_abs(ref.F_clean);
  std::printf("[refgen] max error / max|F| at dt/2, dt/4, dt/8: %.2e %.2e %.2e\n", err[0] / Fmax,
              err[1] / Fmax, err[2] / Fmax);
  EXPECT_GT(std::log2(err[0] / err[1]), 2.5);  // Radau IIA, 2 stages: order 3
  EXPECT_GT(std::log2(err[1] / err[2]), 2.5);
  EXPECT_LT(err[0] / Fmax, 1e-5);  // even 2 substeps per 1 ms sample are far below 0.5% noise
}

TEST(RefgenIntegration, RelaxedForceIsTheStaticLaw) {
  Specimen s;
  s.N = 5;
  s.alpha = 0.9;  // near-linear dashpots relax fast, so a 3 s hold reaches equilibrium
  const Samples r = run_record(s, ramp_and_hold(0.8, 0.2, 3.0), clean_chain(5));
  const double x = r.x_true.back();
  EXPECT_NEAR(x, 0.8, 1e-9);
  // F = K0 x + x / (1/Kpa + N/Kr): the N springs Kr in series with Kpa.
  const double Fs = s.K0 * x + x / (1.0 / s.Kpa + s.N / s.Kr);
  EXPECT_NEAR(r.F_clean.back() / Fs, 1.0, 1e-7);
  EXPECT_NEAR(static_force(s, x) / Fs, 1.0, 1e-15);
}

// A preloaded rig: the specimen held at the preload for ever before t = 0
// starts at the static law there (the end a half gap short of the actuator
// when a clearance was closed by pushing), and the records move about it.
TEST(RefgenChain, PreloadStartsRelaxedAtTheStaticLaw) {
  Specimen s;
  s.N = 7;
  Chain c = clean_chain(5);
  c.preload = -0.7;
  const Samples r = run_record(s, sine_command(0.2, 1.0, 1.0), c);
  EXPECT_EQ(r.x_true[0], -0.7);
  EXPECT_NEAR(r.F_clean[0] / static_force(s, -0.7), 1.0, 1e-12);
  double lo = INFINITY, hi = -INFINITY;
  for (double x : r.x_true) lo = std::fmin(lo, x), hi = std::fmax(hi, x);
  EXPECT_NEAR(lo, -0.9, 0.02);
  EXPECT_NEAR(hi, -0.5, 0.02);
  s.gap = Gap::held;
  s.half_gap = 0.05;
  const Samples g = run_record(s, sine_command(0.2, 1.0, 0.5), c);
  EXPECT_NEAR(g.F_clean[0] / static_force(s, -0.65), 1.0, 1e-12);
}

// A compression-positive load cell records every force negated, the
// measurement chain's additions included.
TEST(RefgenChain, CompressionPositiveLoadCellNegatesTheForce) {
  Specimen s;
  Chain c = clean_chain(5);
  c.offset = 3.0;
  const Samples a = run_record(s, sine_command(0.5, 2.0, 0.5), c);
  c.force_sign = -1.0;
  const Samples b = run_record(s, sine_command(0.5, 2.0, 0.5), c);
  for (size_t k = 0; k < a.F.size(); ++k) EXPECT_EQ(b.F_clean[k], -a.F_clean[k]);
  EXPECT_EQ(expected_word("compression_positive"), "none");
  EXPECT_EQ(expected_word("preload"), "none");
}

// Band-limited noise (an anti-alias filter): the same level as the white
// noise of the same seed, with the lag-1 correlation of a first-order
// low-pass at the corner; the clean channels are untouched.
TEST(RefgenChain, ColoredNoiseKeepsItsLevelAndIsCorrelated) {
  Specimen s;
  Chain c;
  c.substeps = 5;
  const Samples white = run_record(s, sine_command(0.5, 2.0, 8.0), c);
  c.noise_hz = 100.0;
  const Samples red = run_record(s, sine_command(0.5, 2.0, 8.0), c);
  auto stats = [](const Samples &r, double &sd, double &rho) {
    double s2 = 0.0, s11 = 0.0;
    const size_t n = r.F.size();
    for (size_t k = 0; k < n; ++k) {
      const double e = r.F[k] - r.F_clean[k];
      s2 += e * e;
      if (k > 0) s11 += e * (r.F[k - 1] - r.F_clean[k - 1]);
    }
    sd = std::sqrt(s2 / (double)n);
    rho = s11 / s2;
  };
  double sd_w, rho_w, sd_r, rho_r;
  stats(white, sd_w, rho_w);
  stats(red, sd_r, rho_r);
  EXPECT_NEAR(sd_r, sd_w, 0.1 * sd_w);
  EXPECT_LT(std::fabs(rho_w), 0.05);
  EXPECT_NEAR(rho_r, std::exp(-6.283185307179586 * 100.0 * c.dt), 0.05);
  for (size_t k = 0; k < red.F.size(); ++k) EXPECT_EQ(red.F_clean[k], white.F_clean[k]);
  EXPECT_EQ(expected_word("colored_noise"), "none");
}

// A creeping load-cell zero: the recorded force gains a ramp from 0 at the
// start to zero_drift at the end, nothing else.
TEST(RefgenChain, ZeroDriftIsALinearRampOfTheForceZero) {
  Specimen s;
  Chain c = clean_chain(5);
  const Samples a = run_record(s, sine_command(0.5, 2.0, 0.5), c);
  c.zero_drift = 8.0;
  const Samples b = run_record(s, sine_command(0.5, 2.0, 0.5), c);
  for (size_t k = 0; k < a.F.size(); ++k)
    EXPECT_NEAR(b.F_clean[k] - a.F_clean[k], 8.0 * a.t[k] / 0.5, 1e-9);
  EXPECT_EQ(expected_word("zero_drift"), "unexplained");
}

// The other definitions of the elastic words (session 13): the relaxed force
// carries each closed form on top of the static law.
TEST(RefgenEffects, OtherElasticDefinitionsAreTheirClosedForms) {
  Specimen base;
  base.N = 5;
  base.alpha = 0.9;
  const double x = 0.8, F0 = static_force(base, x);
  auto relaxed = [&](const Specimen &s) {
    const Samples r = run_record(s, ramp_and_hold(x, 0.2, 3.0), clean_chain(5));
    return r.F_clean.back();
  };
  Specimen q = base;
  q.quad = -300.0;
  EXPECT_NEAR(relaxed(q) / (F0 - 300.0 * x * x), 1.0, 1e-7);
  Specimen p5 = base;
  p5.quintic = 200.0;
  EXPECT_NEAR(relaxed(p5) / (F0 + 200.0 * std::pow(x, 5)), 1.0, 1e-7);
  Specimen th = base;
  th.soft_k = 600.0;
  th.soft_x = 0.2;
  th.soft_tanh = true;
  EXPECT_NEAR(relaxed(th) / (F0 + 600.0 * 0.2 * std::tanh(x / 0.2)), 1.0, 1e-7);
}

// The erf-shaped Mullins loss: on reloading to half the prior maximum the
// K0 path has lost mu erf(2 (1 - 1/4)) = 0.987 mu of its stiffness (the
// quadratic definition: 0.75 mu).
TEST(RefgenEffects, ErfMullinsLossIsNearlyUniformBelowThePriorMaximum) {
  Specimen s;
  s.Kpa = 1e-3;  // the chain carries nothing: the force is the K0 path
  s.mullins = 0.3;
  s.mullins_erf = true;
  double dF = 0.0;
  const double F = elastic_force(s, 1.0, 0.5, 0.0, 1.0, &dF);
  EXPECT_NEAR(F / (s.K0 * 0.5 + 1e-3 * 0.5), 1.0 - 0.3 * std::erf(1.5), 1e-6);
  // The slope by central differences.
  double d1 = 0.0, d2 = 0.0;
  const double h = 1e-6;
  const double Fp = elastic_force(s, 1.0, 0.5 + h, 0.0, 1.0, &d1);
  const double Fm = elastic_force(s, 1.0, 0.5 - h, 0.0, 1.0, &d2);
  EXPECT_NEAR(dF, (Fp - Fm) / (2 * h), 1e-5 * std::fabs(dF));
}

TEST(RefgenIntegration, NearFrictionTangentsAreTheStsOnes) {
  // alpha -> 0 is the STS friction limit (section 3.2). On a slow triangle
  // (1 mm/s) behind a fast servo:
  Chain c = clean_chain(5);
  c.servo_hz = 200.0;
  Command tri;
  tri.kind = Kind::triangle;
  tri.amp = 1.0;
  tri.hz = 0.25;
  tri.duration = 1.2;  // peak at 1 s
  Specimen s;
  s.alpha = 0.02;
  auto slope = [&](const Samples &r, double t0, double t1) {
    const size_t a = (size_t)(t0 / 1e-3), b = (size_t)(t1 / 1e-3);
    return (r.F_clean[b] - r.F_clean[a]) / (r.x_true[b] - r.x_true[a]);
  };
  // Just after the reversal every cell sticks until cell 1 has seen 2 C0
  // (0.1 mm here): tangent K0 + Kpa, eq. (18).
  const Samples r = run_record(s, tri, c);
  EXPECT_NEAR(slope(r, 1.01, 1.06) / (s.K0 + s.Kpa), 1.0, 0.01);
  // With a small friction level every cell slides long before the peak, at
  // a force that no longer changes: the tangent is the static stiffness.
  s.C0 = 2.0;
  const Samples q = run_record(s, tri, c);
  EXPECT_NEAR(slope(q, 0.7, 0.95) / static_force(s, 1.0), 1.0, 0.01);
}

TEST(RefgenEffects, MaxwellBranchRelaxesWithItsTime) {
  Specimen plain;
  Specimen mx = plain;
  mx.branches.push_back({500.0, 0.2});
  const Command cmd = ramp_and_hold(0.5, 0.05, 1.0);
  const Samples a = run_record(plain, cmd, clean_chain()), b = run_record(mx, cmd, clean_chain());
  // During the hold the branch force decays as exp(-t / tau).
  const double d1 = b.F_clean[300] - a.F_clean[300], d2 = b.F_clean[500] - a.F_clean[500];
  EXPECT_GT(d1, 10.0);
  EXPECT_NEAR(d2 / d1, std::exp(-0.2 / 0.2), 1e-6);
}

TEST(RefgenEffects, RelaxationSpectrumRelaxesAsItsPronySeries) {
  refgen::Scenario sc = make_scenario({"relaxation_spectrum"}, 3, 4.0);
  const std::vector<Branch> &br = sc.specimen.branches;
  ASSERT_EQ(br.size(), 9u);  // 10 ms .. 100 s, two per decade
  Specimen plain = sc.specimen;
  plain.branches.clear();
  Chain c = clean_chain(5);
  c.servo_hz = 200.0;
  const Command cmd = ramp_and_hold(1.0, 0.002, 3.1);
  const Samples a = run_record(plain, cmd, c), b = run_record(sc.specimen, cmd, c);
  // Once the actuator holds, the branches (parallel to the cells, so the
  // force difference) relax as G(t) = sum k_j exp(-t / tau_j), t from the
  // loading (about 2.6 ms: half the ramp plus the servo lag).
  auto G = [&](double t) {
    double g = 0.0;
    for (const Branch &j : br) g += j.k * std::exp(-(t - 0.0026) / j.tau);
    return g;
  };
  auto dF = [&](double t) { return b.F_clean[(size_t)(t / 1e-3)] - a.F_clean[(size_t)(t / 1e-3)]; };
  for (double t : {0.1, 0.3, 1.0, 3.0}) EXPECT_NEAR(dF(t) / dF(0.03), G(t) / G(0.03), 0.01) << t;
  // Power-law-like: between 0.03 and 3 s the log-log slope is about -n.
  const double n = -std::log(br[1].k / br[0].k) / std::log(br[1].tau / br[0].tau);
  EXPECT_NEAR(std::log(dF(3.0) / dF(0.03)) / std::log(100.0), -n, 0.1) << "n = " << n;
}

TEST(RefgenEffects, FloatingClearanceCarriesNoForceInsideTheGap) {
  Specimen s;
  s.gap = Gap::floating;
  s.half_gap = 0.05;
  Command c;
  c.kind = Kind::triangle;
  c.amp = 1.0;
  c.hz = 0.5;
  c.duration = 2.5;
  const Samples r = run_record(s, c, clean_chain());
  int zero = 0;
  for (double F : r.F_clean) zero += std::fabs(F) < 1e-9 * max_abs(r.F_clean);
  // The first 0.05 mm and two gap crossings of 0.1 mm at 2 mm/s: about 125
  // samples at zero force (more or less as the floating end relaxes).
  EXPECT_GT(zero, 100);
  EXPECT_LT(zero, 400);
}

TEST(RefgenEffects, HeldClearanceFreezesTheEndAndKeepsForce) {
  Specimen s;
  s.gap = Gap::held;
  s.half_gap = 0.05;
  Command c;
  c.kind = Kind::triangle;
  c.amp = 1.0;
  c.hz = 0.5;
  c.duration = 1.2;  // one reversal at 0.5 s
  const Samples r = run_record(s, c, clean_chain());
  // In the 50 ms after the reversal the actuator crosses the gap (0.1 mm at
  // 2 mm/s): the end is held, the force only relaxes, never reaches zero.
  const double Fpeak = r.F_clean[500];
  for (size_t k = 510; k < 540; ++k) {
    EXPECT_GT(r.F_clean[k], 0.5 * Fpeak) << k;
    EXPECT_LE(r.F_clean[k], r.F_clean[k - 1] + 1e-9) << k;
  }
}

TEST(RefgenEffects, SlackStripCannotPush) {
  Specimen s;
  s.slack = true;
  Command c;
  c.kind = Kind::sine;
  c.tension = true;  // 0 .. 2 amp
  c.amp = 0.5;
  c.hz = 1.0;
  c.duration = 2.0;
  const Samples r = run_record(s, c, clean_chain());
  int slack = 0;
  for (double F : r.F_clean) {
    EXPECT_GT(F, -1e-9 * max_abs(r.F_clean));
    slack += std::fabs(F) < 1e-9 * max_abs(r.F_clean);
  }
  EXPECT_GT(slack, 50);  // it goes slack near the end of every unloading
}

TEST(RefgenChain, DelayShiftsTheForceChannelOnly) {
  Specimen s;
  Chain c = clean_chain();
  const Command cmd = sine_command(0.5, 3.0, 1.0);
  const Samples a = run_record(s, cmd, c);
  c.delay = 0.004;
  const Samples b = run_record(s, cmd, c);
  EXPECT_EQ(max_abs_diff(a.x_true, b.x_true), 0.0);
  for (size_t k = 10; k < a.F_clean.size(); ++k) ASSERT_NEAR(b.F_clean[k], a.F_clean[k - 4], 1e-9);
}

TEST(RefgenChain, DisplacementDelayShiftsTheDisplacementChannelOnly) {
  Specimen s;
  Chain c = clean_chain();
  const Command cmd = sine_command(0.5, 3.0, 1.0);
  const Samples a = run_record(s, cmd, c);
  c.disp_delay = 0.003;
  const Samples b = run_record(s, cmd, c);
  EXPECT_EQ(max_abs_diff(a.F_clean, b.F_clean), 0.0);
  for (size_t k = 10; k < a.x_true.size(); ++k) ASSERT_NEAR(b.x_true[k], a.x_true[k - 3], 1e-9);
}

// Glitches: isolated samples of the recorded force only, at the set rate.
TEST(RefgenChain, SpikesAreIsolatedSamplesOfTheRecordedForce) {
  Specimen s;
  Chain c = clean_chain();
  const Command cmd = sine_command(0.5, 3.0, 4.0);
  const Samples a = run_record(s, cmd, c);
  c.spikes = 50.0;
  c.spike_rate = 0.005;
  const Samples b = run_record(s, cmd, c);
  EXPECT_EQ(max_abs_diff(a.F_clean, b.F_clean), 0.0);
  long off = 0;
  for (size_t k = 0; k < a.F.size(); ++k)
    if (b.F[k] != a.F[k]) {
      ++off;
      EXPECT_GE(std::fabs(b.F[k] - a.F[k]), 25.0 - 1e-9);
      EXPECT_LE(std::fabs(b.F[k] - a.F[k]), 50.0 + 1e-9);
    }
  EXPECT_NEAR((double)off / (double)a.F.size(), 0.005, 0.0025);
}

TEST(RefgenScenario, SeedFixesTheSpecimenAndEffectsOnlyAddTheirOwn) {
  const refgen::Scenario a = make_scenario({"none"}, 7), b = make_scenario({"maxwell"}, 7);
  EXPECT_EQ(a.specimen.K0, b.specimen.K0);
  EXPECT_EQ(a.chain.dt, b.chain.dt);
  EXPECT_TRUE(a.specimen.branches.empty());
  EXPECT_EQ(b.specimen.branches.size(), 1u);
  EXPECT_EQ(a.records.size(), 7u);
  EXPECT_THROW(make_scenario({"nonsense"}, 1), std::invalid_argument);
  EXPECT_THROW(make_scenario({"slack", "maxwell"}, 1), std::invalid_argument);
  EXPECT_EQ(expected_word("backlash_held"), "backlash");
  EXPECT_EQ(expected_word("hum"), "unexplained");
}

TEST(RefgenCli, BadInputIsAClearErrorAndWritesNothing) {
  const std::string dir = (std::filesystem::temp_directory_path() / "refgen_cli_bad").string();
  std::filesystem::remove_all(dir);
  const std::string cmd = std::string("'") + RTB_REFGEN_PATH +
                          "' --effect cubic_stiffness,nonsense --out-dir '" + dir + "' 2>&1";
  FILE *p = popen(cmd.c_str(), "r");
  ASSERT_NE(p, nullptr);
  std::string out;
  char buf[256];
  while (std::fgets(buf, sizeof buf, p)) out += buf;
  const int status = pclose(p);
  EXPECT_EQ(WEXITSTATUS(status), 2);
  EXPECT_NE(out.find("unknown effect 'nonsense'"), std::string::npos) << out;
  EXPECT_FALSE(std::filesystem::exists(dir));
}

#ifdef RTB_HAVE_OFFLINE
TEST(RefgenCsv, EveryColumnConventionIsReadByTheTool) {
  rtb_test::TempDir dir("refgen_csv");
  Samples r;
  for (int k = 0; k < 10; ++k) {
    r.t.push_back(k * 1e-3);
    r.x.push_back(0.1 * k);
    r.F.push_back(-3.5 * k);
  }
  for (int style = 0; style < 5; ++style) {
    const std::string p = dir.file("r" + std::to_string(style) + ".csv");
    write_record_csv(p, r, style);
    const rtb::Record rec = rtb::read_record_csv(p);
    EXPECT_LT(max_abs_diff(rec.t, r.t), 1e-15) << style;
    EXPECT_LT(max_abs_diff(rec.x, r.x), 1e-12) << style;
    EXPECT_LT(max_abs_diff(rec.F, r.F), 1e-12) << style;
  }
}
#endif  // RTB_HAVE_OFFLINE
