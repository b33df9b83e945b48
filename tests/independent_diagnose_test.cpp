// independent_diagnose_test.cpp -- the diagnosis on data it did not
// generate (issue #10 item 8): records from the independent reference
// generator (tests/refgen/: another integrator, its own effect definitions,
// servo-smoothed actuator, noise on displacement and force, randomized
// parameters and sample rates). Short records (4 s) so each case stays cheap;
// the full sweep is tests/refgen/acceptance.sh.
//
// Each case costs a diagnosis (about 15-60 s CPU in Release): they run in
// the Release tree only; the sanitizer tree runs the refgen unit tests and
// diagnose_test.cpp's short subset, which cover the same code paths. Most
// of them are the long tier (`make test-long`; the list is in
// tests/CMakeLists.txt); `make test` runs the plain, slack, spectrum and two
// out-of-vocabulary cases.
#ifdef RTB_HAVE_OFFLINE
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "offline/diagnose/diagnose.h"
#include "refgen.h"

namespace {

constexpr double kRefgenDuration = 4.0;  // s per record

struct Diagnosed {
  rtb::DiagnoseResult R;
  double noise_floor = 0.0;  // refgen's force-noise floor on the held-out records
};

#if defined(__SANITIZE_ADDRESS__)
#define RTB_SKIP_UNDER_SANITIZERS() \
  GTEST_SKIP() << "a full diagnosis per case: Release tree only (minutes under ASan)"
#else
#define RTB_SKIP_UNDER_SANITIZERS() (void)0
#endif

Diagnosed diagnose_refgen(const std::vector<std::string> &effects, unsigned seed,
                          const rtb::DiagnoseOptions &opt = rtb::DiagnoseOptions()) {
  const refgen::Scenario sc = refgen::make_scenario(effects, seed, kRefgenDuration);
  std::vector<rtb::Record> fit, hold;
  std::vector<refgen::Samples> held;
  for (size_t i = 0; i < sc.records.size(); ++i) {
    const refgen::Samples s = refgen::run_scenario_record(sc, i);
    rtb::Record r;
    r.path = sc.records[i].name;
    r.t = s.t;
    r.x = s.x;
    r.F = s.F;
    (sc.records[i].holdout ? hold : fit).push_back(r);
    if (sc.records[i].holdout) held.push_back(s);
  }
  Diagnosed d;
  d.R = rtb::diagnose(fit, hold, opt);
  std::vector<const refgen::Samples *> hp;
  for (const refgen::Samples &s : held) hp.push_back(&s);
  d.noise_floor = refgen::noise_floor(hp);
  std::string name;
  for (const std::string &e : effects) name += (name.empty() ? "" : "+") + e;
  std::printf("[refgen-diag] %-10s seed %u -> %-14s baseline held-out %.2f%% (floor %.2f%%), %.1f s\n",
              name.c_str(), seed, d.R.cause.c_str(), 100 * d.R.baseline_error_holdout,
              100 * d.noise_floor, d.R.wall_seconds);
  return d;
}

Diagnosed diagnose_refgen(const std::string &effect, unsigned seed) {
  return diagnose_refgen(std::vector<std::string>{effect}, seed);
}

// Out of vocabulary: no cause, and the verdict names what it saw.
void expect_unexplained_naming(const Diagnosed &d, const char *what) {
  EXPECT_EQ(d.R.cause, "unexplained") << d.R.verdict;
  EXPECT_TRUE(d.R.causes.empty()) << d.R.verdict;
  EXPECT_NE(d.R.verdict.find(what), std::string::npos) << d.R.verdict;
}

// refgen's spectrum alone: one cause, `relaxation_spectrum`, held out within
// `times` refgen's force-noise floor.
void expect_spectrum_alone(unsigned seed, double times) {
  const Diagnosed d = diagnose_refgen("relaxation_spectrum", seed);
  EXPECT_EQ(d.R.cause, "relaxation_spectrum") << d.R.verdict;
  EXPECT_EQ(d.R.causes.size(), 1u) << d.R.verdict;
  EXPECT_LT(d.R.extended_error_holdout, times * d.noise_floor) << d.R.verdict;
}

}  // namespace

// Plain RT through another integrator and a real rig's chain: no effect.
TEST(IndependentDiagnose, PlainRtIsNone) {
  RTB_SKIP_UNDER_SANITIZERS();
  const Diagnosed d = diagnose_refgen("none", 1);
  EXPECT_EQ(d.R.cause, "none") << d.R.verdict;
}

// A Maxwell branch the baseline absorbed (seed 16: K0 = 0, a chain 14
// times too stiff): the screen starts the branch at 4 s and the joint fit
// drifts past the records' 4 s, where a branch is a spring (seed 16: 8.1 s,
// 3.03% held out, `unexplained`; seed 18: 4.26 s, 2.43%). The restart from
// the middle of the resolvable times, at the stiffness the screen measured
// (cause_round.cpp), finds the generator's branch; seed 18 also fails when
// the restart starts from the scan's zero stiffness.
class AbsorbedMaxwell : public ::testing::TestWithParam<unsigned> {};

TEST_P(AbsorbedMaxwell, IsFoundAtTheGeneratorsTime) {
  RTB_SKIP_UNDER_SANITIZERS();
  const unsigned seed = GetParam();
  const Diagnosed d = diagnose_refgen("maxwell", seed);
  const refgen::Scenario sc = refgen::make_scenario({"maxwell"}, seed, kRefgenDuration);
  ASSERT_FALSE(d.R.causes.empty()) << d.R.verdict;
  EXPECT_EQ(d.R.causes[0].cand.name, "maxwell") << d.R.verdict;
  ASSERT_EQ(sc.specimen.branches.size(), 1u);
  const refgen::Branch &b = sc.specimen.branches[0];
  EXPECT_NEAR(d.R.extended.p.maxwell_tau, b.tau, 0.1 * b.tau) << d.R.verdict;
  EXPECT_NEAR(d.R.extended.p.maxwell_k, b.k, 0.1 * b.k) << d.R.verdict;
  EXPECT_LT(d.R.extended_error_holdout, 1.3 * d.noise_floor) << d.R.verdict;
}

INSTANTIATE_TEST_SUITE_P(IndependentDiagnose, AbsorbedMaxwell, ::testing::Values(16u, 18u));

// Plain RT oscillating about a held preload (0.5-1.5 amplitudes): the
// element must start relaxed there, or the start transient reads as an
// offset (session 13's binary named `offset` on 4 of seeds 1-6).
TEST(IndependentDiagnose, PreloadedPlainRtIsNone) {
  RTB_SKIP_UNDER_SANITIZERS();
  const Diagnosed d = diagnose_refgen("preload", 1);
  EXPECT_EQ(d.R.cause, "none") << d.R.verdict;
}

// A clearance whose bushing end floats free in the gap (force 0 there).
TEST(IndependentDiagnose, FloatingClearanceIsBacklash) {
  RTB_SKIP_UNDER_SANITIZERS();
  const Diagnosed d = diagnose_refgen("backlash", 1);
  EXPECT_EQ(d.R.cause, "backlash") << d.R.verdict;
}

// A clearance whose bushing end is held in the gap (deformation frozen,
// force relaxing) is a backlash too (issue #10, item 4). Before the rewrite:
// `none`.
TEST(IndependentDiagnose, HeldClearanceIsBacklash) {
  RTB_SKIP_UNDER_SANITIZERS();
  const Diagnosed d = diagnose_refgen("backlash_held", 1);
  EXPECT_EQ(d.R.cause, "backlash") << d.R.verdict;
}

// A strip that cannot push goes slack near the end of unloading (issue #10,
// item 6). Before the rewrite the word did not exist (8 s records: `mullins`).
TEST(IndependentDiagnose, SlackStripIsSlack) {
  RTB_SKIP_UNDER_SANITIZERS();
  const Diagnosed d = diagnose_refgen("slack", 1);
  EXPECT_EQ(d.R.cause, "slack") << d.R.verdict;
}

// refgen's seed-5 spectrum (500 Hz) has branches from 5 sample intervals,
// between the element's branch times when its fastest is screened at 3, 10,
// 30 or 100 intervals (two per decade: the same times, only the range's
// start moves): the spectrum gained 12% held out and the verdict was
// `unexplained`. Screened also at 1.8, 5.6, 18 and 56 intervals, it is
// named near the floor (session 26: 1.64% held out, against refgen's force-
// noise floor of 1.51% that the test holds it to, and the diagnosis' own
// estimate of 1.43%).
TEST(IndependentDiagnose, SpectrumBetweenTheBranchTimesIsNamed) {
  RTB_SKIP_UNDER_SANITIZERS();
  expect_spectrum_alone(5, 1.25);
}

// refgen's seed-36 spectrum (nine branches, 0.01-100 s, weights tau^-0.21)
// is small beside the chain: the plain fit makes the long memory with alpha
// 0.51 and Kr 1188 (generator 0.20 and 5686), and the spectrum fitted from
// there stayed in that basin (Kr 744, 1.88% held out, a 9% gain: the verdict
// was `unexplained`). Refitted from the STS start of its records
// (sts_core_restart), it is named near the floor (session 44: 1.54%
// held out, refgen's floor 1.44%).
TEST(IndependentDiagnose, SpectrumAbsorbedByTheChainIsNamed) {
  RTB_SKIP_UNDER_SANITIZERS();
  expect_spectrum_alone(36, 1.15);
}

// refgen's seed-37 spectrum (nine branches from 10 ms, the fastest the
// heaviest) was screened from 30 sample intervals, where the baseline's
// dashpots already made the fast relaxation; the joint fit does not move the
// branches, and it stopped at 1.76% held out, an 11% gain at a 1.36% floor
// (`unexplained`). Refitted with its branches a half decade earlier
// (moved_spectrum_starts, cause_round.cpp), it is named at the floor
// (session 46: 1.39% held out, k 687 N/mm for the generator's 697).
TEST(IndependentDiagnose, SpectrumScreenedLateIsNamed) {
  RTB_SKIP_UNDER_SANITIZERS();
  expect_spectrum_alone(37, 1.1);
}

// refgen's seed-6 strip is a 12-cell chain. With one displacement cut-off
// for all records (the widest any needed) slack at the tool's 15 cells left
// 1.77% held out (floor 0.78%), a relaxation spectrum was accepted second
// for 16% of it, and only the 12-cell refit (stage 5c, other_cells_explain)
// took it back. With each record low-passed at its own band, slack alone at
// 15 cells is at the floor (0.80%): one cause, and no second word for what
// the filter did.
TEST(IndependentDiagnose, SlackStripOfAnotherCellCount) {
  RTB_SKIP_UNDER_SANITIZERS();
  const Diagnosed d = diagnose_refgen("slack", 6);
  EXPECT_EQ(d.R.cause, "slack") << d.R.verdict;
  EXPECT_EQ(d.R.causes.size(), 1u) << d.R.verdict;
  EXPECT_LT(d.R.extended_error_holdout, 1.3 * d.noise_floor) << d.R.verdict;
}

// 50 Hz mains hum on the force channel is outside the vocabulary: any
// physical name is wrong; "none" or "unexplained" are not.
TEST(IndependentDiagnose, MainsHumGetsNoPhysicalName) {
  RTB_SKIP_UNDER_SANITIZERS();
  const Diagnosed d = diagnose_refgen("hum", 1);
  EXPECT_TRUE(d.R.cause == "none" || d.R.cause == "unexplained") << d.R.verdict;
}

// A load cell that saturates below the loops' peaks records flat tops. No
// word covers it: before stage 0 found it, a degressive cubic spring or a
// softening spring imitated the tops (a wrong physical name).
TEST(IndependentDiagnose, ClippedLoadCellIsUnexplainedAndNamed) {
  RTB_SKIP_UNDER_SANITIZERS();
  const Diagnosed d = diagnose_refgen("clipping", 1);
  expect_unexplained_naming(d, "clipped");
  EXPECT_FALSE(d.R.clipping.empty());
}

// Another definition of the asymmetry, a quadratic term k x^2: fitted as a
// kink k_asym |x| only, the leftover made a friction asymmetry the second
// cause on 3 of 4 seeds (session 13). The word's quadratic definition now
// takes it, alone.
TEST(IndependentDiagnose, QuadraticAsymmetryIsOneAsymmetry) {
  RTB_SKIP_UNDER_SANITIZERS();
  const Diagnosed d = diagnose_refgen("asymmetry_quadratic", 1);
  EXPECT_EQ(d.R.cause, "asymmetry") << d.R.verdict;
  ASSERT_EQ(d.R.causes.size(), 1u) << d.R.verdict;
  EXPECT_EQ(d.R.causes[0].cand.variant, "quadratic") << d.R.verdict;
  EXPECT_LT(d.R.extended_error_holdout, 1.3 * d.noise_floor) << d.R.verdict;
}

// One-sample glitches on the force channel: not the specimen. Without
// stage 0's spike check seed 3 was `none` (the robust floor ignores them).
TEST(IndependentDiagnose, ForceSpikesAreUnexplainedAndNamed) {
  RTB_SKIP_UNDER_SANITIZERS();
  const Diagnosed d = diagnose_refgen("spikes", 3);
  expect_unexplained_naming(d, "spikes");
  EXPECT_FALSE(d.R.spikes.empty());
}

// A creeping load-cell zero (out of vocabulary): an offset or a friction
// asymmetry removed half of it on seeds 1-4 (session 14), leaving a slow
// trend over time; no time-invariant word may take the name.
TEST(IndependentDiagnose, CreepingForceZeroIsUnexplained) {
  RTB_SKIP_UNDER_SANITIZERS();
  const Diagnosed d = diagnose_refgen("zero_drift", 3);
  expect_unexplained_naming(d, "trend");
  EXPECT_FALSE(d.R.withdrawn.empty()) << d.R.verdict;
}

// A Maxwell branch beside a force offset. Seed 22: in the first round the
// offset pays and the branch does not; after the offset, the branch fitted
// from the offset model (whose RT core absorbed it: alpha 0.72) went to
// 6.5 ms, 3.44% held out against 3.15% without it, and only the offset was
// named. Refitted from its own first-round fit (cause_round.cpp), it is
// the generator's 0.179 s branch. Seed 24: the core had absorbed the branch
// from the start (K0 = 0, alpha 0.69, a chain 12 times too stiff), and the
// branch went to 3.76 s from either start, 1.44% fit and a 1% held-out
// gain: only the offset was named (session 39). The restart from the middle
// of the resolved times (slow_branch_restart) finds the generator's 0.078 s.
class BranchBesideOffset : public ::testing::TestWithParam<unsigned> {};

TEST_P(BranchBesideOffset, IsFoundAtTheGeneratorsTime) {
  RTB_SKIP_UNDER_SANITIZERS();
  const unsigned seed = GetParam();
  const std::vector<std::string> effects{"maxwell", "offset"};
  const Diagnosed d = diagnose_refgen(effects, seed);
  const refgen::Scenario sc = refgen::make_scenario(effects, seed, kRefgenDuration);
  ASSERT_EQ(d.R.causes.size(), 2u) << d.R.verdict;
  EXPECT_EQ(d.R.causes[0].cand.name, "offset") << d.R.verdict;
  EXPECT_EQ(d.R.causes[1].cand.name, "maxwell") << d.R.verdict;
  ASSERT_EQ(sc.specimen.branches.size(), 1u);
  const refgen::Branch &b = sc.specimen.branches[0];
  EXPECT_NEAR(d.R.extended.p.maxwell_tau, b.tau, 0.1 * b.tau) << d.R.verdict;
  EXPECT_NEAR(d.R.extended.p.maxwell_k, b.k, 0.1 * b.k) << d.R.verdict;
  EXPECT_LT(d.R.extended_error_holdout, 1.25 * d.noise_floor) << d.R.verdict;
}

INSTANTIATE_TEST_SUITE_P(IndependentDiagnose, BranchBesideOffset, ::testing::Values(22u, 24u));

// Each test at its own temperature (out of vocabulary): the records
// disagree on the force scale by 6-12%, which no word of one specimen
// follows. Blindgen thermal_drift_s10 (its own convention: the force scaled
// by a slow sine of the test time) had `maxwell` named for it. On seed 2
// (scales 0.92-1.08) a cubic spring and a Mullins loss pass the round
// criteria; what they leave is 83% a scale and drift per record
// (residual_signature.cpp), and they are withdrawn.
TEST(IndependentDiagnose, ASpecimenAtAnotherTemperaturePerTestIsUnexplained) {
  RTB_SKIP_UNDER_SANITIZERS();
  const Diagnosed d = diagnose_refgen("temperature", 2);
  expect_unexplained_naming(d, "disagree on the force scale");
  EXPECT_FALSE(d.R.withdrawn.empty()) << d.R.verdict;
}

// A delay whose two definitions only the held-out records tell apart (seed
// 17: 500 Hz, slow fit records, a 30 Hz held-out sine). On the fit records
// the low-pass fits 10% better than the generator's pure lag (J 462
// against 510), and held out it leaves 14.5% against 1.8%: chosen by the
// fit misfit, the delay was named in the wrong definition, 8x the floor.
// The held-out records decide between definitions when they decide clearly
// (definition_preferred, cause_round.cpp).
TEST(IndependentDiagnose, DelaySeenAtHighFrequencyIsAPureLag) {
  RTB_SKIP_UNDER_SANITIZERS();
  const Diagnosed d = diagnose_refgen("delay", 17);
  const refgen::Scenario sc = refgen::make_scenario({"delay"}, 17, kRefgenDuration);
  ASSERT_EQ(d.R.cause, "delay") << d.R.verdict;
  EXPECT_FALSE(d.R.extended.delay_lowpass) << "a pure lag, not a low-pass: " << d.R.verdict;
  EXPECT_NEAR(d.R.extended.delay, sc.chain.delay, 0.05 * sc.chain.delay) << d.R.verdict;
  EXPECT_LT(d.R.extended_error_holdout, 1.5 * d.noise_floor) << d.R.verdict;
}

// A moving mass behind band-limited noise (seed 64: both channels through a
// 52 Hz first-order low-pass at 1 kHz). Stage 0's cut-off took that noise
// as white and kept fs/5 on every record; the slow fit records'
// acceleration noise shrank the fitted mass 7x (0.0016 of 0.0116), which
// gained 12% held out: `unexplained`. With the noise's correlation in the
// cut-off's risk (displacement_noise.cpp) the records keep their own bands,
// as with white noise.
TEST(IndependentDiagnose, AMassBehindBandLimitedNoiseIsNamed) {
  RTB_SKIP_UNDER_SANITIZERS();
  const Diagnosed d = diagnose_refgen(std::vector<std::string>{"colored_noise", "inertia"}, 64);
  const refgen::Scenario sc = refgen::make_scenario({"colored_noise", "inertia"}, 64, kRefgenDuration);
  ASSERT_EQ(d.R.cause, "inertia") << d.R.verdict;
  EXPECT_GT(d.R.denoise.correlation, 0.5);
  EXPECT_NEAR(d.R.extended.p.mass, sc.specimen.mass, 0.15 * sc.specimen.mass) << d.R.verdict;
  EXPECT_LT(d.R.extended_error_holdout, 1.3 * d.noise_floor) << d.R.verdict;
}

// Delay and asymmetry together (seed 12). Until session 23 they paid only
// together (stage 5e, cause_pair.cpp): the asymmetry alone gains 13% held
// out (a first cause needs 15%) and the delay's cross-correlation, averaged
// per sample over the records, found the force leading. Pooled by each
// record's information on a shift (plausibility.cpp) it lags 2.1 ms against
// a fitted 2.65, and the delay is a first cause on its own, the asymmetry a
// second. Either route must name both, at their true sizes, at the floor.
TEST(IndependentDiagnose, DelayAndAsymmetryAreBothNamed) {
  RTB_SKIP_UNDER_SANITIZERS();
  const Diagnosed d = diagnose_refgen(std::vector<std::string>{"delay", "asymmetry"}, 12);
  const refgen::Scenario sc = refgen::make_scenario({"delay", "asymmetry"}, 12, kRefgenDuration);
  ASSERT_EQ(d.R.causes.size(), 2u) << d.R.verdict;
  std::vector<std::string> names = {d.R.causes[0].cand.name, d.R.causes[1].cand.name};
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"asymmetry", "delay"})) << d.R.verdict;
  EXPECT_FALSE(d.R.extended.delay_lowpass) << "a pure lag, not a low-pass: " << d.R.verdict;
  EXPECT_NEAR(d.R.extended.delay, sc.chain.delay, 0.05 * sc.chain.delay) << d.R.verdict;
  EXPECT_NEAR(d.R.extended.p.k_asym, sc.specimen.asym, 0.05 * std::fabs(sc.specimen.asym))
      << d.R.verdict;
  EXPECT_LT(d.R.extended_error_holdout, 1.3 * d.noise_floor) << d.R.verdict;
}

// Stage 5e (cause_pair.cpp): two words that pay only together. On the same
// data the delay alone gains 19% held out and the asymmetry alone 38% (-5%
// until session 44, when its kink was bounded by K0: the baseline had
// absorbed it); the pair takes the held-out error from 19% to 1.6%, at the
// floor. With a first cause required to gain 50%, no single word passes, and
// only the pair stage can name the two, each member still paying against the
// other alone.
TEST(IndependentDiagnose, TwoWordsThatPayOnlyTogetherAreAPair) {
  RTB_SKIP_UNDER_SANITIZERS();
  rtb::DiagnoseOptions opt;
  opt.min_gain = 0.5;
  const Diagnosed d = diagnose_refgen(std::vector<std::string>{"delay", "asymmetry"}, 12, opt);
  const refgen::Scenario sc = refgen::make_scenario({"delay", "asymmetry"}, 12, kRefgenDuration);
  ASSERT_EQ(d.R.causes.size(), 2u) << d.R.verdict;
  std::vector<std::string> names = {d.R.causes[0].cand.name, d.R.causes[1].cand.name};
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"asymmetry", "delay"})) << d.R.verdict;
  EXPECT_TRUE(d.R.causes[0].paired && d.R.causes[1].paired) << "not through the pair stage: "
                                                            << d.R.verdict;
  EXPECT_NEAR(d.R.extended.delay, sc.chain.delay, 0.05 * sc.chain.delay) << d.R.verdict;
  EXPECT_LT(d.R.extended_error_holdout, 1.3 * d.noise_floor) << d.R.verdict;
}

#endif  // RTB_HAVE_OFFLINE
