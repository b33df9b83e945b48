// candidates.cpp -- see candidates.h.
#include "diagnose/candidates.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

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
  return s;
}

const std::vector<Candidate> &candidate_vocabulary() {
  static const std::vector<Candidate> v = {
      {"cubic_stiffness", true, {P_k3}, false, false},
      {"asymmetry", true, {P_k_asym}, false, false},
      {"maxwell", true, {P_maxwell_k, P_maxwell_tau}, false, false},
      {"viscous", true, {P_viscous_c}, false, false},
      {"backlash", true, {P_backlash}, false, false},
      {"mullins", true, {P_mullins}, false, false},
      {"delay", false, {}, true, false},
      {"inertia", true, {P_mass}, false, false},
      {"offset", false, {}, false, true},
      {"softening", true, {P_sat_force, P_sat_disp}, false, false},
  };
  return v;
}

ExtFitSpec candidate_spec(const Candidate &c, const DataScales &s) {
  ExtFitSpec spec;
  spec.free = core_params();
  spec.free.insert(spec.free.end(), c.extra.begin(), c.extra.end());
  spec.fit_delay = c.delay;
  spec.fit_offset = c.offset;
  spec.scale[P_k3] = 0.1 * s.Fmax / (s.Xmax * s.Xmax * s.Xmax);
  spec.scale[P_k_asym] = 0.1 * s.Ksec;
  // Step unit of the sizes optimized linearly from 0 (param_transform.h).
  for (ParamId id : c.extra)
    if (is_ramp(id) && id != P_mullins) spec.scale[id] = extra_start_value(id, s);
  spec.delay_scale = 10.0 * s.dt;
  spec.offset_scale = 0.01 * s.Fmax;
  return spec;
}

double extra_start_value(ParamId id, const DataScales &s) {
  switch (id) {
    case P_viscous_c: return 0.02 * s.Fmax / s.Vmax;
    case P_mass: return 0.02 * s.Fmax / s.Amax;
    case P_maxwell_k: return 0.1 * s.Ksec;
    case P_maxwell_tau: return 0.1 * s.duration;
    case P_mullins: return 0.1;
    case P_backlash: return 0.02 * s.Xmax;
    case P_sat_force: return 0.05 * s.Fmax;
    case P_sat_disp: return 0.1 * s.Xmax;
    default: return 0.0;
  }
}

std::string describe_effect(const Candidate &c, const ExtModel &m) {
  char b[200];
  const rtb_params &p = m.p;
  if (c.name == "cubic_stiffness")
    std::snprintf(b, sizeof b, "cubic stiffness k3 = %.4g (%s)", p.k3,
                  p.k3 >= 0 ? "progressive" : "degressive");
  else if (c.name == "asymmetry")
    std::snprintf(b, sizeof b, "asymmetry k_asym = %.4g (tension %.4g, compression %.4g)", p.k_asym,
                  p.K0 + p.k_asym, p.K0 - p.k_asym);
  else if (c.name == "maxwell")
    std::snprintf(b, sizeof b, "Maxwell branch k = %.4g, tau = %.4g s", p.maxwell_k, p.maxwell_tau);
  else if (c.name == "viscous")
    std::snprintf(b, sizeof b, "linear damping c = %.4g", p.viscous_c);
  else if (c.name == "backlash")
    std::snprintf(b, sizeof b, "backlash of %.4g", p.backlash);
  else if (c.name == "mullins")
    std::snprintf(b, sizeof b, "Mullins softening mu = %.4g", p.mullins);
  else if (c.name == "delay")
    std::snprintf(b, sizeof b, "force channel delayed by %.4g s", m.delay);
  else if (c.name == "inertia")
    std::snprintf(b, sizeof b, "moving mass m = %.4g", p.mass);
  else if (c.name == "softening")
    std::snprintf(b, sizeof b, "softening spring %.4g tanh(x / %.4g) (initial stiffness %.4g)",
                  p.sat_force, p.sat_disp, p.sat_disp > 0 ? p.sat_force / p.sat_disp : 0.0);
  else if (c.name == "offset")
    std::snprintf(b, sizeof b, "force offset of %.4g", m.offset);
  else
    std::snprintf(b, sizeof b, "%s", c.name.c_str());
  return b;
}

}  // namespace rtb
