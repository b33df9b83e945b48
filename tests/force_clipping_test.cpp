// force_clipping_test.cpp -- stage 0 of the diagnosis (force_clipping.h): a
// saturated force channel is found from the records alone, its samples
// leave the misfit, and noisy or coarsely quantized unclipped records are
// left alone.
#ifdef RTB_HAVE_OFFLINE
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>

#include "offline/diagnose/force_clipping.h"
#include "measured_records.h"

namespace rtb {
namespace {

// 2 s of a 2 Hz sine of amplitude 10 at 1 kHz, with white noise, then
// optionally clipped at +-clip and quantized to steps of q.
Record clipped_sine(double noise, double clip, double q, unsigned seed = 3) {
  std::mt19937 g(seed);
  std::normal_distribution<double> n01(0.0, 1.0);
  Record r;
  r.path = "sine.csv";
  for (int i = 0; i <= 2000; ++i) {
    const double t = 1e-3 * i;
    double F = 10.0 * std::sin(2.0 * M_PI * 2.0 * t) + noise * n01(g);
    if (clip > 0.0) F = std::fmax(-clip, std::fmin(clip, F));
    if (q > 0.0) F = q * std::round(F / q);
    r.t.push_back(t);
    r.x.push_back(std::sin(2.0 * M_PI * 2.0 * t));
    r.F.push_back(F);
  }
  return r;
}

TEST(ForceClipping, SaturatedChannelIsFoundAndLeavesTheMisfit) {
  std::vector<Record> recs = {clipped_sine(0.05, 8.0, 0.0)};
  const std::vector<ClippedRecord> c = mask_force_clipping(recs);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_TRUE(c[0].top);
  EXPECT_TRUE(c[0].bottom);
  EXPECT_DOUBLE_EQ(c[0].level_top, 8.0);
  EXPECT_DOUBLE_EQ(c[0].level_bottom, -8.0);
  // |10 sin| > 8 for 2 acos(0.8)/pi = 41% of the time, up to the noise.
  EXPECT_NEAR((double)c[0].samples / 2001.0, 0.41, 0.02);
  long masked = 0;
  for (size_t i = 0; i < recs[0].F.size(); ++i) {
    masked += recs[0].masked[i];
    if (recs[0].masked[i]) EXPECT_EQ(std::fabs(recs[0].F[i]), 8.0);
  }
  EXPECT_EQ(masked, c[0].samples);
  EXPECT_NE(clipping_text(c, 1).find("clipped at 8 and -8 in 1 of 1 records"), std::string::npos)
      << clipping_text(c, 1);
}

TEST(ForceClipping, OneSidedClippingIsOneSided) {
  Record r = clipped_sine(0.05, 0.0, 0.0);
  for (double &F : r.F) F = std::fmin(F, 9.0);
  std::vector<Record> recs = {r};
  const std::vector<ClippedRecord> c = mask_force_clipping(recs);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_TRUE(c[0].top);
  EXPECT_FALSE(c[0].bottom);
}

TEST(ForceClipping, NoisyOrQuantizedUnclippedRecordsAreLeftAlone) {
  // Noise only; noise-free but quantized to 1% and 0.1% of the amplitude
  // (a smooth peak holds its top code for a while, as long as the next one);
  // quantized with noise.
  std::vector<Record> recs = {clipped_sine(0.05, 0.0, 0.0), clipped_sine(0.0, 0.0, 0.1), clipped_sine(0.0, 0.0, 0.01),
                              clipped_sine(0.05, 0.0, 0.01)};
  EXPECT_TRUE(mask_force_clipping(recs).empty());
  for (const Record &r : recs) EXPECT_TRUE(r.masked.empty());
  // The same records clipped are found, quantized or not.
  std::vector<Record> clipped = {clipped_sine(0.0, 9.0, 0.1), clipped_sine(0.05, 9.0, 0.01)};
  EXPECT_EQ(mask_force_clipping(clipped).size(), 2u);
}

// No measured record of ../shared/data is clipped (the detector must not
// mask real peaks). Skips when the data are absent.
TEST(ForceClipping, NoMeasuredRecordIsClipped) {
  std::vector<Record> recs;
  std::string dir;
  if (!rtb_test::measured_records(&recs, &dir))
    GTEST_SKIP() << "measured data " << dir << " absent; skipping";
  ASSERT_GE(recs.size(), 50u);
  const std::vector<ClippedRecord> c = mask_force_clipping(recs);
  EXPECT_TRUE(c.empty()) << clipping_text(c, recs.size()) << " first: " << c[0].file;
}

}  // namespace
}  // namespace rtb
#endif
