// synthetic_records.cpp -- see synthetic_records.h.
#include "synth/synthetic_records.h"

#include "rtb_offline.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>

namespace rtb {

namespace {

double input_at(const InputSpec &in, double t) {
  const double A = in.amplitude, f = in.frequency;
  switch (in.kind) {
    case InputKind::Triangle: return A * (2.0 / M_PI) * std::asin(std::sin(2 * M_PI * f * t));
    case InputKind::Sine: return A * std::sin(2 * M_PI * f * t);
    case InputKind::Step: {
      const double u = (t - in.step_at) / in.rise;
      return A * std::min(1.0, std::max(0.0, u));
    }
    case InputKind::MultiSine:
      // All components start at zero, like the other inputs (a record that
      // starts away from rest would be ramped in by the fitting tools).
      return A * (0.5 * std::sin(2 * M_PI * f * t) + 0.3 * std::sin(2 * M_PI * 2.7 * f * t) +
                  0.2 * std::sin(2 * M_PI * 7.3 * f * t));
  }
  return 0.0;
}
// d2x/dt2 of the input, exact: 0 on the triangle's and the step's straight
// pieces, and at their corners too (a delta there, of no width at a sample).
double input_accel(const InputSpec &in, double t) {
  const double A = in.amplitude, w = 2 * M_PI * in.frequency;
  switch (in.kind) {
    case InputKind::Triangle:
    case InputKind::Step: return 0.0;
    case InputKind::Sine: return -A * w * w * std::sin(w * t);
    case InputKind::MultiSine:
      return -A * (0.5 * w * w * std::sin(w * t) + 0.3 * std::pow(2.7 * w, 2) * std::sin(2.7 * w * t) +
                   0.2 * std::pow(7.3 * w, 2) * std::sin(7.3 * w * t));
  }
  return 0.0;
}
}  // namespace

std::vector<double> input_displacement(const InputSpec &in, std::vector<double> &t) {
  std::vector<double> x;
  const long n = (long)std::floor(in.duration / in.dt + 0.5);
  t.clear();
  for (long i = 0; i <= n; ++i) {
    t.push_back(i * in.dt);
    x.push_back(input_at(in, i * in.dt));
  }
  return x;
}

Record synthesize(const InputSpec &in, const TruthSpec &truth, const std::string &name) {
  Record rec;
  rec.path = name;
  rec.units = "time=s displacement=mm force=N (synthetic)";
  rec.x = input_displacement(in, rec.t);
  // Fine-step reference: the element integrated at dt / oversample. Its
  // load-path mass is the exact m x''(t) instead of the element's estimate:
  // at an ideal input corner any estimate from samples is a spike one fine
  // step wide, which the record's samples catch at 10x its coarse height
  // or miss (the truth's own spikes that the fits then chased).
  const int os = std::max(1, truth.oversample);
  const double h = in.dt / os;
  rtb_params pe = truth.p;
  pe.mass = 0.0;
  rtb_state s;
  if (rtb_state_init(&s, &pe, 0.0) != RTB_OK) throw std::runtime_error("synthesize: bad params");
  rtb_settings set;  // the truth at the fits' tolerance: with oversample 1, the fitted discrete map
  rtb_settings_default(&set);
  set.tol = kFitTol;
  std::vector<double> tf{0.0}, Ff{s.force};
  const size_t n = rec.t.size();
  for (size_t i = 1; i < n; ++i)
    for (int k = 1; k <= os; ++k) {
      const double t = rec.t[i - 1] + k * h;
      double F;
      if (rtb_step(&s, &pe, &set, input_at(in, t), h, &F) < 0)
        throw std::runtime_error("synthesize: stepper error");
      tf.push_back(t);
      Ff.push_back(F + truth.p.mass * input_accel(in, t));
    }
  // Delay: the force channel lags (linear interpolation on the fine grid).
  std::mt19937_64 rng(truth.seed);
  std::normal_distribution<double> nd(0.0, 1.0);
  rec.F.resize(n);
  for (size_t i = 0; i < n; ++i) {
    const double u = rec.t[i] - truth.delay;
    double F;
    if (u <= 0.0) F = Ff[0];
    else {
      const size_t k = std::min(tf.size() - 2, (size_t)(u / h));
      const double a = (u - tf[k]) / h;
      F = (1 - a) * Ff[k] + a * Ff[k + 1];
    }
    rec.F[i] = F + truth.offset;
  }
  double fmax = 0.0;
  for (double F : rec.F) fmax = std::max(fmax, std::fabs(F));
  for (double &F : rec.F) F += truth.noise * fmax * nd(rng);
  return rec;
}

Scenario hidden_effect_scenario(const std::string &effect, unsigned seed, double noise,
                                double duration) {
  std::mt19937_64 rng(seed * 7919u + 17u);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  auto logu = [&](double lo, double hi) { return lo * std::pow(hi / lo, U(rng)); };
  Scenario sc;
  sc.effect = effect;
  rtb_params &p = sc.truth.p;
  rtb_params_default(&p, RTB_MODEL_RT);
  p.K0 = logu(300, 2000);
  p.Kpa = logu(300, 2000);
  p.Kr = logu(1000, 8000);
  p.C0 = logu(10, 80);
  p.alpha = 0.1 + 0.3 * U(rng);
  const double A = 1.0;  // mm
  // Size of the elastic force at the amplitude, for effect sizing.
  const double Fel = (p.K0 + 1.0 / (1.0 / p.Kpa + p.cells / p.Kr)) * A;
  if (effect == "cubic_stiffness") p.k3 = (U(rng) < 0.5 ? 1 : -0.6) * 0.25 * Fel / (A * A * A);
  else if (effect == "asymmetry") p.k_asym = (U(rng) < 0.5 ? 1 : -1) * 0.25 * p.K0;
  else if (effect == "maxwell") { p.maxwell_k = 0.4 * Fel / A; p.maxwell_tau = logu(0.2, 1.0); }
  else if (effect == "viscous") p.viscous_c = 0.1 * Fel / (2 * 3.14159 * 3.0 * A);
  else if (effect == "backlash") p.backlash = 0.05 * A;
  else if (effect == "mullins") p.mullins = 0.3;
  else if (effect == "delay") sc.truth.delay = 0.004;
  else if (effect == "inertia") p.mass = 0.15 * Fel / (A * std::pow(2 * 3.14159 * 3.0, 2));
  else if (effect == "offset") sc.truth.offset = 0.05 * Fel;
  else if (effect == "softening") { p.sat_force = 0.3 * Fel; p.sat_disp = logu(0.1, 0.3) * A; }
  else if (effect == "backlash_held") { p.backlash = 0.05 * A; p.backlash_held = 1; }
  else if (effect == "slack") p.slack = 1;
  else if (effect == "relaxation_spectrum") {
    p.spec_k = 0.5 * Fel / A;
    p.spec_exp = 0.2 + 0.3 * U(rng);
    p.spec_tau_min = 3e-3;
    p.spec_tau_max = 10.0;
  } else if (effect == "friction_asymmetry") p.fric_asym = (U(rng) < 0.5 ? 1 : -1) * 0.4;
  else if (effect != "none") throw std::invalid_argument("unknown effect " + effect);
  sc.truth.noise = noise;
  const double T = duration;
  InputSpec tri{InputKind::Triangle, A, 0.25, T};
  InputSpec s1{InputKind::Sine, 0.6 * A, 1.0, T};
  InputSpec s2{InputKind::Sine, 0.3 * A, 3.0, T};
  InputSpec step{InputKind::Step, 0.8 * A, 0.0, T};
  InputSpec ms{InputKind::MultiSine, A, 0.5, T};
  unsigned k = seed * 10;
  auto synth = [&](const InputSpec &in, const char *name) {
    TruthSpec t = sc.truth;
    t.seed = ++k;
    return synthesize(in, t, std::string(name) + "_" + effect);
  };
  sc.fit = {synth(tri, "triangle"), synth(s1, "sine1Hz"), synth(s2, "sine3Hz")};
  sc.holdout = {synth(step, "step"), synth(ms, "multisine")};
  return sc;
}

}  // namespace rtb
