// diagnose_test.cpp -- hidden effects (issue #4). Records come from the RT
// model plus one effect the pipeline is not told about, with 0.5% force noise
// and randomized parameters (fixed seed, not one the thresholds were tuned
// on), integrated 10x finer than sampled. Targets: every effect named, no
// false alarm on plain RT, the noise floor estimated from the
// data within 15% of the truth's error, and where the effect dominates the
// residual the named extension at least halves the held-out error.
#include <gtest/gtest.h>

#include <sys/wait.h>

#include <algorithm>
#include <cstdio>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>

#include "offline/diagnose/diagnose.h"
#include "offline/synth/synthetic_records.h"

using namespace rtb;

namespace {

#if defined(__SANITIZE_ADDRESS__)
// The sanitizer build checks memory, not statistics: one scenario, whose
// diagnosis takes the longest path (short fits, several rounds).
const std::vector<std::string> kEffects = {"backlash"};
#else
const std::vector<std::string> kEffects = {"none",  "offset", "backlash", "mullins",
                                           "delay", "maxwell", "inertia"};
// The long tier (`make test-long`, tests/CMakeLists.txt): 21-53 s CPU each.
const std::vector<std::string> kLongEffects = {"cubic_stiffness", "asymmetry", "viscous", "softening"};
#endif
// 4 s records (8 s until session 9): the same verdicts in a third of the
// time, which keeps `make test` well under 15 minutes. Longer records are
// diagnosed by BM_Diagnose (10 s) and the refgen acceptance runs (8 s).
constexpr double kRecordDuration = 4.0;
constexpr unsigned kSeed = 5;

// The true model's own held-out error: the noise floor of that scenario.
double truth_error(const Scenario &sc) {
  ExtModel t;
  t.p = sc.truth.p;
  t.delay = sc.truth.delay;
  t.offset = sc.truth.offset;
  return extended_error(t, sc.holdout, MisfitOptions());
}

}  // namespace

// One test per scenario, so that ctest runs them in parallel.
class DiagnoseHidden : public ::testing::TestWithParam<std::string> {};

TEST_P(DiagnoseHidden, NamesTheHiddenEffect) {
  const std::string effect = GetParam();
  const Scenario sc = hidden_effect_scenario(effect, kSeed, 0.005, kRecordDuration);
  const DiagnoseResult R = diagnose(sc.fit, sc.holdout, DiagnoseOptions());
  std::printf("[diag] %-16s -> %-16s %s (%.1f s)\n", effect.c_str(), R.cause.c_str(),
              R.verdict.c_str(), R.wall_seconds);
  if (effect == "none") {
    EXPECT_EQ(R.cause, "none") << "false alarm: " << R.verdict;
    return;
  }
  // (Mullins on this seed was a known miss on 8-10 s records until session
  // 39: DiagnoseLongRecords.AMullinsLossFoundThroughARefusedPair.)
  ASSERT_EQ(R.cause, effect) << R.verdict;
  // The selection's figure (trimmed of isolated spikes) falls with every
  // named cause; where the plain one rises (inertia: the truth's own spikes
  // at ideal input corners), the verdict says so with both figures.
  EXPECT_LT(R.extended_error_holdout_trimmed, R.baseline_error_holdout_trimmed) << R.verdict;
  if (R.gain < 0.0)
    EXPECT_NE(R.verdict.find("trimmed of isolated spikes"), std::string::npos) << R.verdict;
  const double floor = truth_error(sc);
  // Where the effect dominates the residual, the extension brings the
  // (trimmed: an inertia term spikes at ideal input corners) held-out error
  // close to the noise floor.
  if (R.baseline_error_holdout > 3.0 * floor && effect != "inertia")
    EXPECT_GE(R.gain, 0.5) << effect << ": " << R.verdict << " (noise floor " << floor << ")";
  // The size of the effect comes back.
  if (effect == "backlash") EXPECT_NEAR(R.extended.p.backlash / sc.truth.p.backlash, 1.0, 0.05);
  if (effect == "offset") EXPECT_NEAR(R.extended.offset / sc.truth.offset, 1.0, 0.10);
  if (effect == "delay") EXPECT_NEAR(R.extended.delay / sc.truth.delay, 1.0, 0.10);
  // Every cause is reported with its sizes in the final model (final_sizes).
  for (const Cause &c : R.causes)
    for (size_t i = 0; i < c.names.size(); ++i)
      for (size_t k = 0; k < R.extended_fit.names.size(); ++k)
        if (R.extended_fit.names[k] == c.names[i])
          EXPECT_EQ(c.value[i], R.extended_fit.value[(Eigen::Index)k]) << c.names[i];
  // The noise floor estimated from the data is the true model's error (not
  // for inertia: there the truth, evaluated at the sample rate, has its own
  // one-sample spikes at input corners, which are no noise).
  if (effect != "inertia") EXPECT_NEAR(R.floor.error_holdout / floor, 1.0, 0.15);
}

INSTANTIATE_TEST_SUITE_P(Seed5, DiagnoseHidden, ::testing::ValuesIn(kEffects));
#if !defined(__SANITIZE_ADDRESS__)
INSTANTIATE_TEST_SUITE_P(Seed5Long, DiagnoseHidden, ::testing::ValuesIn(kLongEffects));
#endif

#if !defined(__SANITIZE_ADDRESS__)  // statistics, not memory: the Release tree runs it
// BM_Diagnose's Maxwell records (10 s): a Maxwell branch leaves a phase that
// a delay fit partly takes as a second cause (1.64 ms; the records' pooled
// least-squares shift 0.33 ms, their correlation peak 0.91 ms). It is not a
// time shift (plausibility.cpp), and only the branch is named.
// The branch's first fit stops at tau 1.10 s (1.98% held out, 2.1x the
// floor); the accepted model's restarts along its least determined
// direction (stage 5c, refit_along_ridge) reach the generator's basin.
TEST(DiagnoseLongRecords, AMaxwellPhaseIsNotADelay) {
  const Scenario sc = hidden_effect_scenario("maxwell", kSeed, 0.005, 10.0);
  const DiagnoseResult R = diagnose(sc.fit, sc.holdout, DiagnoseOptions());
  ASSERT_EQ(R.cause, "maxwell") << R.verdict;
  for (const Cause &c : R.causes) EXPECT_NE(c.cand.name, "delay") << R.verdict;
  EXPECT_NEAR(R.extended.p.maxwell_tau / sc.truth.p.maxwell_tau, 1.0, 0.1) << R.verdict;
  EXPECT_LT(R.extended_error_holdout, 1.1 * truth_error(sc)) << R.verdict;
}

// BM_Diagnose's Mullins records (10 s, a loss of 30% of K0): the word's
// first-round fit stops in a basin that fits 1.52% but holds out 3.59%
// against the baseline's 3.54%, and no single word pays. The pair stage's
// leads (backlash, maxwell) each reach 0.83% held out with it, and neither
// pays against the Mullins loss alone refitted from the pair: that refit is
// the first cause (before session 39: `unexplained`, 4.3x the floor).
TEST(DiagnoseLongRecords, AMullinsLossFoundThroughARefusedPair) {
  const Scenario sc = hidden_effect_scenario("mullins", kSeed, 0.005, 10.0);
  const DiagnoseResult R = diagnose(sc.fit, sc.holdout, DiagnoseOptions());
  ASSERT_EQ(R.cause, "mullins") << R.verdict;
  ASSERT_EQ(R.causes.size(), 1u) << R.verdict;
  EXPECT_NEAR(R.extended.p.mullins / sc.truth.p.mullins, 1.0, 0.05) << R.verdict;
  EXPECT_EQ(R.extended.p.mullins_whole, sc.truth.p.mullins_whole);
  EXPECT_GE(R.gain, 0.5) << R.verdict;
  EXPECT_LT(R.extended_error_holdout, 1.1 * truth_error(sc)) << R.verdict;
}
#endif

TEST(DiagnoseCli, ReportHasTheDocumentedKeys) {
  const std::string dir = std::string(RTB_BINARY_DIR) + "/diagnose_cli_test";
  std::system(("mkdir -p '" + dir + "'").c_str());
  const Scenario sc = hidden_effect_scenario("offset", kSeed, 0.005, 3.0);
  std::string args;
  int k = 0;
  for (const std::vector<Record> *set : {&sc.fit, &sc.holdout})
    for (const Record &r : *set) {
      const std::string path = dir + "/r" + std::to_string(k++) + ".csv";
      write_record_csv(path, r.t, r.x, r.F, r.units);
      args += (set == &sc.fit ? " --data '" : " --holdout '") + path + "'";
    }
  const std::string out = dir + "/report.json", hdr = dir + "/ext.h";
  std::remove(out.c_str());
#if defined(__SANITIZE_ADDRESS__)
  // Memory, not statistics: three words keep the report's every path (38 s
  // under ASan with the whole vocabulary).
  const std::vector<std::string> words = {"cubic_stiffness", "delay", "offset"};
  const std::string only = " --only cubic_stiffness,delay,offset";
#else
  std::vector<std::string> words;
  for (const Candidate &c : candidate_vocabulary()) words.push_back(c.name);
  const std::string only;
#endif
  const std::string cmd = std::string("'") + RTB_CLI_PATH + "' diagnose --quiet" + args + only +
                          " --out '" + out + "' --header '" + hdr + "' > /dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::ifstream f(out);
  ASSERT_TRUE(f.good());
  const nlohmann::json j = nlohmann::json::parse(f);
  EXPECT_EQ(j["cause"], "offset");
  for (const char *key : {"baseline", "extended"}) {
    EXPECT_TRUE(j[key].contains("params"));
    EXPECT_TRUE(j[key]["error_fit"].is_number());
    EXPECT_TRUE(j[key]["error_holdout"].is_number());
  }
  EXPECT_TRUE(j["gain"].is_number());
  ASSERT_TRUE(j["candidates"].is_array());
  size_t first_round = 0;
  for (const auto &c : j["candidates"]) first_round += c["round"] == 0;
  EXPECT_EQ(first_round, words.size());  // every word tried (variants count)
  // Issue #10's report: the causes with sizes and held-out gain, the noise
  // floor, and per-record figures of the extended model.
  ASSERT_TRUE(j["causes"].is_array());
  ASSERT_GE(j["causes"].size(), 1u);
  EXPECT_EQ(j["causes"][0]["name"], "offset");
  EXPECT_TRUE(j["causes"][0]["size"]["offset"]["value"].is_number());
  EXPECT_TRUE(j["causes"][0]["gain"].is_number());
  EXPECT_TRUE(j["dropped"].is_array());  // stage 5d: none here (one cause)
  EXPECT_GT(j["noise_floor"]["error_holdout"].get<double>(), 0.0);
  ASSERT_EQ(j["extended"]["records"].size(), sc.fit.size() + sc.holdout.size());
  for (const auto &r : j["extended"]["records"]) {
    EXPECT_TRUE(r["role"] == "fit" || r["role"] == "holdout");
    EXPECT_GT(r["error"].get<double>(), 0.0);
    EXPECT_LT(r["nrmse"].get<double>(), 0.05);
  }
  for (const auto &c : j["candidates"]) {
    EXPECT_TRUE(c.contains("name"));
    EXPECT_TRUE(c.contains("params"));
    EXPECT_TRUE(c.contains("error_fit"));
    EXPECT_TRUE(c.contains("error_holdout"));
    EXPECT_TRUE(c.contains("criterion"));
  }
  std::ifstream h(hdr);
  EXPECT_TRUE(h.good());
}

#if !defined(__SANITIZE_ADDRESS__)  // statistics, not memory: the Release tree runs it
// What-if mode (--causes): the imposed word is fitted and accepted although
// plain data do not select it, and stage 5's verdict on it is still there.
TEST(DiagnoseWhatIf, ImposedWordIsFittedAndReportedNotSelected) {
  const Scenario sc = hidden_effect_scenario("none", kSeed, 0.005, 3.0);
  DiagnoseOptions o;
  o.imposed = {"viscous"};
  const DiagnoseResult R = diagnose(sc.fit, sc.holdout, o);
  EXPECT_TRUE(R.imposed);
  ASSERT_EQ(R.causes.size(), 1u) << R.verdict;
  EXPECT_EQ(R.cause, "viscous");
  EXPECT_EQ(R.verdict.rfind("imposed causes", 0), 0u) << R.verdict;
  // Plain data: neither the held-out nor the fit records show a dashpot, so
  // the verdict does not claim the word was judged on the fit records.
  EXPECT_FALSE(R.causes[0].on_fit_records) << R.verdict;
  EXPECT_EQ(R.verdict.find("judged on the fit records"), std::string::npos) << R.verdict;
  // The first round is the diagnosis's (every word screened); the imposed
  // word was fitted and judged, and not found eligible.
  EXPECT_EQ(R.candidates.size(), candidate_vocabulary().size());
  int fitted = 0;
  for (const CandidateOutcome &co : R.candidates) {
    if (co.cand.name != "viscous") continue;
    ++fitted;
    EXPECT_TRUE(co.joint);
    EXPECT_FALSE(co.eligible) << "plain data selected a cause: " << R.verdict;
    EXPECT_FALSE(co.why.empty());
  }
  EXPECT_EQ(fitted, 1);  // (without the imposition plain data give `none`: Seed5 "none")
}

// A record's length is part of its input: the spectrum's slowest branch
// reaches the longest record the model is run on, held-out ones too (VHB
// 4910's 1800 s holds against 400 s fit records), not only the fit ones.
TEST(DiagnoseWhatIf, SpectrumMemoryReachesTheLongestHeldOutRecord) {
  Scenario sc = hidden_effect_scenario("relaxation_spectrum", kSeed, 0.005, 3.0);
  for (Record &r : sc.fit) {  // fit records of 1.5 s, held-out ones of 3 s
    const size_t n = r.t.size() / 2;
    r.t.resize(n), r.x.resize(n), r.F.resize(n);
  }
  double fit_len = 0.0, hold_len = 0.0;
  for (const Record &r : sc.fit) fit_len = std::max(fit_len, r.t.back() - r.t.front());
  for (const Record &r : sc.holdout) hold_len = std::max(hold_len, r.t.back() - r.t.front());
  ASSERT_GT(hold_len, 1.5 * fit_len);
  DiagnoseOptions o;
  o.quiet = true;
  o.imposed = {"relaxation_spectrum"};
  const DiagnoseResult R = diagnose(sc.fit, sc.holdout, o);
  ASSERT_EQ(R.causes.size(), 1u) << R.verdict;
  EXPECT_NEAR(R.extended_fit.model.p.spec_tau_max, hold_len, 1e-9 * hold_len);
  EXPECT_GT(R.extended_fit.model.p.spec_tau_min, 0.0);
}
#endif

TEST(DiagnoseCli, UnknownOrRepeatedWordIsAUsageErrorAndWritesNothing) {
  const std::string out = std::string(RTB_BINARY_DIR) + "/diagnose_unknown_word.json";
  std::remove(out.c_str());
  for (const char *opt : {"--only viscous,slak", "--causes viscous,slak", "--causes slack,slack"}) {
    const std::string cmd = std::string("'") + RTB_CLI_PATH + "' diagnose --data none.csv " + opt +
                            " --out '" + out + "' 2> /dev/null";
    const int rc = std::system(cmd.c_str());
    EXPECT_TRUE(WIFEXITED(rc) && WEXITSTATUS(rc) == 2) << cmd;
    EXPECT_FALSE(std::ifstream(out).good());
  }
}
