// preload_start_test.cpp -- records that start away from zero (a preloaded
// specimen): the automatic choice between the ramp of section 5.5 and a
// ramp-and-hold, the held start against the paper's static limit, the exact
// adjoint through the hold, and no spurious inertia impulse at the start.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "offline/identify/gradcheck.h"
#include "offline/model/forward.h"
#include "offline_test_records.h"

using namespace rtb;

namespace {

// A 1 Hz sine of amplitude a about x0, at 1 kHz for `duration` s.
Record sine_about(double x0, double a, double duration) {
  Record r;
  for (int i = 0; i * 1e-3 <= duration + 1e-12; ++i) {
    const double t = i * 1e-3;
    r.t.push_back(t);
    r.x.push_back(x0 + a * std::sin(6.283185307179586 * t));
    r.F.push_back(0.0);
  }
  return r;
}

rtb_params paper_rt() {
  rtb_params p;
  rtb_params_default(&p, RTB_MODEL_RT);
  return p;
}

// The paper's static limit (all dashpots relaxed): K0 x + x / (1/Kpa + N/Kr).
double static_limit(const rtb_params &p, double x) {
  return p.K0 * x + x / (1.0 / p.Kpa + p.cells / p.Kr);
}

}  // namespace

TEST(PreloadStart, AutomaticHoldsOnlyAStartBeyondTheNoise) {
  SimOptions sim;
  EXPECT_FALSE(holds_start(sine_about(0.003, 1.0, 0.5), sim));  // the rig's zero plus noise
  EXPECT_TRUE(holds_start(sine_about(0.5, 1.0, 0.5), sim));     // a preload
  EXPECT_TRUE(holds_start(sine_about(-0.5, 1.0, 0.5), sim));
  sim.start = StartMode::ramp;
  EXPECT_FALSE(holds_start(sine_about(0.5, 1.0, 0.5), sim));
  sim.start = StartMode::hold;
  EXPECT_TRUE(holds_start(sine_about(0.003, 1.0, 0.5), sim));

  const Record r = sine_about(0.8, 0.2, 0.5);
  SimOptions ramp;
  ramp.start = StartMode::ramp;
  const DriveGrid gr = make_drive_grid(r, ramp), gh = make_drive_grid(r, SimOptions());
  EXPECT_FALSE(gr.held);
  EXPECT_TRUE(gh.held);
  EXPECT_GT(gh.first_sample, gr.first_sample);
  EXPECT_EQ(gh.x.size() - gh.first_sample, r.x.size());
  double held = 0.0;
  for (int i = gr.first_sample + 1; i <= gh.first_sample; ++i) {
    EXPECT_EQ(gh.x[i], r.x[0]);
    held += gh.dt[i];
  }
  EXPECT_GT(held, 1e5);  // the hold is long against every relaxation time of the element
  const Record at_zero = sine_about(0.0, 1.0, 0.5);
  EXPECT_EQ(make_drive_grid(at_zero, SimOptions()).first_sample, 0);
}

// After the hold the element is at the paper's static limit, which the ramp
// alone (the specimen just arrived) is not. alpha = 0.5: a dashpot force decays
// as t^-1 there, so 1e5 s leaves nothing a record could see.
TEST(PreloadStart, HeldStartIsTheStaticLimit) {
  rtb_params p = paper_rt();
  p.alpha = 0.5;
  const double x0 = 1.0;
  const Record r = sine_about(x0, 0.1, 0.2);
  const double Fs = static_limit(p, x0);
  const double held = simulate_force(p, r, SimOptions())[0];
  SimOptions ramp;
  ramp.start = StartMode::ramp;
  const double ramped = simulate_force(p, r, ramp)[0];
  EXPECT_NEAR(held, Fs, 1e-4 * std::fabs(Fs));
  EXPECT_GT(std::fabs(ramped - Fs), 0.05 * std::fabs(Fs)) << "the ramp alone should not be relaxed";
  // The paper's alpha = 0.2: a cell's dashpot force decays as t^-1/4, so
  // after 1e5 s some remains (as it would on any rig), within 1% of the load
  // and a tenth of what the ramp leaves.
  const double held_paper = simulate_force(paper_rt(), r, SimOptions())[0];
  const double ramped_paper = simulate_force(paper_rt(), r, ramp)[0];
  const double Fs_paper = static_limit(paper_rt(), x0);
  EXPECT_NEAR(held_paper, Fs_paper, 1e-2 * Fs_paper);
  EXPECT_LT(std::fabs(held_paper - Fs_paper), 0.1 * std::fabs(ramped_paper - Fs_paper));
}

// The hold is ordinary steps: the gradient stays the exact adjoint of the
// discrete stepper, with the memories the hold sets (Maxwell, Mullins, a held
// clearance, then the inertia term whose input velocity restarts) in play.
TEST(PreloadStart, AdjointIsExactThroughTheHold) {
  rtb_params truth = paper_rt();
  std::vector<Record> recs = rtb_test::paper_records(truth, 0.5);
  for (Record &r : recs)
    for (double &x : r.x) x += 0.6;  // preloaded by 0.6 mm: every record is held first
  for (const Record &r : recs) ASSERT_TRUE(holds_start(r, SimOptions()));
  rtb_params p = truth;
  p.K0 *= 0.8;
  p.alpha = 0.3;
  p.maxwell_k = 200;
  p.maxwell_tau = 0.05;
  p.mullins = 0.2;
  p.k3 = 40;
  p.backlash = 0.0517;
  p.backlash_held = 1;
  const GradcheckResult g = gradcheck(p, recs, MisfitOptions());
  ASSERT_FALSE(g.rows.empty());
  for (const GradcheckRow &r : g.rows)
    EXPECT_LT(r.rel, 1e-6) << param_name(r.id) << " adjoint " << r.adjoint << " fd " << r.fd;
  EXPECT_LT(g.dot_product_rel_mismatch, 1e-10);
  // The inertia term, whose input velocity restarts after the hold. (With
  // the held clearance too, mass agrees to only ~1.5e-6: FD straddles a
  // contact switch of that clearance near the preloaded records' samples,
  // as with a gap of exactly 0.05 in AdjointIntegrators.)
  p.backlash = 0.0;
  p.mass = 1e-3;
  const GradcheckResult gm = gradcheck(p, recs, MisfitOptions());
  for (const GradcheckRow &r : gm.rows)
    EXPECT_LT(r.rel, 1e-6) << param_name(r.id) << " adjoint " << r.adjoint << " fd " << r.fd;
}

// A held specimen has no input velocity; a record that starts moving must not
// see the velocity jump as an acceleration m v0 / dt at its first sample.
TEST(PreloadStart, NoInertiaImpulseWhereTheRecordStartsMoving) {
  rtb_params p = paper_rt();
  const Record r = sine_about(0.8, 0.5, 0.05);  // starts at 3.1 mm/s
  const std::vector<double> F0 = simulate_force(p, r, SimOptions());
  p.mass = 1e-3;  // [force time^2 / length]
  const std::vector<double> Fm = simulate_force(p, r, SimOptions());
  // m a of the sine itself at t = 1 ms is m (2 pi)^2 0.5 sin(2 pi 1e-3) ~ 1e-4 N;
  // an impulse would be m v0 / dt = 3.1 N.
  EXPECT_LT(std::fabs(Fm[1] - F0[1]), 1e-2);
  EXPECT_LT(std::fabs(Fm[2] - F0[2]), 1e-2);
}
