// mullins_definitions_test.cpp -- the Mullins word's two definitions
// (candidates.h, other_definition): the softening of K0 alone, and of the
// whole RT force (rtb_params.mullins_whole, ABI 7). The whole form against
// its closed form (eq. (2) is homogeneous in Kpa, Kr, C0, so the cells move
// as in the plain element and the force is eta times the plain force), the
// map between the two starts, and the joint fit's choice on records made with
// either (blindgen mullins_s1: a loss on the whole material, fitted on K0
// alone, went to the bound and the diagnosis named a cubic spring).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "rt_bushing.h"

namespace {

rtb_params paper(int model) {
  rtb_params p;
  rtb_params_default(&p, model);
  return p;
}

// A growing then shrinking sine (a Mullins history: every level below the
// prior maximum after the peak), 1 kHz.
double mullins_input(int k) {
  const double t = 1e-3 * k;
  const double env = t < 1.0 ? 0.3 + 0.9 * t : std::max(0.2, 1.2 - 0.6 * (t - 1.0));
  return env * std::sin(2.0 * M_PI * 2.0 * t);
}

// eta = 1 - mu (1 - |x| / m) below the prior maximum m, 1 at or above it.
double eta(double mu, double x, double m) {
  return std::fabs(x) < m ? 1.0 - mu * (1.0 - std::fabs(x) / m) : 1.0;
}

TEST(MullinsDefinitions, WholeSofteningScalesThePlainForceExactly) {
  for (int model : {RTB_MODEL_RT, RTB_MODEL_STS}) {
    SCOPED_TRACE(model);
    rtb_params plain = paper(model), whole = plain, k0 = plain;
    whole.mullins = k0.mullins = 0.4;
    whole.mullins_whole = 1.0;
    ASSERT_EQ(rtb_params_validate(&whole), RTB_OK);
    rtb_state sp, sw, sk;
    ASSERT_EQ(rtb_state_init(&sp, &plain, 0.0), RTB_OK);
    ASSERT_EQ(rtb_state_init(&sw, &whole, 0.0), RTB_OK);
    ASSERT_EQ(rtb_state_init(&sk, &k0, 0.0), RTB_OK);
    double m = 0.0, worst = 0.0, fmax = 0.0, differs = 0.0;
    for (int k = 1; k <= 2500; ++k) {
      const double x = mullins_input(k);
      double Fp, Fw, Fk;
      ASSERT_GE(rtb_step(&sp, &plain, NULL, x, 1e-3, &Fp), 0);
      ASSERT_GE(rtb_step(&sw, &whole, NULL, x, 1e-3, &Fw), 0);
      ASSERT_GE(rtb_step(&sk, &k0, NULL, x, 1e-3, &Fk), 0);
      worst = std::max(worst, std::fabs(Fw - eta(0.4, x, m) * Fp));
      differs = std::max(differs, std::fabs(Fw - Fk));
      fmax = std::max(fmax, std::fabs(Fp));
      m = std::max(m, std::fabs(x));
    }
    EXPECT_LE(worst, 1e-12 * fmax) << "the cells must move as in the plain element";
    // The two definitions are different laws: the whole one also softens the
    // chain's (viscous and elastic) force.
    EXPECT_GE(differs, 0.02 * fmax);
  }
}

// Ogden-Roxburgh's shape (mullins_width w > 0): on the whole force the
// element is erf-eta times the plain one, eta = 1 - mu erf((m^2 - x^2)/w^2);
// a narrow w makes the loss nearly uniform below the max, the linear shape's
// is proportional to the distance from it.
TEST(MullinsDefinitions, ErfShapeScalesThePlainForceExactly) {
  for (double w : {0.05, 0.3, 2.0}) {
    SCOPED_TRACE(w);
    rtb_params plain = paper(RTB_MODEL_RT), erfw = plain;
    erfw.mullins = 0.4;
    erfw.mullins_whole = 1.0;
    erfw.mullins_width = w;
    ASSERT_EQ(rtb_params_validate(&erfw), RTB_OK);
    rtb_state sp, se;
    ASSERT_EQ(rtb_state_init(&sp, &plain, 0.0), RTB_OK);
    ASSERT_EQ(rtb_state_init(&se, &erfw, 0.0), RTB_OK);
    double m = 0.0, worst = 0.0, fmax = 0.0, lowest_eta = 1.0;
    for (int k = 1; k <= 2500; ++k) {
      const double x = mullins_input(k);
      double Fp, Fe;
      ASSERT_GE(rtb_step(&sp, &plain, NULL, x, 1e-3, &Fp), 0);
      ASSERT_GE(rtb_step(&se, &erfw, NULL, x, 1e-3, &Fe), 0);
      const double e = std::fabs(x) < m ? 1.0 - 0.4 * std::erf((m * m - x * x) / (w * w)) : 1.0;
      worst = std::max(worst, std::fabs(Fe - e * Fp));
      fmax = std::max(fmax, std::fabs(Fp));
      if (std::fabs(x) < 0.5 * m) lowest_eta = std::min(lowest_eta, e);
      m = std::max(m, std::fabs(x));
    }
    EXPECT_LE(worst, 1e-12 * fmax);
    if (w == 0.05) EXPECT_LT(lowest_eta, 0.6 + 1e-9) << "uniform loss below half the max";
  }
  rtb_params p = paper(RTB_MODEL_RT);
  p.mullins_width = -0.1;
  const char *field = nullptr;
  EXPECT_EQ(rtb_params_check(&p, &field), RTB_ERR_PARAM_RANGE);
  EXPECT_STREQ(field, "mullins_width");
}

TEST(MullinsDefinitions, FlagIsValidatedAndOffWithoutALoss) {
  rtb_params p = paper(RTB_MODEL_RT);
  p.mullins_whole = 0.5;
  EXPECT_EQ(rtb_params_validate(&p), RTB_ERR_PARAM_RANGE);
  p.mullins_whole = 1.0;  // with mu = 0 the element is the plain one
  rtb_params q = paper(RTB_MODEL_RT);
  rtb_state a, b;
  ASSERT_EQ(rtb_state_init(&a, &p, 0.0), RTB_OK);
  ASSERT_EQ(rtb_state_init(&b, &q, 0.0), RTB_OK);
  for (int k = 1; k <= 300; ++k) {
    double Fa, Fb;
    ASSERT_GE(rtb_step(&a, &p, NULL, mullins_input(k), 1e-3, &Fa), 0);
    ASSERT_GE(rtb_step(&b, &q, NULL, mullins_input(k), 1e-3, &Fb), 0);
    ASSERT_EQ(Fa, Fb) << k;
  }
}

}  // namespace

#ifdef RTB_HAVE_OFFLINE
#include "ext_model_helpers.h"

namespace rtb {
namespace {

const Candidate &mullins_word() { return rtb_test::vocabulary_word("mullins"); }

TEST(MullinsDefinitions, TheOtherDefinitionStartsWithTheSameStaticLoss) {
  ExtModel start = rtb_test::paper_model();
  start.p.mullins = 0.6;
  const rtb_params &p = start.p;
  const double share = p.K0 / (p.K0 + 1.0 / (1.0 / p.Kpa + p.cells / p.Kr));
  Candidate alt;
  ExtModel alt_start;
  ASSERT_TRUE(other_definition(mullins_word(), start, DataScales(), &alt, &alt_start));
  EXPECT_EQ(alt.name, "mullins");
  EXPECT_EQ(alt.variant, "whole");
  ASSERT_EQ(alt.extra.size(), 1u);
  EXPECT_EQ(alt.extra[0], P_mullins);
  EXPECT_EQ(alt_start.p.mullins_whole, 1.0);
  EXPECT_NEAR(alt_start.p.mullins, std::max(0.05, 0.6 * share), 1e-15);
  Candidate back;
  ExtModel back_start;
  ASSERT_TRUE(other_definition(alt, alt_start, DataScales(), &back, &back_start));
  EXPECT_EQ(back.variant, "");
  EXPECT_EQ(back_start.p.mullins_whole, 0.0);
  EXPECT_NEAR(back_start.p.mullins, std::min(0.9, alt_start.p.mullins / share), 1e-15);
}

Record growing_sine(const char *name, double hz) {
  Record r;
  r.path = name;
  for (int k = 0; k <= 3000; ++k) {
    const double t = 1e-3 * k;
    r.t.push_back(t);
    r.x.push_back((0.4 + 0.6 * std::min(1.0, t / 1.5)) * std::sin(2.0 * M_PI * hz * t) *
                  (t < 2.0 ? 1.0 : 0.5));
    r.F.push_back(0.0);
  }
  return r;
}

using rtb_test::fit_word;

// Records made with one definition: its fit reaches them, the other's does not.
TEST(MullinsDefinitions, TheRecordsChooseTheirDefinition) {
  const Candidate &k0 = mullins_word();
  Candidate whole;
  ExtModel unused;
  ASSERT_TRUE(other_definition(k0, rtb_test::paper_model(), DataScales(), &whole, &unused));
  for (bool truth_whole : {true, false}) {
    SCOPED_TRACE(truth_whole);
    ExtModel truth = rtb_test::paper_model();
    truth.p.mullins = truth_whole ? 0.3 : 0.5;
    truth.p.mullins_whole = truth_whole ? 1.0 : 0.0;
    std::vector<Record> recs = {growing_sine("slow", 0.7), growing_sine("fast", 4.0)};
    rtb_test::measure_through(truth, recs);
    ExtModel from_k0 = rtb_test::paper_model(), from_whole = from_k0;
    from_k0.p.mullins = 0.3;
    from_whole.p.mullins = 0.2;
    from_whole.p.mullins_whole = 1.0;
    const ExtFitResult a = fit_word(k0, from_k0, recs), b = fit_word(whole, from_whole, recs);
    const ExtFitResult &right = truth_whole ? b : a, &wrong = truth_whole ? a : b;
    EXPECT_NEAR(right.model.p.mullins, truth.p.mullins, 1e-4);
    EXPECT_LT(right.error, 1e-6);
    EXPECT_GT(wrong.error, 100.0 * right.error + 1e-3) << "one definition fits the other's data";
  }
}

}  // namespace
}  // namespace rtb
#endif
