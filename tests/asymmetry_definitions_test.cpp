// asymmetry_definitions_test.cpp -- the asymmetry word's two definitions
// (candidates.h, other_definition): k_asym |xb| (a kink at 0) and the
// quadratic spring k2 xb^2 (ABI 6). The element's static law against the
// closed form, the map between the two starts, and the joint fit's choice:
// on records made with one definition, the fit of that definition reaches
// the data and the other does not (refgen asymmetry_quadratic: fitted with
// |x| only, a friction asymmetry took the leftover on 3 of 4 seeds).
#ifdef RTB_HAVE_OFFLINE
#include <gtest/gtest.h>

#include <cmath>

#include "ext_model_helpers.h"

namespace rtb {
namespace {

// A slow triangle (quasi-static loops) and a 3 Hz sine, from rest at 0.
Record record(const char *name, double hz, double amp, bool triangle) {
  Record r;
  r.path = name;
  for (double t = 0.0; t <= 3.0 + 1e-12; t += 1e-3) {
    const double phase = hz * t - std::floor(hz * t);
    r.t.push_back(t);
    r.x.push_back(triangle ? amp * (phase < 0.25   ? 4.0 * phase
                                    : phase < 0.75 ? 2.0 - 4.0 * phase
                                                   : 4.0 * phase - 4.0)
                           : amp * std::sin(2.0 * M_PI * hz * t));
    r.F.push_back(0.0);
  }
  return r;
}

using rtb_test::paper_model;

std::vector<Record> asymmetry_records(const ExtModel &truth) {
  std::vector<Record> recs = {record("triangle", 0.5, 1.2, true), record("sine", 3.0, 0.7, false)};
  rtb_test::measure_through(truth, recs);
  return recs;
}

const Candidate &asymmetry_word() { return rtb_test::vocabulary_word("asymmetry"); }

TEST(AsymmetryDefinitions, QuadraticSpringIsInTheStaticLaw) {
  rtb_params p = paper_model().p;
  p.k2 = -40.0;
  ASSERT_EQ(rtb_params_validate(&p), RTB_OK);
  const double chain = 1.0 / (1.0 / p.Kpa + p.cells / p.Kr);
  for (double x : {-1.5, -0.2, 0.0, 0.7, 2.0})
    EXPECT_NEAR(rtb_static_force(&p, x), (p.K0 + chain) * x - 40.0 * x * x, 1e-12 * (1 + x * x));
  // A state initialised at x0 carries the static force (the relaxed chain).
  rtb_state s;
  ASSERT_EQ(rtb_state_init(&s, &p, 0.9), RTB_OK);
  EXPECT_NEAR(s.force, rtb_static_force(&p, 0.9), 1e-12 * std::fabs(s.force));
}

TEST(AsymmetryDefinitions, TheOtherDefinitionMatchesAtTwoThirdsOfTheStroke) {
  DataScales sc;
  sc.Xmax = 1.5;
  ExtModel start = paper_model();
  start.p.k_asym = 90.0;
  Candidate alt;
  ExtModel alt_start;
  ASSERT_TRUE(other_definition(asymmetry_word(), start, sc, &alt, &alt_start));
  EXPECT_EQ(alt.name, "asymmetry");
  EXPECT_EQ(alt.variant, "quadratic");
  ASSERT_EQ(alt.extra.size(), 1u);
  EXPECT_EQ(alt.extra[0], P_k2);
  EXPECT_EQ(alt_start.p.k_asym, 0.0);
  EXPECT_DOUBLE_EQ(alt_start.p.k2, 90.0);  // k2 x^2 = k_asym |x| at x = 2/3 Xmax = 1
  // And back, to the kink (clamped to |k_asym| <= 0.9 K0).
  Candidate back;
  ExtModel back_start;
  ASSERT_TRUE(other_definition(alt, alt_start, sc, &back, &back_start));
  EXPECT_EQ(back.variant, "");
  EXPECT_EQ(back.extra[0], P_k_asym);
  EXPECT_DOUBLE_EQ(back_start.p.k_asym, 90.0);
  EXPECT_EQ(back_start.p.k2, 0.0);
  // Words with one definition have no other.
  for (const Candidate &c : candidate_vocabulary())
    if (c.name == "cubic_stiffness" || c.name == "viscous")
      EXPECT_FALSE(other_definition(c, start, sc, &alt, &alt_start)) << c.name;
}

using rtb_test::fit_word;

TEST(AsymmetryDefinitions, TheRecordsChooseTheirDefinition) {
  const Candidate &kink = asymmetry_word();
  Candidate quad;
  ExtModel unused;
  ASSERT_TRUE(other_definition(kink, paper_model(), DataScales(), &quad, &unused));
  // Quadratic truth: tangent K0 + 2 k2 x, +-25% of the static stiffness at 1.2 mm.
  ExtModel truth = paper_model();
  truth.p.k2 = 120.0;
  const std::vector<Record> recs = asymmetry_records(truth);
  ExtModel from_kink = paper_model();
  from_kink.p.k_asym = 100.0;
  ExtModel from_quad = paper_model();
  from_quad.p.k2 = 80.0;
  const ExtFitResult a = fit_word(kink, from_kink, recs), b = fit_word(quad, from_quad, recs);
  EXPECT_NEAR(b.model.p.k2, 120.0, 1e-3);
  EXPECT_LT(b.error, 1e-6);
  EXPECT_GT(a.error, 100.0 * b.error + 1e-3) << "the kink fits a quadratic term too well";
  // Kink truth: the other way round.
  truth = paper_model();
  truth.p.k_asym = 150.0;
  const std::vector<Record> recs2 = asymmetry_records(truth);
  const ExtFitResult c = fit_word(kink, from_kink, recs2), d = fit_word(quad, from_quad, recs2);
  EXPECT_NEAR(c.model.p.k_asym, 150.0, 1e-3);
  EXPECT_GT(d.error, 100.0 * c.error + 1e-3);
}

// A tension side softer than K0 alone (blindgen asymmetry_s34: a bilinear
// spring 471 N/mm softer in tension, K0 151): the kink takes K0 below zero
// while the chain holds the static tangent up, |k_asym| <= K0 + chain. Held
// at |k_asym| <= K0, the fit stopped at the clamp and a friction asymmetry
// took the leftover.
TEST(AsymmetryDefinitions, AKinkPastK0AloneIsFound) {
  ExtModel truth = paper_model();
  const double chain = 1.0 / (1.0 / truth.p.Kpa + truth.p.cells / truth.p.Kr);
  const double K0 = truth.p.K0;
  truth.p.K0 = K0 - 0.5 * (K0 + 0.6 * chain);  // bilinear: -(K0 + 0.6 chain) max(x, 0)
  truth.p.k_asym = -0.5 * (K0 + 0.6 * chain);
  ASSERT_EQ(rtb_params_validate(&truth.p), RTB_OK);
  ASSERT_GT(-truth.p.k_asym, truth.p.K0) << "past K0 alone";
  const std::vector<Record> recs = asymmetry_records(truth);
  ExtModel from_kink = paper_model();
  from_kink.p.k_asym = -0.5 * K0;
  const ExtFitResult a = fit_word(asymmetry_word(), from_kink, recs);
  EXPECT_NEAR(a.model.p.k_asym, truth.p.k_asym, 1e-4 * chain);
  EXPECT_NEAR(a.model.p.K0, truth.p.K0, 1e-4 * chain);
  EXPECT_LT(a.error, 1e-6);
}

}  // namespace
}  // namespace rtb
#endif
