// candidates.cpp -- see candidates.h.
#include "diagnose/candidates.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <utility>

namespace rtb {

DataScales data_scales(const std::vector<Record> &recs) {
  DataScales s;
  s.Fmax = s.Xmax = s.Vmax = s.Amax = 0.0;
  double dts = 0.0;
  long ndt = 0;
  s.duration = 0.0;
  for (const Record &r : recs) {
    s.duration = std::max(s.duration, r.t.back() - r.t.front());
    for (size_t i = 0; i < r.t.size(); ++i) {
      s.Fmax = std::max(s.Fmax, std::fabs(r.F[i]));
      s.Xmax = std::max(s.Xmax, std::fabs(r.x[i]));
      if (i > 0) {
        const double h = r.t[i] - r.t[i - 1];
        dts += h;
        ++ndt;
        s.Vmax = std::max(s.Vmax, std::fabs(r.x[i] - r.x[i - 1]) / h);
      }
      if (i > 0 && i + 1 < r.t.size()) {
        const double h0 = r.t[i] - r.t[i - 1], h1 = r.t[i + 1] - r.t[i];
        const double a = 2.0 * ((r.x[i + 1] - r.x[i]) / h1 - (r.x[i] - r.x[i - 1]) / h0) / (h0 + h1);
        s.Amax = std::max(s.Amax, std::fabs(a));
      }
    }
  }
  auto pos = [](double v) { return v > 0.0 ? v : 1.0; };
  s.Fmax = pos(s.Fmax);
  s.Xmax = pos(s.Xmax);
  s.Vmax = pos(s.Vmax);
  s.Amax = pos(s.Amax);
  s.Ksec = s.Fmax / s.Xmax;
  s.dt = ndt ? dts / ndt : 1e-3;
  s.duration = pos(s.duration);
  s.memory = s.duration;
  return s;
}

void set_spectrum_range(rtb_params &p, const DataScales &s, double tau_min) {
  p.spec_tau_min = tau_min;
  p.spec_tau_max = std::max(p.spec_tau_min, s.memory);
  const double cap = p.spec_tau_min * std::pow(10.0, (RTB_MAX_BRANCHES - 1) / 2.0);
  p.spec_tau_max = std::min(p.spec_tau_max, cap);
}

namespace {
void set_held(rtb_params &p, const DataScales &) { p.backlash_held = 1; }
void set_slack(rtb_params &p, const DataScales &) { p.slack = 1; }
// Branch times from a few sample intervals to the longest record: the whole
// range the data can resolve, two branches per decade (bushing_force.h). The
// screen moves the fastest branch (spectrum_passes).
void set_spectrum(rtb_params &p, const DataScales &s) { set_spectrum_range(p, s, 3.0 * s.dt); }

// Shapes scanned by the screen, and the starts of its short fits.
void maxwell_tau_of_duration(rtb_params &p, const DataScales &s, double g) {
  p.maxwell_tau = std::max(g * s.duration, 5.0 * s.dt);
}
void sat_disp_of_stroke(rtb_params &p, const DataScales &s, double g) { p.sat_disp = g * s.Xmax; }
void spectrum_exponent(rtb_params &p, const DataScales &, double g) { p.spec_exp = g; }
void spectrum_fastest_branch(rtb_params &p, const DataScales &s, double g) {
  set_spectrum_range(p, s, g * s.dt);
}
void backlash_of_stroke(rtb_params &p, const DataScales &s, double g) { p.backlash = g * s.Xmax; }
void mullins_fraction(rtb_params &p, const DataScales &, double g) { p.mullins = g; }
void relax_width_of_stroke(rtb_params &p, const DataScales &s, double g) { p.relax_width = g * s.Xmax; }
// Ogden-Roxburgh's erf shape on the whole RT force, its width a third of the
// stroke: a loss that is nearly uniform below the prior max (blindgen
// mullins_s3: erf over 8% of the peak energy, w = 0.28 X).
void set_mullins_erf(rtb_params &p, const DataScales &s) {
  p.mullins_whole = 1;
  p.mullins_width = 0.3 * s.Xmax;
}

// The spectrum's shape: the exponent (from 3 sample intervals), then the
// fastest branch at that exponent (11 evaluations, not 28: the screen runs
// every round). Branches faster than the specimen's own fastest relaxation
// act, beyond the fit records' bandwidth, as a stiffness the held-out
// records contradict (refgen relaxation_spectrum_s3: from 3 sample
// intervals the joint fit gets 1.07% on the fit records and 2.14% held out,
// from 10 (the truth) 1.03% and 1.48%). The screen sees all records, the
// held-out kind too. With two branches per decade, fastest branches a
// half-decade apart (3, 10, 30, 100) put every branch at the same times,
// only the range's start moves; the grid also takes the two positions in
// between (x 1.8 and x 5.6 of a decade's start), so that a specimen's
// branches are within a sixth of a decade of the element's (refgen
// relaxation_spectrum_s5 at 500 Hz, branches from 5 sample intervals: from 3
// the spectrum gained 12% held out and the verdict was `unexplained`, from
// 5.6 it gains 17%).
std::vector<ShapePass> spectrum_passes() {
  return {{spectrum_exponent, {-0.3, 0.0, 0.3, 0.6}, 0.3},
          {spectrum_fastest_branch, {1.8, 5.6, 10.0, 18.0, 30.0, 56.0, 100.0}, 3.0}};
}

// A physical word: the extension parameters it frees.
Candidate word(const char *name, std::vector<ParamId> extra, Configure configure = nullptr,
               const char *variant = "") {
  Candidate c;
  c.name = name;
  c.extra = std::move(extra);
  c.configure = configure;
  c.variant = variant;
  return c;
}
// A measurement-chain artefact: a delay or an offset of the force channel.
Candidate artefact(const char *name, bool delay, bool offset) {
  Candidate c;
  c.name = name;
  c.physical = false;
  c.delay = delay;
  c.offset = offset;
  return c;
}
Candidate shape_scanned(Candidate c, std::vector<ShapePass> passes) {
  c.screen = ScreenMethod::shape_scan;
  c.passes = std::move(passes);
  return c;
}
Candidate short_fitted(Candidate c, ShapeSetter start_at, std::vector<double> starts) {
  c.screen = ScreenMethod::short_fit;
  c.start_at = start_at;
  c.starts = std::move(starts);
  return c;
}
}  // namespace

// Starting gaps of the clearance screens are fractions of the stroke: a
// clearance much wider than the first is a different basin (a friction device
// with a 10%-of-stroke play, e.g.); each start is its own screen job.
// Mullins is linear in mu, but a baseline fitted without it sits in another
// basin (on refgen's Mullins cases Kr 1676 against 4766, alpha 0.10 against
// 0.22): the score test at mu = 0 sees 1% of the misfit go, a joint fit from
// mu = 0.3 takes it to the floor (3.5% -> 1.26%).
const std::vector<Candidate> &candidate_vocabulary() {
  static const std::vector<Candidate> v = {
      word("cubic_stiffness", {P_k3}),
      word("asymmetry", {P_k_asym}),
      shape_scanned(word("maxwell", {P_maxwell_k, P_maxwell_tau}),
                    {{maxwell_tau_of_duration, {0.003, 0.01, 0.03, 0.1, 0.3, 1.0}, 0.1}}),
      word("viscous", {P_viscous_c}),
      short_fitted(word("backlash", {P_backlash}), backlash_of_stroke, {0.02, 0.1}),
      short_fitted(word("backlash", {P_backlash}, set_held, "held"), backlash_of_stroke, {0.03}),
      short_fitted(word("mullins", {P_mullins}), mullins_fraction, {0.3}),
      short_fitted(word("mullins", {P_mullins, P_mullins_width}, set_mullins_erf, "erf"),
                   mullins_fraction, {0.3}),
      artefact("delay", true, false),
      word("inertia", {P_mass}),
      artefact("offset", false, true),
      shape_scanned(word("softening", {P_sat_force, P_sat_disp}),
                    {{sat_disp_of_stroke, {0.03, 0.1, 0.3, 1.0}, 0.1}}),
      short_fitted(word("slack", {}, set_slack), nullptr, {}),
      shape_scanned(word("relaxation_spectrum", {P_spec_k, P_spec_exp}, set_spectrum),
                    spectrum_passes()),
      word("friction_asymmetry", {P_fric_asym}),
      short_fitted(word("stretch_relaxation", {P_relax_width}), relax_width_of_stroke, {0.5, 2.0}),
  };
  return v;
}

// A relaxation that weakens with stretch refines a relaxation the records
// already showed (a Maxwell branch or a spectrum): on its own its factor
// g(x) on the RT chain is a dynamic softening, which `softening` names.
std::string needs_other_cause(const Candidate &c, const std::vector<Candidate> &causes) {
  if (c.name != "stretch_relaxation") return "";
  for (const Candidate &k : causes)
    if (k.name == "maxwell" || k.name == "relaxation_spectrum") return "";
  return "refines a relaxation: needs maxwell or relaxation_spectrum among the causes";
}

bool candidates_conflict(const Candidate &a, const Candidate &b) {
  if (a.name == b.name) return true;
  auto is = [&](const char *n, const char *var) {
    return (a.name == n && a.variant == var) || (b.name == n && b.variant == var);
  };
  return is("slack", "") && is("backlash", "held");
}

ExtFitSpec candidate_spec(const Candidate &c, const DataScales &s) { return combined_spec({c}, s); }

ExtFitSpec combined_spec(const std::vector<Candidate> &cs, const DataScales &s) {
  ExtFitSpec spec;
  spec.free = core_params();
  for (const Candidate &c : cs) {
    for (ParamId id : c.extra)
      if (std::find(spec.free.begin(), spec.free.end(), id) == spec.free.end()) spec.free.push_back(id);
    spec.fit_delay = spec.fit_delay || c.delay;
    spec.fit_offset = spec.fit_offset || c.offset;
  }
  spec.scale[P_k3] = 0.1 * s.Fmax / (s.Xmax * s.Xmax * s.Xmax);
  spec.scale[P_k_asym] = 0.1 * s.Ksec;
  spec.scale[P_k2] = 0.1 * s.Ksec / s.Xmax;
  spec.scale[P_spec_exp] = 0.3;
  // Step unit of the sizes optimized linearly from 0 (param_transform.h).
  for (ParamId id : spec.free)
    if (is_ramp(id) && id != P_mullins && id != P_fric_asym && id != P_K0)
      spec.scale[id] = extra_start_value(id, s);
  spec.delay_scale = 10.0 * s.dt;
  spec.offset_scale = 0.01 * s.Fmax;
  return spec;
}

bool other_definition(const Candidate &c, const ExtModel &start, const DataScales &s,
                      Candidate *alt, ExtModel *alt_start) {
  *alt = c;
  *alt_start = start;
  if (c.delay && start.delay_lead) return false;  // a lead has one definition
  if (c.delay) {
    alt_start->delay_lowpass = !start.delay_lowpass;
    return true;
  }
  if (c.name == "mullins" && c.variant == "erf") return false;  // its own word entry
  if (c.name == "mullins") {
    // K0-only and whole-force softening look alike at zero size; the whole
    // form starts with the same loss of force at the stroke: mu S = mu_K0 K0 x.
    const bool to_whole = c.variant.empty();
    alt->variant = to_whole ? "whole" : "";
    rtb_params &p = alt_start->p;
    const double share = p.K0 / (p.K0 + 1.0 / (1.0 / p.Kpa + p.cells / p.Kr));
    p.mullins = std::max(0.05, std::min(0.9, to_whole ? p.mullins * share : p.mullins / share));
    p.mullins_whole = to_whole ? 1.0 : 0.0;
    return true;
  }
  if (c.name != "asymmetry") return false;
  const bool to_quadratic = c.variant.empty();
  alt->extra = {to_quadratic ? P_k2 : P_k_asym};
  alt->variant = to_quadratic ? "quadratic" : "";
  const double x = 2.0 / 3.0 * s.Xmax;  // k_asym x = k2 x^2 there
  rtb_params &p = alt_start->p;
  if (to_quadratic) p.k2 = p.k_asym / x, p.k_asym = 0.0;
  else p.k_asym = std::max(-0.9 * k_asym_bound(p), std::min(0.9 * k_asym_bound(p), p.k2 * x)), p.k2 = 0.0;
  return true;
}

double extra_start_value(ParamId id, const DataScales &s) {
  switch (id) {
    case P_viscous_c: return 0.02 * s.Fmax / s.Vmax;
    case P_mass: return 0.02 * s.Fmax / s.Amax;
    case P_maxwell_k: return 0.1 * s.Ksec;
    case P_maxwell_tau: return 0.1 * s.duration;
    case P_mullins: return 0.1;
    case P_mullins_width: return 0.3 * s.Xmax;
    case P_backlash: return 0.02 * s.Xmax;
    case P_sat_force: return 0.05 * s.Fmax;
    case P_sat_disp: return 0.1 * s.Xmax;
    case P_spec_k: return 0.1 * s.Ksec;
    default: return 0.0;
  }
}

std::string display_name(const Candidate &c) {
  return c.variant.empty() ? c.name : c.name + " (" + c.variant + ")";
}

std::string describe_effect(const Candidate &c, const ExtModel &m) {
  char b[200];
  const rtb_params &p = m.p;
  if (c.name == "cubic_stiffness")
    std::snprintf(b, sizeof b, "cubic stiffness k3 = %.4g (%s)", p.k3,
                  p.k3 >= 0 ? "progressive" : "degressive");
  else if (c.name == "asymmetry" && c.variant == "quadratic")
    std::snprintf(b, sizeof b, "asymmetry, quadratic k2 = %.4g (tangent stiffness K0 %+.4g x)",
                  p.k2, 2.0 * p.k2);
  else if (c.name == "asymmetry")
    std::snprintf(b, sizeof b, "asymmetry k_asym = %.4g (tension %.4g, compression %.4g)", p.k_asym,
                  p.K0 + p.k_asym, p.K0 - p.k_asym);
  else if (c.name == "maxwell")
    std::snprintf(b, sizeof b, "Maxwell branch k = %.4g, tau = %.4g s", p.maxwell_k, p.maxwell_tau);
  else if (c.name == "viscous")
    std::snprintf(b, sizeof b, "linear damping c = %.4g", p.viscous_c);
  else if (c.name == "backlash")
    std::snprintf(b, sizeof b, "backlash of %.4g (%s end)", p.backlash,
                  p.backlash_held != 0.0 ? "held" : "floating");
  else if (c.name == "mullins" && p.mullins_width > 0.0)
    std::snprintf(b, sizeof b, "Mullins softening mu = %.4g of the %s, Ogden-Roxburgh erf shape "
                  "of width %.4g", p.mullins, p.mullins_whole != 0.0 ? "whole RT force" : "K0",
                  p.mullins_width);
  else if (c.name == "mullins" && p.mullins_whole != 0.0)
    std::snprintf(b, sizeof b, "Mullins softening mu = %.4g of the whole RT force", p.mullins);
  else if (c.name == "mullins")
    std::snprintf(b, sizeof b, "Mullins softening mu = %.4g of K0", p.mullins);
  else if (c.name == "delay" && m.delay_lowpass)
    std::snprintf(b, sizeof b, "force channel low-passed, first order, time constant %.4g s "
                  "(corner %.4g Hz)", m.delay, m.delay > 0 ? 1.0 / (6.283185307179586 * m.delay) : 0.0);
  else if (c.name == "delay" && m.delay_lead)
    std::snprintf(b, sizeof b, "displacement channel delayed by %.4g s (the force leads it)", m.delay);
  else if (c.name == "delay")
    std::snprintf(b, sizeof b, "force channel delayed by %.4g s", m.delay);
  else if (c.name == "inertia")
    std::snprintf(b, sizeof b, "moving mass m = %.4g", p.mass);
  else if (c.name == "softening")
    std::snprintf(b, sizeof b, "softening spring %.4g tanh(x / %.4g) (initial stiffness %.4g)",
                  p.sat_force, p.sat_disp, p.sat_disp > 0 ? p.sat_force / p.sat_disp : 0.0);
  else if (c.name == "offset")
    std::snprintf(b, sizeof b, "force offset of %.4g", m.offset);
  else if (c.name == "slack")
    std::snprintf(b, sizeof b, "slack: the specimen cannot push (floats free at zero force)");
  else if (c.name == "relaxation_spectrum")
    std::snprintf(b, sizeof b, "relaxation spectrum k = %.4g, exponent %.3g over %.3g..%.3g s",
                  p.spec_k, p.spec_exp, p.spec_tau_min, p.spec_tau_max);
  else if (c.name == "stretch_relaxation")
    std::snprintf(b, sizeof b, "relaxation weakening with stretch: relaxing force x 1/sqrt(1 + (x/%.4g)^2)",
                  p.relax_width);
  else if (c.name == "friction_asymmetry")
    std::snprintf(b, sizeof b, "friction asymmetry a = %.3g (dashpot level x%.3g for + motion, x%.3g for -)",
                  p.fric_asym, 1 + p.fric_asym, 1 - p.fric_asym);
  else
    std::snprintf(b, sizeof b, "%s", c.name.c_str());
  return b;
}

}  // namespace rtb
