// noise_floor_test.cpp -- the noise level the diagnosis estimates from a
// residual (noise_floor.h): white noise by the fourth differences, band-
// limited noise (an anti-alias filter) by their spread at lags 1-4, and
// never more than the residual holds. Sequences made here with the
// standard library's generator, not the diagnosis's.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "offline/diagnose/noise_floor.h"
#include "test_numbers.h"

namespace {


// Unit-variance noise with correlation a^|k| (a = 0: white), plus a smooth
// model error of amplitude `smooth` at 20 Hz (1 kHz sampling).
std::vector<double> residual(double a, double smooth, unsigned seed, size_t n = 4000) {
  std::mt19937_64 gen(seed);
  std::normal_distribution<double> z(0.0, 1.0);
  std::vector<double> e(n);
  double v = z(gen);
  const double b = std::sqrt(1.0 - a * a);
  for (size_t k = 0; k < n; ++k) {
    if (k > 0) v = a * v + b * z(gen);
    e[k] = v + smooth * std::sin(kTwoPi * 20.0 * 1e-3 * (double)k);
  }
  return e;
}

}  // namespace

// White noise: no correlation (below the white threshold), the white
// estimate exactly;
// a smooth model error four times the noise does not move it.
TEST(NoiseSigma, WhiteNoiseIsTheFourthDifferenceEstimate) {
  for (unsigned seed = 1; seed <= 5; ++seed) {
    const std::vector<double> e = residual(0.0, 4.0, seed);
    const double a = rtb::noise_correlation(e);
    const double s = rtb::noise_sigma(e, a);
    EXPECT_LT(a, rtb::kWhiteBelow);
    EXPECT_EQ(s, rtb::white_noise_sigma(e));
    EXPECT_NEAR(s, 1.0, 0.06);
  }
}

// Band-limited noise (corners 60-150 Hz at 1 kHz): the white estimate
// sees 0.45-0.8 of it. The fitted level is closer to the truth than that
// (within 30%: a^L changes little between lags when a nears 0.7, so a 4000-
// sample record pins a to about 0.1), with a smooth model error as large as
// the noise.
TEST(NoiseSigma, BandLimitedNoiseKeepsItsLevel) {
  for (double hz : {60.0, 100.0, 150.0}) {
    const double a_true = std::exp(-kTwoPi * hz * 1e-3);
    for (unsigned seed = 1; seed <= 3; ++seed) {
      const std::vector<double> e = residual(a_true, 1.0, seed);
      const double a = rtb::noise_correlation(e);
      const double s = rtb::noise_sigma(e, a);
      const double white = rtb::white_noise_sigma(e);
      EXPECT_LT(white, 0.8) << hz << " Hz";
      EXPECT_LT(std::fabs(s - 1.0), std::fabs(white - 1.0)) << hz << " Hz, seed " << seed;
      EXPECT_NEAR(s, 1.0, 0.3) << hz << " Hz, seed " << seed;
      EXPECT_NEAR(a, a_true, 0.12) << hz << " Hz, seed " << seed;
    }
  }
}

// A mains hum (50 Hz and its third harmonic, 3 noise sigmas) also raises
// the spread with the lag, but not as band-limited noise does: it is no
// correlation of the noise, and the floor stays the white noise's (the hum
// is what the residual holds above it).
TEST(NoiseSigma, AHumIsNotBandLimitedNoise) {
  for (unsigned seed = 1; seed <= 4; ++seed) {
    std::vector<double> e = residual(0.0, 0.0, seed);
    for (size_t k = 0; k < e.size(); ++k) {
      const double p = kTwoPi * 50.0 * 1e-3 * (double)k;
      e[k] += 3.0 * (std::sin(p) + 0.3 * std::sin(3.0 * p));
    }
    EXPECT_EQ(rtb::noise_correlation(e), 0.0) << "seed " << seed;
    EXPECT_NEAR(rtb::noise_sigma(e, rtb::noise_correlation(e)), 1.0, 0.1);
  }
}

// Never above the residual's own robust spread: strongly correlated noise
// (a = 0.95) whose a the fit cannot resolve (it is capped at 0.8) gives at
// most what the values hold.
TEST(NoiseSigma, NeverMoreThanTheResidualHolds) {
  std::vector<double> e = residual(0.95, 0.0, 7);
  double mean = 0.0, sq = 0.0;
  for (double v : e) mean += v / (double)e.size();
  for (double v : e) sq += (v - mean) * (v - mean) / (double)e.size();
  EXPECT_LE(rtb::noise_sigma(e, rtb::noise_correlation(e)), 1.1 * std::sqrt(sq));
}

// The correlation is the acquisition chain's: the median over the records.
// Records at rest (x = 0, so the model's force is 0 and the residual is the
// measured force): three with white noise and one whose residual looks
// correlated (a model error that grows with the lag) stay white; four with
// band-limited noise are band-limited.
TEST(NoiseFloor, TheCorrelationIsTheChainsNotOneRecords) {
  auto record = [](double a, unsigned seed) {
    rtb::Record r;
    r.F = residual(a, 0.0, seed);
    for (size_t k = 0; k < r.F.size(); ++k) r.t.push_back(1e-3 * (double)k);
    r.x.assign(r.F.size(), 0.0);
    return r;
  };
  rtb::ExtModel m;
  rtb_params_default(&m.p, RTB_MODEL_RT);
  const rtb::MisfitOptions opt;
  const std::vector<rtb::Record> white = {record(0.0, 1), record(0.0, 2), record(0.0, 3)};
  const rtb::NoiseFloor one = rtb::estimate_noise_floor(m, white, {record(0.6, 4)}, opt);
  EXPECT_EQ(one.correlation, 0.0);
  EXPECT_EQ(one.sigma_holdout[0], rtb::white_noise_sigma(record(0.6, 4).F));
  const rtb::NoiseFloor all = rtb::estimate_noise_floor(
      m, {record(0.6, 1), record(0.6, 2), record(0.6, 3)}, {record(0.6, 4)}, opt);
  EXPECT_NEAR(all.correlation, 0.6, 0.12);
  EXPECT_NEAR(all.sigma_holdout[0], 1.0, 0.3);
}

// Stage 0's displacement filter reshapes the displacement's share of the
// residual (the model returns K lp(x_noise)), and the four lags of that
// residual fit no a^|k|; on the recorded displacement, whose noise came
// through the same chain as the force's, they do (refgen
// colored_noise_s57). A 2 Hz sine through the default element, noise of
// correlation 0.4 on both channels (the displacement's at K sigma_x = 1.5
// sigma_F), the model input smoothed by a zero-phase 1-4-6-4-1 filter.
TEST(NoiseFloor, TheCorrelationIsReadOnTheRecordedDisplacement) {
  const double a_true = 0.4;
  rtb::ExtModel m;
  rtb_params_default(&m.p, RTB_MODEL_RT);
  const rtb::MisfitOptions opt;
  std::vector<rtb::Record> recs;
  std::vector<std::vector<double>> recorded;
  double sigma_F = 0.0;
  for (unsigned seed = 1; seed <= 4; ++seed) {
    rtb::Record r;
    for (size_t k = 0; k < 4000; ++k) {
      r.t.push_back(1e-3 * (double)k);
      r.x.push_back(std::sin(kTwoPi * (1.0 + 0.5 * seed) * r.t.back()));
    }
    r.F.assign(r.x.size(), 0.0);
    Eigen::VectorXd F;
    rtb::predict_extended(m, r, opt.sim, rtb::ExtFitSpec(), F, nullptr);
    double lo = F.minCoeff(), hi = F.maxCoeff(), k_eff = (hi - lo) / 2.0;
    sigma_F = 0.01 * (hi - lo);
    const std::vector<double> nF = residual(a_true, 0.0, seed), nx = residual(a_true, 0.0, 100 + seed);
    for (size_t k = 0; k < r.x.size(); ++k) {
      r.F[k] = F[(Eigen::Index)k] + sigma_F * nF[k];
      r.x[k] += 1.5 * sigma_F / k_eff * nx[k];
    }
    recorded.push_back(r.x);
    std::vector<double> s = r.x;  // the model input: smoothed
    for (size_t k = 2; k + 2 < s.size(); ++k)
      s[k] = (r.x[k - 2] + 4 * r.x[k - 1] + 6 * r.x[k] + 4 * r.x[k + 1] + r.x[k + 2]) / 16.0;
    r.x = s;
    recs.push_back(r);
  }
  const std::vector<rtb::Record> fit(recs.begin(), recs.begin() + 3), hold(recs.begin() + 3, recs.end());
  const rtb::NoiseFloor own = rtb::estimate_noise_floor(m, fit, hold, opt);
  const rtb::NoiseFloor rec = rtb::estimate_noise_floor(m, fit, hold, opt, recorded);
  std::printf("correlation: filtered input %.2f, recorded %.2f; sigma %.3f / %.3f of sigma_F\n",
              own.correlation, rec.correlation, own.sigma_holdout[0] / sigma_F,
              rec.sigma_holdout[0] / sigma_F);
  EXPECT_NEAR(rec.correlation, a_true, 0.12);
  EXPECT_GT(rec.sigma_holdout[0], 0.9 * sigma_F);
  EXPECT_LT(own.sigma_holdout[0], 0.8 * sigma_F);  // the white estimate of the filtered input's
  // Not given, or the records' own: as before.
  const rtb::NoiseFloor same = rtb::estimate_noise_floor(
      m, fit, hold, opt, {fit[0].x, fit[1].x, fit[2].x, hold[0].x});
  EXPECT_EQ(same.correlation, own.correlation);
  EXPECT_EQ(same.error_holdout, own.error_holdout);
}
