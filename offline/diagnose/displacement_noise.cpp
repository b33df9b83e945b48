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
  d.cutoff_hz = 0.2 / dt;
  for (Record &r : recs) r.x = lowpass_zero_phase(r.x, uniform_step(r), d.cutoff_hz, 4);
  return d;
}

}  // namespace rtb
