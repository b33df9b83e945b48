// measurement.cpp -- the test rig around the specimen: the servo low-pass
// between command and actuator, the fine-step integration with step halving
// as a fallback, and the recording chain (force-channel delay, offset, mains
// hum, noise on both channels, sampling).
#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "rng.h"
#include "specimen_model.h"

namespace refgen {
namespace {

constexpr double kTwoPi = 6.283185307179586;

// Actuator = command through a 1st-order (x' = w (u - x)) or 2nd-order
// (x'' = w^2 (u - x) - 2 zeta w x') low-pass, w = 2 pi servo_hz.
struct Servo {
  double t = 0.0, x = 0.0, v = 0.0;
};

void servo_rates(const Chain &c, const Command &cmd, double t, double x, double v, double *dx,
                 double *dv) {
  const double w = kTwoPi * c.servo_hz, u = c.preload + cmd.value(t);
  if (c.servo_order == 1) {
    *dx = w * (u - x);
    *dv = 0.0;
  } else {
    *dx = v;
    *dv = w * w * (u - x) - 2.0 * c.servo_zeta * w * v;
  }
}

// Classical RK4 to t1 with w h <= 0.02 (the filter is not stiff).
void advance(Servo &s, const Chain &c, const Command &cmd, double t1) {
  const double span = t1 - s.t, w = kTwoPi * c.servo_hz;
  const int n = std::max(1, (int)std::ceil(span * w / 0.02));
  const double h = span / n;
  for (int i = 0; i < n; ++i) {
    const double t = s.t + i * h;
    double k1x, k1v, k2x, k2v, k3x, k3v, k4x, k4v;
    servo_rates(c, cmd, t, s.x, s.v, &k1x, &k1v);
    servo_rates(c, cmd, t + h / 2, s.x + h / 2 * k1x, s.v + h / 2 * k1v, &k2x, &k2v);
    servo_rates(c, cmd, t + h / 2, s.x + h / 2 * k2x, s.v + h / 2 * k2v, &k3x, &k3v);
    servo_rates(c, cmd, t + h, s.x + h * k3x, s.v + h * k3v, &k4x, &k4v);
    s.x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
    s.v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
  }
  s.t = t1;
}

Drive drive_of(const Servo &s, const Chain &c, const Command &cmd) {
  const double w = kTwoPi * c.servo_hz, u = c.preload + cmd.value(s.t);
  Drive d;
  d.t = s.t;
  d.x = s.x;
  if (c.servo_order == 1) {
    d.v = w * (u - s.x);
    d.a = w * (cmd.slope(s.t) - d.v);
  } else {
    d.v = s.v;
    d.a = w * w * (u - s.x) - 2.0 * c.servo_zeta * w * s.v;
  }
  return d;
}

// One fine step; where Newton fails (a clearance closing inside the step),
// two half steps, down to 1/2^16 of the step.
void fine_step(const Specimen &s, const Chain &c, const Command &cmd, SpecimenState &st,
               Servo &sv, double t, double h, int depth) {
  const Servo saved = sv;
  Drive d[2];
  advance(sv, c, cmd, t + h / 3.0);
  d[0] = drive_of(sv, c, cmd);
  advance(sv, c, cmd, t + h);
  d[1] = drive_of(sv, c, cmd);
  if (radau_step(s, st, t, h, d)) return;
  if (depth >= 16)
    throw std::runtime_error("refgen: Newton did not converge at t = " + std::to_string(t) +
                             " s even with step " + std::to_string(h) + " s");
  sv = saved;
  fine_step(s, c, cmd, st, sv, t, h / 2, depth + 1);
  fine_step(s, c, cmd, st, sv, t + h / 2, h / 2, depth + 1);
}

double interpolate(const std::vector<double> &F, double pos) {
  if (pos <= 0.0) return F.front();
  const size_t i = (size_t)pos;
  if (i + 1 >= F.size()) return F.back();
  const double w = pos - (double)i;
  return (1.0 - w) * F[i] + w * F[i + 1];
}

}  // namespace

Samples run_record(const Specimen &s, const Command &cmd, const Chain &c) {
  const size_t n = (size_t)std::floor(cmd.duration / c.dt + 0.5) + 1;
  const size_t m = (size_t)std::max(1, c.substeps);
  const double h = c.dt / (double)m;
  // Force on the load cell and actuator position on the fine grid.
  std::vector<double> F(1 + (n - 1) * m), x(F.size(), c.preload);
  SpecimenState st = c.preload != 0.0 ? relaxed_state(s, c.preload) : rest_state(s);
  Servo sv;
  sv.x = c.preload;
  F[0] = specimen_force(s, st, drive_of(sv, c, cmd));
  for (size_t j = 0; j + 1 < F.size(); ++j) {
    fine_step(s, c, cmd, st, sv, (double)j * h, h, 0);
    sv.t = (double)(j + 1) * h;  // no drift of the clock from the halvings
    F[j + 1] = specimen_force(s, st, drive_of(sv, c, cmd));
    x[j + 1] = sv.x;
  }
  if (c.force_lowpass_hz > 0.0) {  // the amplifier's first-order low-pass, exact for a held input
    const double a = std::exp(-kTwoPi * c.force_lowpass_hz * h);
    for (size_t j = 1; j < F.size(); ++j) F[j] = a * F[j - 1] + (1.0 - a) * F[j];
  }
  Samples r;
  r.t.resize(n);
  r.x_true.resize(n);
  r.F_clean.resize(n);
  double Fmax = 0.0, xmax = 0.0;
  for (size_t k = 0; k < n; ++k) {
    const double t = (double)k * c.dt;
    r.t[k] = t;
    r.x_true[k] = c.disp_delay > 0.0 ? interpolate(x, (t - c.disp_delay) / h) : x[k * m];
    const double Fk = interpolate(F, (t - c.delay) / h);  // the force channel lags
    Fmax = std::fmax(Fmax, std::fabs(Fk));
    xmax = std::fmax(xmax, std::fabs(r.x_true[k]));
    const double p = kTwoPi * 50.0 * t + c.hum_phase;
    const double zero = c.offset + c.zero_drift * t / cmd.duration;
    r.F_clean[k] = c.force_sign * (Fk + zero + c.hum * (std::sin(p) + 0.3 * std::sin(3.0 * p)));
  }
  Rng rng(c.seed);
  r.x.resize(n);
  r.F.resize(n);
  // Band-limited noise: an AR(1) sequence of unit variance, whose spectrum
  // is a first-order low-pass at noise_hz (white when 0).
  const double a = c.noise_hz > 0.0 ? std::exp(-kTwoPi * c.noise_hz * c.dt) : 0.0;
  const double b = std::sqrt(1.0 - a * a);
  double ex = rng.normal(), eF = rng.normal();
  for (size_t k = 0; k < n; ++k) {
    if (k > 0) ex = a * ex + b * rng.normal(), eF = a * eF + b * rng.normal();
    r.x[k] = r.x_true[k] + c.disp_noise * xmax * ex;
    r.F[k] = r.F_clean[k] + c.force_noise * Fmax * eF;
  }
  if (c.spikes > 0.0)  // isolated glitches of either sign, on the recorded force only
    for (size_t k = 0; k < n; ++k)
      if (rng.uniform() < c.spike_rate) r.F[k] += (rng.uniform() < 0.5 ? -1.0 : 1.0) * c.spikes * rng.uniform(0.5, 1.0);
  if (c.clip > 0.0)  // a saturating load cell (or its amplifier) clips what it records
    for (size_t k = 0; k < n; ++k) {
      r.F_clean[k] = std::fmax(-c.clip, std::fmin(c.clip, r.F_clean[k]));
      r.F[k] = std::fmax(-c.clip, std::fmin(c.clip, r.F[k]));
    }
  return r;
}

double noise_floor(const std::vector<const Samples *> &recs) {
  double J = 0.0, J0 = 0.0;
  for (const Samples *r : recs)
    for (size_t k = 0; k < r->F.size(); ++k) {
      J += (r->F_clean[k] - r->F[k]) * (r->F_clean[k] - r->F[k]);
      J0 += r->F[k] * r->F[k];
    }
  return J0 > 0.0 ? std::sqrt(J / J0) : 0.0;
}

}  // namespace refgen
