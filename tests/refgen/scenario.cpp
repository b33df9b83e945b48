// scenario.cpp -- what a seed decides: the specimen's RT parameters, the
// rig's conventions (servo, sample rate, noise, CSV columns) and the record
// set a test engineer would run. The base draws do not depend on the
// effects, so "none" and an effect with the same seed share the specimen;
// each effect draws its size from its own stream.
#include <cmath>
#include <cstdint>
#include <stdexcept>

#include "effects.h"

namespace refgen {
namespace {

std::uint64_t hash(const std::string &s) {  // FNV-1a
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char ch : s) h = (h ^ ch) * 1099511628211ull;
  return h;
}

// Scales a tone record so that its largest |value| is `peak`.
void normalize(Command &c, double peak) {
  double m = 0.0;
  for (double t = 0.0; t <= c.duration; t += 1e-3) m = std::fmax(m, std::fabs(c.value(t)));
  for (Tone &k : c.tones) k.amp *= peak / m;
  c.amp = peak;  // reported only
}

Command tone_record(Kind kind, double duration, bool tension) {
  Command c;
  c.kind = kind;
  c.duration = duration;
  c.tension = tension;
  return c;
}

void add_records(Scenario &sc, Rng &rng, double T, bool tension) {
  const double A = sc.amplitude;
  auto add = [&](const std::string &name, bool holdout, const Command &c) {
    sc.records.push_back({name, holdout, c});
  };
  Command c = tone_record(Kind::triangle, T, tension);  // quasi-static loops
  c.amp = A;
  c.hz = std::fmax(rng.uniform(0.2, 0.3), 1.0 / T);
  add("fit_triangle", false, c);
  c = tone_record(Kind::sine, T, tension);
  c.amp = rng.uniform(0.6, 0.8) * A;
  c.hz = 1.0;
  add("fit_sine1Hz", false, c);
  c.amp = rng.uniform(0.3, 0.5) * A;
  c.hz = 5.0;
  add("fit_sine5Hz", false, c);
  c = tone_record(Kind::step, T, tension);  // ramp, hold (relaxation), back, hold
  c.amp = (tension ? 1.0 : rng.sign()) * rng.uniform(0.7, 0.9) * A;
  c.t_up = 0.3;
  c.ramp_time = rng.uniform(0.05, 0.15);
  c.t_down = 0.55 * T;
  add("fit_step", false, c);
  c = tone_record(Kind::multisine, T, tension);
  const double f0 = rng.uniform(0.4, 0.8), mult[4] = {1.0, 2.3, 4.7, 7.9}, w[4] = {0.5, 0.3, 0.2, 0.12};
  for (int i = 0; i < 4; ++i) c.tones.push_back({w[i], f0 * mult[i], rng.uniform(0.0, 6.2832)});
  normalize(c, A * (tension ? 2.0 : 1.0));
  add("fit_multisine", false, c);
  // Held out: a small high-frequency sine and an earthquake-like record.
  c = tone_record(Kind::sine, T, tension);
  c.amp = rng.uniform(0.1, 0.2) * A;
  c.hz = rng.uniform(15.0, 30.0);
  add("holdout_sine", true, c);
  c = tone_record(Kind::random, T, tension);
  c.t_strong = 0.15 * T;
  c.t_decay = 0.6 * T;
  for (int i = 0; i < 40; ++i) {
    const double f = rng.log_uniform(0.3, 12.0);
    c.tones.push_back({1.0 / std::sqrt(f), f, rng.uniform(0.0, 6.2832)});
  }
  normalize(c, rng.uniform(0.7, 1.0) * A * (tension ? 2.0 : 1.0));
  add("holdout_random", true, c);
}

}  // namespace

Scenario make_scenario(const std::vector<std::string> &effects, unsigned seed, double duration) {
  if (!(duration >= 1.0)) throw std::invalid_argument("duration must be at least 1 s");
  Rng rng(seed * 1000003ull + 11ull);
  Scenario sc;
  sc.effects = effects;
  sc.seed = seed;
  Specimen &s = sc.specimen;
  s.K0 = rng.uniform(500, 1500);
  s.Kpa = rng.uniform(500, 1500);
  s.Kr = rng.uniform(2000, 6000);
  s.C0 = rng.uniform(20, 60);
  s.alpha = rng.uniform(0.15, 0.35);
  s.N = rng.integer(10, 20);
  Chain &c = sc.chain;
  c.servo_order = rng.uniform() < 0.5 ? 1 : 2;
  c.servo_hz = rng.uniform(20.0, 60.0);
  c.servo_zeta = rng.uniform(0.6, 0.9);
  const double u = rng.uniform();
  c.dt = u < 0.7 ? 1e-3 : u < 0.85 ? 2e-3 : 5e-4;
  c.substeps = c.dt > 1e-3 ? 20 : c.dt < 1e-3 ? 5 : 10;  // fine step 0.1 ms
  c.disp_noise = rng.uniform(0.002, 0.005);
  c.force_noise = 0.005;
  sc.amplitude = rng.uniform(0.8, 1.5);
  sc.column_style = rng.integer(0, 4);
  bool tension = false;
  for (const std::string &e : effects) tension = tension || e == "slack";
  add_records(sc, rng, duration, tension);
  for (const std::string &e : effects) {
    Rng er(seed ^ hash(e));
    apply_effect(sc, e, er);
  }
  check_combination(sc);
  return sc;
}

Samples run_scenario_record(const Scenario &sc, size_t i) {
  // Every force law scales with the stiffness; the states, which the laws
  // balance, do not move.
  Specimen s = sc.specimen;
  const double k = sc.records.at(i).stiffness;
  for (double *f : {&s.K0, &s.Kpa, &s.Kr, &s.C0, &s.cubic, &s.asym, &s.soft_k, &s.quad,
                    &s.quintic, &s.viscous})
    *f *= k;
  for (Branch &b : s.branches) b.k *= k;
  Chain chain = sc.chain;
  chain.seed = sc.seed * 100ull + i;  // a noise stream per record
  return run_record(s, sc.records[i].cmd, chain);
}

}  // namespace refgen
