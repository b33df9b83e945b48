// residual_signature_test.cpp -- stage 6's trend figures (residual_signature.cpp),
// which withdraw causes that only compensate a drift: a slow trend of the
// force over time counts where the displacement moves, not during a hold,
// where a slowly changing residual is a relaxation shape the model misses
// (VHB 4910's 1800 s holds had softening + friction asymmetry, 8.89% held
// out, withdrawn for it).
#ifdef RTB_HAVE_OFFLINE
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "ext_model_helpers.h"
#include "offline/diagnose/diagnose_stages.h"

namespace rtb {
namespace {

// A 1 Hz sine and a ramp to 1 mm in 0.2 s held to the end, 4 s at 1 kHz.
std::vector<Record> sine_and_hold() {
  Record sine, hold;
  sine.path = "sine";
  hold.path = "hold";
  for (int k = 0; k <= 4000; ++k) {
    const double t = 1e-3 * k;
    sine.t.push_back(t);
    sine.x.push_back(std::sin(2.0 * M_PI * t));
    hold.t.push_back(t);
    hold.x.push_back(std::min(1.0, t / 0.2));
  }
  sine.F.assign(sine.t.size(), 0.0);
  hold.F.assign(hold.t.size(), 0.0);
  std::vector<Record> recs = {sine, hold};
  rtb_test::measure_through(rtb_test::paper_model(), recs);
  return recs;
}

// The records' force plus e(record, t).
template <class E>
std::vector<Record> with_residual(std::vector<Record> recs, E e) {
  for (size_t r = 0; r < recs.size(); ++r)
    for (size_t i = 0; i < recs[r].t.size(); ++i) recs[r].F[i] += e(r, recs[r].t[i]);
  return recs;
}

ResidualSignature signature(const std::vector<Record> &recs) {
  return diag::residual_signature(rtb_test::paper_model(), recs, {}, MisfitOptions());
}

TEST(ResidualSignature, ARelaxationShapeDuringAHoldIsNoTrend) {
  // The hold record's force relaxes 40 N further than the model over its
  // 3.8 s hold; the sine record leaves a 3rd-harmonic miss of 2 N.
  const auto recs = with_residual(sine_and_hold(), [](size_t r, double t) {
    return r == 1 ? (t > 0.2 ? -40.0 * (1.0 - std::exp(-(t - 0.2) / 1.5)) : 0.0)
                  : 2.0 * std::sin(6.0 * M_PI * t);
  });
  EXPECT_LT(signature(recs).trend_share, 0.05);
  EXPECT_LT(signature(recs).drift_share, 0.05);
}

TEST(ResidualSignature, AZeroDriftIsATrendWhereTheInputMoves) {
  // A load-cell zero creeping by 10 N over each record, plus the same
  // relaxation miss as above: the drift still dominates.
  const auto recs = with_residual(sine_and_hold(), [](size_t r, double t) {
    const double relax = r == 1 && t > 0.2 ? -40.0 * (1.0 - std::exp(-(t - 0.2) / 1.5)) : 0.0;
    return 2.5 * (t - 2.0) + relax;
  });
  EXPECT_GT(signature(recs).trend_share, 0.5);
}

}  // namespace
}  // namespace rtb
#endif
