// displacement_noise.cpp -- see displacement_noise.h.
#include "diagnose/displacement_noise.h"

#include <algorithm>
#include <cmath>

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

// The record's bandwidth: halve the cut-off from fs/5 while what it removes
// is still white noise (at most 1.25x the sigma^2 (1 - 2 fc/fs) noise alone
// would lose), down to fs/200. The servo of a displacement-controlled rig
// passes nothing above a few tens of Hz; a fixed fs/5 let so much noise
// into the acceleration that a fitted mass came out 12x too small.
double record_cutoff(const Record &r, double dt, double sigma) {
  const double fs = 1.0 / dt;
  double fc = 0.2 * fs;
  while (fc / 2.0 >= fs / 200.0) {
    const double next = fc / 2.0;
    if (removed_variance(r.x, dt, next) > 1.25 * sigma * sigma * (1.0 - 2.0 * next / fs)) break;
    fc = next;
  }
  return fc;
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
  for (Record &r : recs) {
    const double fc = record_cutoff(r, uniform_step(r), white_noise_sigma(r.x));
    d.record_cutoff_hz.push_back(fc);
    d.cutoff_hz = std::max(d.cutoff_hz, fc);
    r.x = lowpass_zero_phase(r.x, uniform_step(r), fc, 4);
  }
  return d;
}

}  // namespace rtb
