// param_ids.cpp -- names and accessors of the identifiable parameters.
#include "rtb_offline.h"

namespace rtb {

const char *param_name(ParamId id) {
  static const char *const names[P_COUNT] = {
      "K0", "Kpa", "Kr", "C0", "alpha", "k3", "k_asym", "maxwell_k", "maxwell_tau",
      "viscous_c", "mass", "backlash", "mullins", "sat_force", "sat_disp"};
  return (id >= 0 && id < P_COUNT) ? names[id] : "?";
}

double &param_ref(rtb_params &p, ParamId id) {
  switch (id) {
    case P_K0: return p.K0;
    case P_Kpa: return p.Kpa;
    case P_Kr: return p.Kr;
    case P_C0: return p.C0;
    case P_alpha: return p.alpha;
    case P_k3: return p.k3;
    case P_k_asym: return p.k_asym;
    case P_maxwell_k: return p.maxwell_k;
    case P_maxwell_tau: return p.maxwell_tau;
    case P_viscous_c: return p.viscous_c;
    case P_mass: return p.mass;
    case P_backlash: return p.backlash;
    case P_mullins: return p.mullins;
    case P_sat_force: return p.sat_force;
    case P_sat_disp: return p.sat_disp;
    case P_COUNT: break;
  }
  throw std::logic_error("param_ref: bad id");
}

double param_get(const rtb_params &p, ParamId id) {
  return param_ref(const_cast<rtb_params &>(p), id);
}

}  // namespace rtb
