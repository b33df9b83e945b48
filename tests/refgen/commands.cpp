// commands.cpp -- the commanded actuator signals of the record kinds a test
// engineer runs: slow triangle, sines, ramp-and-hold (relaxation),
// multi-sine and an earthquake-like random record. Every one starts at rest
// at x = 0. `tension` gives the one-sided form (0 .. 2 amp) used for
// specimens that cannot push.
#include <cmath>

#include "refgen.h"

namespace refgen {
namespace {

constexpr double kTwoPi = 6.283185307179586;

// Triangle wave of unit amplitude and period 1 in phase s, 0 at s = 0 rising.
double triangle(double s) {
  const double f = s + 0.75 - std::floor(s + 0.75);
  return 4.0 * std::fabs(f - 0.5) - 1.0;
}
double triangle_slope(double s) {
  const double f = s + 0.75 - std::floor(s + 0.75);
  return f >= 0.5 ? 4.0 : -4.0;
}

// Ramp from 0 to 1 between a and a + w (linear), and its slope.
double ramp(double t, double a, double w) { return t <= a ? 0.0 : t >= a + w ? 1.0 : (t - a) / w; }
double ramp_slope(double t, double a, double w) { return t > a && t < a + w ? 1.0 / w : 0.0; }

// Envelope of multi-sine (0.5 s smooth fade-in) and random records (smooth
// build-up to t_strong, Gaussian decay after t_decay); C1 everywhere.
double envelope(const Command &c, double t, double *slope) {
  const double rise = c.kind == Kind::random ? c.t_strong : 0.5;
  double e = 1.0, de = 0.0;
  if (t < rise) {
    const double u = t / rise;
    e = u * u * (3.0 - 2.0 * u);
    de = 6.0 * u * (1.0 - u) / rise;
  } else if (c.kind == Kind::random && t > c.t_decay) {
    const double w = 0.35 * (c.duration - c.t_decay), u = (t - c.t_decay) / w;
    e = std::exp(-u * u);
    de = -2.0 * u / w * e;
  }
  *slope = de;
  return e;
}

// Sum of tones: sin for two-sided records, 1 - cos for one-sided ones.
double tone_sum(const Command &c, double t, double *slope) {
  double v = 0.0, dv = 0.0;
  for (const Tone &k : c.tones) {
    const double w = kTwoPi * k.hz, p = w * t + k.phase;
    v += c.tension ? k.amp * (1.0 - std::cos(p)) : k.amp * std::sin(p);
    dv += c.tension ? k.amp * w * std::sin(p) : k.amp * w * std::cos(p);
  }
  *slope = dv;
  return v;
}

}  // namespace

double Command::value(double t) const {
  const double w = kTwoPi * hz;
  switch (kind) {
    case Kind::triangle:
      return tension ? amp * (1.0 + triangle(hz * t - 0.25)) : amp * triangle(hz * t);
    case Kind::sine:
      return tension ? amp * (1.0 - std::cos(w * t)) : amp * std::sin(w * t);
    case Kind::step:
      return amp * (ramp(t, t_up, ramp_time) - ramp(t, t_down, ramp_time));
    case Kind::multisine:
    case Kind::random: {
      double de = 0.0, ds = 0.0;
      return envelope(*this, t, &de) * tone_sum(*this, t, &ds);
    }
  }
  return 0.0;
}

double Command::slope(double t) const {
  const double w = kTwoPi * hz;
  switch (kind) {
    case Kind::triangle:
      return amp * hz * triangle_slope(tension ? hz * t - 0.25 : hz * t);
    case Kind::sine:
      return tension ? amp * w * std::sin(w * t) : amp * w * std::cos(w * t);
    case Kind::step:
      return amp * (ramp_slope(t, t_up, ramp_time) - ramp_slope(t, t_down, ramp_time));
    case Kind::multisine:
    case Kind::random: {
      double de = 0.0, ds = 0.0;
      const double e = envelope(*this, t, &de), v = tone_sum(*this, t, &ds);
      return de * v + e * ds;
    }
  }
  return 0.0;
}

}  // namespace refgen
