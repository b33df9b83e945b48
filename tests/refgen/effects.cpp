// effects.cpp -- the generator's own definitions and sizes of the effects a
// real specimen or rig adds to plain RT. Sizes are drawn per seed, relative
// to the reference amplitude A and the static stiffness Kst = F_static(A)/A,
// large enough to be clearly visible through 0.5% force noise, small enough
// to be plausible on a rig.
#include <cmath>
#include <stdexcept>

#include "effects.h"

namespace refgen {

const std::vector<std::string> &effect_names() {
  static const std::vector<std::string> names = {
      "none",     "cubic_stiffness", "asymmetry", "maxwell",  "viscous",
      "backlash", "backlash_held",   "mullins",   "delay",    "delay_lowpass", "inertia",
      "offset",   "softening",       "slack",     "relaxation_spectrum",
      "friction_asymmetry",          "hum",       "drift",     "clipping",  "spikes", "zero_drift",
      "temperature",
      // other definitions of the same words
      "asymmetry_quadratic", "softening_tanh", "mullins_erf", "stiffening_quintic",
      "delay_displacement",
      // a rig convention, not an effect: the records oscillate about a held preload
      "preload", "compression_positive", "colored_noise"};
  return names;
}

std::string expected_word(const std::string &effect) {
  if (effect == "backlash_held") return "backlash";
  if (effect == "delay_lowpass" || effect == "delay_displacement") return "delay";
  if (effect == "asymmetry_quadratic") return "asymmetry";
  if (effect == "softening_tanh") return "softening";
  if (effect == "mullins_erf") return "mullins";
  if (effect == "stiffening_quintic") return "cubic_stiffness";
  if (effect == "preload" || effect == "compression_positive" || effect == "colored_noise")
    return "none";
  if (effect == "hum" || effect == "drift" || effect == "clipping" || effect == "spikes" ||
      effect == "zero_drift" || effect == "temperature")
    return "unexplained";
  return effect;
}

namespace {

constexpr double kTwoPi = 6.283185307179586;

// Power-law-like (long-memory) relaxation: Maxwell branches two per decade
// from 10 ms to 100 s with weights ~ tau^-n, the Prony series of G(t) ~ t^-n
// on a log-uniform grid (over a 0.03-3 s window its log-log slope is about
// -(n + 0.05)).
void add_spectrum(Specimen &s, double k_total, double n) {
  std::vector<double> w;
  double sum = 0.0;
  for (int j = 0; j <= 8; ++j) {
    const double tau = 0.01 * std::pow(10.0, 0.5 * j);
    w.push_back(std::pow(tau, -n));
    sum += w.back();
    s.branches.push_back({0.0, tau});
  }
  const size_t first = s.branches.size() - w.size();
  for (size_t j = 0; j < w.size(); ++j) s.branches[first + j].k = k_total * w[j] / sum;
}

}  // namespace

void apply_effect(Scenario &sc, const std::string &e, Rng &rng) {
  Specimen &s = sc.specimen;
  Chain &c = sc.chain;
  const double A = sc.amplitude, Kst = static_force(s, 1.0), Fel = Kst * A;
  const double T = sc.records.empty() ? 8.0 : sc.records.front().cmd.duration;
  if (e == "none") return;
  if (e == "cubic_stiffness")  // mostly stiffening; softening cubics are smaller
    s.cubic = (rng.uniform() < 0.7 ? 1.0 : -0.5) * rng.uniform(0.15, 0.3) * Kst / (A * A);
  else if (e == "asymmetry") {
    s.asym = rng.sign() * rng.uniform(0.12, 0.25) * Kst;
    s.asym_width = 0.05 * A;
  }
  else if (e == "maxwell")
    s.branches.push_back({rng.uniform(0.3, 0.5) * Kst, rng.log_uniform(0.05, 0.5)});
  else if (e == "viscous")  // loss factor c w / Kst of 0.05-0.08 at 5 Hz
    s.viscous = rng.uniform(0.05, 0.08) * Kst / (kTwoPi * 5.0);
  else if (e == "inertia")  // m w^2 = 12-20% of Kst at 20 Hz (a fixture of 10-20 kg)
    s.mass = rng.uniform(0.12, 0.2) * Kst / std::pow(kTwoPi * 20.0, 2);
  else if (e == "backlash" || e == "backlash_held") {
    s.gap = e == "backlash" ? Gap::floating : Gap::held;
    s.half_gap = rng.uniform(0.02, 0.05) * A;
  }
  else if (e == "mullins")
    s.mullins = rng.uniform(0.2, 0.4);
  else if (e == "delay")
    c.delay = rng.uniform(0.002, 0.006);
  else if (e == "delay_lowpass")  // the other definition: a load-cell amplifier's bandwidth,
    c.force_lowpass_hz = 1.0 / (kTwoPi * rng.uniform(0.002, 0.006));  // group delay 2-6 ms
  else if (e == "delay_displacement")  // the other channel lags: the force leads by 2-6 ms
    c.disp_delay = rng.uniform(0.002, 0.006);
  else if (e == "offset")
    c.offset = rng.sign() * rng.uniform(0.02, 0.05) * Fel;
  else if (e == "softening") {
    s.soft_k = rng.uniform(0.3, 0.6) * Kst;
    s.soft_x = rng.uniform(0.15, 0.3) * A;
  }
  else if (e == "slack")
    s.slack = true;  // the records are one-sided (make_scenario)
  else if (e == "relaxation_spectrum")
    add_spectrum(s, rng.uniform(0.4, 0.8) * Kst, rng.uniform(0.2, 0.5));
  else if (e == "friction_asymmetry")
    s.c0_neg_ratio = std::pow(rng.uniform(1.2, 2.0), rng.sign());
  else if (e == "asymmetry_quadratic")  // tangent stiffness at +-A differs by 30-50% of Kst
    s.quad = rng.sign() * rng.uniform(0.08, 0.12) * Kst / A;
  else if (e == "stiffening_quintic")   // +12-25% of the elastic force at A
    s.quintic = rng.uniform(0.12, 0.25) * Kst / (A * A * A * A);
  else if (e == "softening_tanh") {
    s.soft_k = rng.uniform(0.3, 0.6) * Kst;
    s.soft_x = rng.uniform(0.15, 0.3) * A;
    s.soft_tanh = true;
  }
  else if (e == "mullins_erf") {
    s.mullins = rng.uniform(0.15, 0.3);
    s.mullins_erf = true;
  }
  else if (e == "preload")  // held at 0.5-1.5 A before the records start, either side
    c.preload = rng.sign() * rng.uniform(0.5, 1.5) * A;
  else if (e == "compression_positive")  // the load cell's sign convention, not an effect
    c.force_sign = -1.0;
  else if (e == "colored_noise")  // an anti-alias filter at 5-15% of the sample rate
    c.noise_hz = rng.uniform(0.05, 0.15) / c.dt;
  else if (e == "hum") {
    c.hum = rng.uniform(0.01, 0.02) * Fel;
    c.hum_phase = rng.uniform(0.0, kTwoPi);
  }
  else if (e == "drift")  // stiffness changes 4-8% linearly over each record
    s.drift_rate = rng.sign() * rng.uniform(0.04, 0.08) / T;
  else if (e == "temperature") {  // each test at its own temperature: forces 6-12% apart
    const double spread = rng.uniform(0.06, 0.12);
    for (RecordSpec &r : sc.records) r.stiffness = 1.0 + spread * rng.uniform(-1.0, 1.0);
  }
  else if (e == "zero_drift")  // the load cell's zero creeps (warming amplifier) by 2-5%
    c.zero_drift = rng.sign() * rng.uniform(0.02, 0.05) * Fel;
  else if (e == "clipping")  // the force channel saturates below the loops' peaks
    c.clip = rng.uniform(0.75, 0.9) * Fel;
  else if (e == "spikes") {  // one sample in 200-500 off by 5-15% of the elastic force
    c.spikes = rng.uniform(0.05, 0.15) * Fel;
    c.spike_rate = 1.0 / rng.uniform(200.0, 500.0);
  }
  else
    throw std::invalid_argument("unknown effect '" + e + "'");
}

void check_combination(const Scenario &sc) {
  const Specimen &s = sc.specimen;
  const bool floats = s.gap == Gap::floating || s.slack;
  if (floats && (!s.branches.empty() || s.viscous != 0.0))
    throw std::invalid_argument(
        "a floating end (backlash, slack) cannot be combined with rate-dependent branches "
        "(maxwell, relaxation_spectrum, viscous)");
  if (s.slack && sc.chain.preload != 0.0)
    throw std::invalid_argument("slack records are one-sided from 0: no preload");
  if (s.slack && s.gap != Gap::none)
    throw std::invalid_argument("slack and backlash cannot be combined");
  int gaps = 0;
  for (const std::string &e : sc.effects) gaps += e == "backlash" || e == "backlash_held";
  if (gaps > 1) throw std::invalid_argument("only one clearance per scenario");
}

}  // namespace refgen
