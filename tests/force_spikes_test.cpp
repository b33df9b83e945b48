// force_spikes_test.cpp -- stage 0 of the diagnosis (force_spikes.h):
// isolated one-sample spikes in the force channel are found from the records
// alone and leave the misfit; noise (Gaussian or heavy-tailed), sharp but
// genuine jumps of the force, fast sines sampled coarsely and the measured
// records of ../shared/data are left alone.
#ifdef RTB_HAVE_OFFLINE
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>

#include "offline/diagnose/force_spikes.h"
#include "measured_records.h"

namespace rtb {
namespace {

// 4 s of a sine of amplitude 10 at 1 kHz with white noise of std `noise`
// (Laplace-distributed when `laplace`).
Record spiky_sine(double hz, double noise, bool laplace = false, unsigned seed = 5) {
  std::mt19937 g(seed);
  std::normal_distribution<double> n01(0.0, 1.0);
  std::exponential_distribution<double> ex(1.0);
  Record r;
  r.path = "sine.csv";
  for (int i = 0; i <= 4000; ++i) {
    const double t = 1e-3 * i;
    const double w = laplace ? (ex(g) - ex(g)) / std::sqrt(2.0) : n01(g);
    r.t.push_back(t);
    r.x.push_back(std::sin(2.0 * M_PI * hz * t));
    r.F.push_back(10.0 * std::sin(2.0 * M_PI * hz * t) + noise * w);
  }
  return r;
}

TEST(ForceSpikes, IsolatedSpikesAreFoundAndLeaveTheMisfit) {
  Record r = spiky_sine(2.0, 0.05);
  std::vector<size_t> at;
  for (size_t k = 100; k < r.F.size() - 100; k += 397) {  // 10 spikes of +-0.6 .. 1.5
    const double s = (at.size() % 2 ? -1.0 : 1.0) * (0.6 + 0.1 * (double)at.size());
    r.F[k] += s;
    at.push_back(k);
  }
  std::vector<Record> recs = {r};
  const std::vector<SpikedRecord> s = mask_force_spikes(recs);
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].spikes, (long)at.size());
  for (size_t k : at) EXPECT_EQ(recs[0].masked[k], 1) << "spike at " << k;
  long masked = 0;
  for (char m : recs[0].masked) masked += m;
  EXPECT_EQ(masked, (long)at.size());
  EXPECT_NEAR(s[0].largest, 1.5, 0.25);
  EXPECT_NE(spikes_text(s, 3).find("10 isolated one-sample spikes in 1 of 3 records"), std::string::npos)
      << spikes_text(s, 3);
}

TEST(ForceSpikes, NoiseJumpsAndCoarseSinesAreLeftAlone) {
  // Gaussian and Laplace noise at 0.5% of the amplitude; a 60 Hz sine at
  // 1 kHz (17 samples per period); a force that steps by 3 at one sample
  // three times (a genuine jump leaves +1/2, -1/2, not -1/2, 1, -1/2).
  Record step = spiky_sine(2.0, 0.05);
  for (size_t k = 0; k < step.F.size(); ++k) step.F[k] += 3.0 * (double)(k / 1000);
  std::vector<Record> recs = {spiky_sine(2.0, 0.05), spiky_sine(2.0, 0.05, true), spiky_sine(60.0, 0.05), step};
  for (unsigned seed = 6; seed < 12; ++seed) recs.push_back(spiky_sine(2.0, 0.05, true, seed));
  const std::vector<SpikedRecord> s = mask_force_spikes(recs);
  EXPECT_TRUE(s.empty()) << spikes_text(s, recs.size()) << " first: " << s[0].file;
  for (const Record &r : recs) EXPECT_TRUE(r.masked.empty());
}

TEST(ForceSpikes, TwoSpikesAreNotAGlitchedRecord) {
  Record r = spiky_sine(2.0, 0.05);
  r.F[500] += 1.0;
  r.F[2500] -= 1.0;
  std::vector<Record> recs = {r};
  EXPECT_TRUE(mask_force_spikes(recs).empty());  // at least 3 (and 2e-4 of the samples)
}

// No measured record of ../shared/data has spikes by this test (the
// detector must not mask a friction break-away or a stepped relaxation).
// Skips when the data are absent.
TEST(ForceSpikes, NoMeasuredRecordIsSpiked) {
  std::vector<Record> recs;
  std::string dir;
  if (!rtb_test::measured_records(&recs, &dir))
    GTEST_SKIP() << "measured data " << dir << " absent; skipping";
  ASSERT_GE(recs.size(), 50u);
  const std::vector<SpikedRecord> s = mask_force_spikes(recs);
  EXPECT_TRUE(s.empty()) << spikes_text(s, recs.size()) << " first: " << s[0].file;
}

}  // namespace
}  // namespace rtb
#endif
