// displacement_noise.cpp -- see displacement_noise.h.
#include "diagnose/displacement_noise.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include "diagnose/noise_floor.h"
#include "preprocess/preprocess.h"

namespace rtb {

namespace {
// The grid step when the grid is uniform to 1%, else 0.
double uniform_step(const Record &r) {
  const double h = (r.t.back() - r.t.front()) / (double)(r.t.size() - 1);
  for (size_t i = 1; i < r.t.size(); ++i)
    if (std::fabs(r.t[i] - r.t[i - 1] - h) > 0.01 * h) return 0.0;
  return h;
}
// Variance of x - lowpass(x, fc): what a cut-off at fc removes.
double removed_variance(const std::vector<double> &x, double dt, double fc) {
  const std::vector<double> lp = lowpass_zero_phase(x, dt, fc, 4);
  double mean = 0.0, sq = 0.0;
  for (size_t i = 0; i < x.size(); ++i) mean += x[i] - lp[i];
  mean /= (double)x.size();
  for (size_t i = 0; i < x.size(); ++i) sq += (x[i] - lp[i] - mean) * (x[i] - lp[i] - mean);
  return sq / (double)x.size();
}

// The filter's weight on the noise, tr(S C)/(n sigma^2) for the linear
// smoother S and noise of covariance C = sigma^2 a^|i-j|: the zero-phase
// response s_k to a unit impulse far from both ends, summed with weights
// a^|k|. White noise (a = 0) gives s_0 = tr(S)/n, the filter's own weight
// on a sample; band-limited noise gives more (its low-frequency part passes
// a cut-off above the noise band whole).
double noise_weight(double dt, double fc, double a) {
  const size_t half = (size_t)std::ceil(20.0 / (fc * dt)) + 16;
  std::vector<double> d(2 * half + 1, 0.0);
  d[half] = 1.0;
  const std::vector<double> s = lowpass_zero_phase(d, dt, fc, 4);
  double w = s[half], ak = 1.0;
  if (a > 0.0)
    for (size_t k = 1; k <= half; ++k) {
      ak *= a;
      w += ak * (s[half - k] + s[half + k]);
    }
  return w;
}

// The record's bandwidth, by Stein's unbiased risk estimate (SURE) of the
// filtered displacement's mean-square error against the noise-free one:
//   E|lp(x) - x_true|^2 = |x - lp(x)|^2 - sigma^2 (1 - 2 tr(S C)/(n sigma^2)),
// C the noise's covariance, of correlation a^|k| (noise_weight; white: tr(S)/n),
// over cut-offs halved from fs/5 down to fs/200: the noise passed (sigma^2
// tr(S)/n) against the signal the filter takes. Of the cut-offs within one
// standard error of the least risk (sigma^2 sqrt(2/n), the estimate's own
// scatter on white noise) the lowest is taken: where the displacement does
// not decide, the smoother input is what the element's derivatives
// (inertia, a dashpot) and its memory (Mullins, a clearance) prefer; a
// fixed fs/5 let so much noise into the acceleration that a fitted mass came
// out 12x too small. The rule before (halve while what goes is at most 1.25x
// the noise alone) took up to half a noise sigma of signal: blindgen
// relaxation_spectrum_s21 (500 Hz, sigma_x 19 um, a 9.4 Hz random held-out
// record) was cut at 12.5 Hz, 11 um rms off the true displacement, where
// 25 Hz leaves 6 um; the force that cost (~30 N against a 36 N noise) held
// the spectrum's fit at 1.28x the force noise floor (1.12x now, named).
double record_cutoff(const Record &r, double dt, double sigma, double a) {
  const double fs = 1.0 / dt;
  std::vector<std::pair<double, double>> risk;  // (fc, estimated error), fc falling
  double least = INFINITY;
  for (double fc = 0.2 * fs; fc >= fs / 200.0; fc /= 2.0) {
    risk.emplace_back(fc, removed_variance(r.x, dt, fc) -
                              sigma * sigma * (1.0 - 2.0 * noise_weight(dt, fc, a)));
    least = std::min(least, risk.back().second);
  }
  const double se = sigma * sigma * std::sqrt(2.0 / (double)r.x.size());
  double lowest = 0.0;  // the last within least + se: the lowest, since fc falls
  for (const auto &fr : risk)
    if (fr.second <= least + se) lowest = fr.first;
  return lowest;
}
}  // namespace

DisplacementDenoise denoise_displacement(std::vector<Record> &recs, double threshold) {
  DisplacementDenoise d;
  double Fmax = 0.0, Xmax = 0.0, dt = 0.0;
  for (const Record &r : recs) {
    for (double v : r.F) Fmax = std::max(Fmax, std::fabs(v));
    for (double v : r.x) Xmax = std::max(Xmax, std::fabs(v));
    d.sigma_x = std::max(d.sigma_x, white_noise_sigma(r.x));
    d.sigma_F = std::max(d.sigma_F, white_noise_sigma(r.F));
    const double h = uniform_step(r);
    if (!(h > 0.0)) return d;  // a non-uniform grid: leave every record as it is
    dt = std::max(dt, h);
  }
  if (!(Xmax > 0.0) || !(d.sigma_F > 0.0)) return d;
  d.noise_ratio = 2.0 * Fmax / Xmax * d.sigma_x / d.sigma_F;
  if (d.noise_ratio < threshold) return d;
  // Band-limited noise (an anti-alias filter, a conditioning amplifier):
  // the chain's correlation, the median over the records as for the force
  // (noise_floor.h). Its level is then the marginal one, of which the white
  // estimate sees 0.4-0.7, and SURE weighs the noise each cut-off passes
  // with it: taken as white, refgen colored_noise+inertia_s64 (a 52 Hz
  // corner at 1 kHz) kept fs/5 on every record, and the slow fit records'
  // acceleration noise shrank the fitted mass 7x (0.0016 of 0.0116).
  std::vector<double> corr;
  for (const Record &r : recs) corr.push_back(noise_correlation(r.x));
  std::nth_element(corr.begin(), corr.begin() + (long)corr.size() / 2, corr.end());
  const double a = corr[corr.size() / 2] < kWhiteBelow ? 0.0 : corr[corr.size() / 2];
  d.correlation = a;
  for (Record &r : recs) {
    const double fc = record_cutoff(r, uniform_step(r), noise_sigma(r.x, a), a);
    d.record_cutoff_hz.push_back(fc);
    d.cutoff_hz = std::max(d.cutoff_hz, fc);
    r.x = lowpass_zero_phase(r.x, uniform_step(r), fc, 4);
  }
  return d;
}

}  // namespace rtb
