// noise_floor.h -- how small the residual can get: the white-noise level of
// the measurement, estimated from the data itself.
//
// The baseline residual e = F_measured - F_model carries (a) the model's
// error, smooth in time like the input, and (b) white noise: the force
// sensor's and the displacement sensor's (the model, driven by a noisy x,
// returns K x_noise). Fourth differences of e remove (a) -- a component at
// frequency f is scaled by (2 sin(pi f dt))^4, 1e-3 at f = fs/30 -- and keep
// (b) with variance 70 sigma^2, so sigma = 1.4826 MAD(d4 e) / sqrt(70);
// the median ignores the few large differences at input corners or steps.
// Acquisition chains often band-limit the noise (an anti-alias filter):
// correlated noise has less high-frequency content, and the white estimate
// is then 0.4-0.7 of its level (refgen colored_noise, a first-order
// low-pass at 5-15% of the sample rate: plain RT came out `unexplained` at
// 2x the floor). So sigma is fitted to the fourth differences at lags 1 to
// 4 with the noise correlation a^|k| of a first-order low-pass: their
// variances are sigma^2 q(a^L), q(a) = 70 - 112 a + 56 a^2 - 16 a^3 + 2 a^4.
// White noise gives a within 0.1 of 0; the white estimate is kept below
// a = 0.2, and a is capped at 0.8 (beyond, q(a^L) hardly changes with L and
// a would be guessed, in the direction that raises the floor). The
// correlation is the chain's: the median over the records of a diagnosis.
// Stage 0's displacement filter reshapes the displacement's share of the
// residual (the model returns K lp(x_noise), correlated over more lags than
// the chain's a^|k|), so the four lags of that residual may fit no a^|k| at
// all; the residual on the recorded displacement, whose noise on both
// channels came through the same chain, still does. The correlation is the
// larger of the two medians (refgen colored_noise_s57, a 135 Hz corner at
// 1 kHz: filtered residual no fit, taken as white, `unexplained` at 2.2x a
// floor of 0.90%; with the recorded displacement a = 0.35, floor 1.61%).
// The floor is the eq. (27) error that noise alone would give on a set of
// records: sqrt(sum_r w_r sigma_r^2 T_r / (2 J0)).
#ifndef RTB_OFFLINE_NOISE_FLOOR_H
#define RTB_OFFLINE_NOISE_FLOOR_H

#include <vector>

#include "diagnose/extended_fit.h"

namespace rtb {

// Robust white-noise standard deviation of uniformly sampled values.
double white_noise_sigma(const std::vector<double> &s);
// Band within which a displacement record x is at rest: 5 robust sigma of its
// noise, at least 1e-3 of `scale` (its reach) for a clean sensor. A 0.1% band
// alone ended every at-rest prefix at the first noisy sample of refgen's
// 0.2-0.5% noise.
double rest_band(const std::vector<double> &x, double scale);
// Below this lag-1 correlation the noise is taken as white.
constexpr double kWhiteBelow = 0.2;
// The lag-1 correlation a of the noise in uniformly sampled values, fitted
// (0 to 0.8; see above).
double noise_correlation(const std::vector<double> &s);
// Robust standard deviation of the noise in uniformly sampled values whose
// noise has correlation a^|k| (white below kWhiteBelow).
double noise_sigma(const std::vector<double> &s, double a);

struct NoiseFloor {
  std::vector<double> sigma_fit, sigma_holdout;  // per record [force]
  double error_fit = 0.0, error_holdout = 0.0;   // eq. (27) floor of each set
  double correlation = 0.0;  // the noise's lag-1 correlation, median of the records (0: white)
};

// The floor of model m's residual on each set (holdout may be empty).
// recorded_x: each record's displacement as recorded, before stage 0's
// filter, fit records then held-out ones (empty: the records' own).
NoiseFloor estimate_noise_floor(const ExtModel &m, const std::vector<Record> &fit,
                                const std::vector<Record> &holdout, const MisfitOptions &opt,
                                const std::vector<std::vector<double>> &recorded_x = {});

}  // namespace rtb

#endif
