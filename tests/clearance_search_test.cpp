// clearance_search_test.cpp -- how many bushing responses the clearance
// search of rtb_step (step.cpp, resolve_gap) spends per step (issue #11): a
// contact that holds costs one, a floating end found by Newton from the
// last position two or three. Its answers (contact or a free end at zero
// force) are checked in step_info_test.cpp (ClearanceIterationsAndResidual).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "physics_helpers.h"
#include "rt_bushing/rt_bushing.h"

namespace {

struct SearchCost {
  double mean_responses;
  int max_responses, max_work, free_steps;
};

// BM_Extension's input (10 Hz, 1 mm sine with 10 um noise at 1 kHz) after
// 2000 steps of warm-up; every step must converge.
SearchCost search_cost(const rtb_params &p) {
  std::mt19937_64 g(12345);
  std::normal_distribution<double> noise(0.0, 0.01);
  rtb_state s;
  EXPECT_EQ(rtb_state_init(&s, &p, 0.0), RTB_OK);
  SearchCost c{0.0, 0, 0, 0};
  const int warm = 2000, steps = 10000;
  for (int i = 0; i < warm + steps; ++i) {
    const double x = std::sin(2.0 * rtbtest::kPi * 10.0 * (i + 1) * 1e-3) + noise(g);
    double F;
    rtb_step_info info;
    EXPECT_EQ(rtb_step_ex(&s, &p, nullptr, x, 1e-3, &F, &info), RTB_OK) << i;
    if (i < warm) continue;
    c.mean_responses += info.clearance_iterations / (double)steps;
    c.max_responses = std::max(c.max_responses, (int)info.clearance_iterations);
    c.max_work = std::max(c.max_work, (int)info.work);
    c.free_steps += s.contact == 0;
  }
  return c;
}

}  // namespace

TEST(ClearanceSearch, ResponsesPerStepOnTheExtensionBenchmarkInput) {
  // Session 35's search on the same input: 1.51 responses per step, at most
  // 5, 176 work units at most: a contact that still held was solved twice
  // (the clamped old position first), and every floating step checked the
  // far contact point before its Newton search.
  rtb_params p = rtbtest::paper_params(RTB_MODEL_RT);
  p.backlash = 0.05;
  const SearchCost c = search_cost(p);
  std::printf("[clearance] 0.05 mm: %.3f responses per step, at most %d; work at most %d; %d free steps\n",
              c.mean_responses, c.max_responses, c.max_work, c.free_steps);
  EXPECT_GT(c.free_steps, 100);  // the search is exercised, not only contacts
  EXPECT_LE(c.mean_responses, 1.1);
  EXPECT_LE(c.max_responses, 4);
  EXPECT_LE(c.max_work, 150);
}
