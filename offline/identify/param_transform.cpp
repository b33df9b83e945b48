// param_transform.cpp -- see param_transform.h.
#include "identify/param_transform.h"

#include <algorithm>
#include <cmath>

namespace rtb {

namespace {
enum class Kind { Log, CappedLog, Alpha, Linear, Ramp };
bool is_stiffness(ParamId id) {
  return id == P_K0 || id == P_Kpa || id == P_Kr || id == P_maxwell_k || id == P_spec_k;
}
Kind kind_of(ParamId id, double cap) {
  switch (id) {
    case P_K0:
    case P_maxwell_k:
    case P_viscous_c:
    case P_mass:
    case P_mullins:
    case P_sat_force:
    case P_spec_k:
    case P_fric_asym: return Kind::Ramp;
    case P_alpha: return Kind::Alpha;
    case P_k2:
    case P_k3:
    case P_k_asym:
    case P_spec_exp: return Kind::Linear;
    default: return cap > 0.0 && is_stiffness(id) ? Kind::CappedLog : Kind::Log;
  }
}
// Admissible box of a Ramp parameter (linear, zero-admissible). A signed K0
// (next to a softening spring) may go down to -cap; to_params then holds it
// above k0_floor, the library's bound.
double ramp_lower(ParamId id, bool signed_K0, double cap) {
  if (id == P_K0 && signed_K0) return cap > 0.0 ? -cap : -INFINITY;
  return id == P_fric_asym ? -0.95 : 0.0;  // |a| < 1
}
// rtb_params_check keeps the static tangent at x = 0 non-negative:
// K0 + chain + sat_force / sat_disp >= 0, chain = 1 / (1/Kpa + N/Kr) (the
// cells relaxed, rtb_static_force); a slack specimen K0 + chain >= 0.
// to_params holds K0 at kShare of that floor: strictly inside whatever the
// rounding.
constexpr double kShare = 1.0 - 1e-9;
struct K0Floor {
  double value, d_Kpa, d_Kr, d_sat_force, d_sat_disp;
};
K0Floor k0_floor(const rtb_params &p) {
  const double c = 1.0 / (1.0 / p.Kpa + p.cells / p.Kr);
  const double sat = p.sat_disp > 0.0 && p.slack == 0.0 ? p.sat_force / p.sat_disp : 0.0;
  K0Floor f;
  f.value = -kShare * (c + sat);
  f.d_Kpa = -kShare * c * c / (p.Kpa * p.Kpa);
  f.d_Kr = -kShare * c * c * p.cells / (p.Kr * p.Kr);
  f.d_sat_force = sat > 0.0 ? -kShare / p.sat_disp : 0.0;
  f.d_sat_disp = sat > 0.0 ? kShare * sat / p.sat_disp : 0.0;
  if (p.slack != 0.0 && p.relax_width > 0.0) f = K0Floor{0.0, 0.0, 0.0, 0.0, 0.0};  // K0 >= 0
  return f;
}
bool contains(const std::vector<ParamId> &v, ParamId id) {
  return std::find(v.begin(), v.end(), id) != v.end();
}
double ramp_upper(ParamId id, double cap) {
  if (id == P_mullins || id == P_fric_asym) return 0.95;  // rtb_params_validate: < 1
  if (is_stiffness(id) && cap > 0.0) return cap;
  return INFINITY;
}
constexpr double kAlphaLo = RTB_ALPHA_MIN, kAlphaHi = 1.0;
double logistic(double t) { return 1.0 / (1.0 + std::exp(-t)); }
}  // namespace

double k_asym_bound(const rtb_params &p) { return std::fmax(p.K0 - k0_floor(p).value, 0.0); }

void admit_K0(rtb_params &p) {
  const bool below_zero = p.sat_force > 0.0 || p.k_asym != 0.0;
  if (!below_zero || (p.slack != 0.0 && p.relax_width > 0.0)) p.K0 = std::max(p.K0, 0.0);
}

bool is_ramp(ParamId id) { return kind_of(id, 0.0) == Kind::Ramp; }

std::vector<ParamId> core_params() { return {P_K0, P_Kpa, P_Kr, P_C0, P_alpha}; }

double stiffness_cap_for(const std::vector<Record> &recs) {
  double F = 0.0, X = 0.0;
  for (const Record &r : recs) {
    for (double v : r.F) F = std::fmax(F, std::fabs(v));
    for (double v : r.x) X = std::fmax(X, std::fabs(v));
  }
  return (F > 0.0 && X > 0.0) ? kStiffnessCapFactor * F / X : 0.0;
}

ParamTransform::ParamTransform(std::vector<ParamId> free_ids, const rtb_params &start,
                               double cap)
    : free(std::move(free_ids)), stiffness_cap(std::isfinite(cap) && cap > 0.0 ? cap : 0.0) {
  // A softening spring or a kink may take K0 below zero: blindgen
  // asymmetry_s34's tension side is 320 N/mm softer than K0 = 151.
  signed_K0 = contains(free, P_K0) && (contains(free, P_sat_force) || contains(free, P_k_asym));
  kink_floor = signed_K0 && !contains(free, P_sat_force);
  for (ParamId id : free) {
    const double v = std::fabs(param_get(start, id));
    scale[id] = v > 0.0 ? v : 1.0;
    // A ramp step is absolute: a stiffness started near 0 must still be able
    // to grow to the data's secant stiffness (cap / kStiffnessCapFactor) in
    // a few steps.
    if (kind_of(id, stiffness_cap) == Kind::Ramp && is_stiffness(id) && stiffness_cap > 0.0)
      scale[id] = std::fmax(scale[id], stiffness_cap / kStiffnessCapFactor);
    if (id == P_mullins || id == P_fric_asym) scale[id] = 0.1;
  }
}

Eigen::VectorXd ParamTransform::to_theta(const rtb_params &p) const {
  Eigen::VectorXd th(free.size());
  for (size_t i = 0; i < free.size(); ++i) {
    const ParamId id = free[i];
    const double v = param_get(p, id);
    switch (kind_of(id, stiffness_cap)) {
      case Kind::Log: th[i] = std::log(std::fmax(v, 1e-300)); break;
      case Kind::CappedLog: {  // inverse of p = c e^t / (c + e^t)
        const double u = std::fmin(std::fmax(v, 1e-300) / stiffness_cap, 1.0 - 1e-9);
        th[i] = std::log(std::fmax(v, 1e-300)) - std::log1p(-u);
        break;
      }
      case Kind::Alpha: {
        const double u = std::fmin(std::fmax((v - kAlphaLo) / (kAlphaHi - kAlphaLo), 1e-9), 1 - 1e-9);
        th[i] = std::log(u / (1.0 - u));
        break;
      }
      case Kind::Linear: th[i] = v / scale[id]; break;
      case Kind::Ramp:
        th[i] = std::fmin(std::fmax(v, lower_of(id)), ramp_upper(id, stiffness_cap)) / scale[id];
        break;
    }
  }
  return th;
}

rtb_params ParamTransform::to_params(const Eigen::VectorXd &th, const rtb_params &base) const {
  rtb_params p = base;
  for (size_t i = 0; i < free.size(); ++i) {
    const ParamId id = free[i];
    double &v = param_ref(p, id);
    switch (kind_of(id, stiffness_cap)) {
      case Kind::Log: v = std::exp(th[i]); break;
      case Kind::CappedLog:
        v = stiffness_cap / (1.0 + std::exp(std::log(stiffness_cap) - th[i]));
        break;
      case Kind::Alpha: v = kAlphaLo + (kAlphaHi - kAlphaLo) * logistic(th[i]); break;
      case Kind::Linear: v = th[i] * scale[id]; break;
      case Kind::Ramp:  // clamped, so that an unbounded optimizer (BFGS) stays valid
        v = std::fmin(std::fmax(th[i] * scale[id], lower_of(id)), ramp_upper(id, stiffness_cap));
        break;
    }
  }
  // Keep K0 above its floors and |k_asym| within k_asym_bound (rtb_params_check) by clamping.
  if (signed_K0) p.K0 = std::fmax(p.K0, std::fmax(k0_floor(p).value, kink_floor_at(th)));
  const double asym_max = k_asym_bound(p);
  if (std::fabs(p.k_asym) > asym_max) p.k_asym = std::copysign(asym_max, p.k_asym);
  if (p.alpha >= 1.0) p.alpha = std::nextafter(1.0, 0.0);
  return p;
}

Eigen::VectorXd ParamTransform::dp_dtheta(const Eigen::VectorXd &th) const {
  Eigen::VectorXd d(free.size());
  for (size_t i = 0; i < free.size(); ++i) {
    const ParamId id = free[i];
    switch (kind_of(id, stiffness_cap)) {
      case Kind::Log: d[i] = std::exp(th[i]); break;
      case Kind::CappedLog: {
        const double p = stiffness_cap / (1.0 + std::exp(std::log(stiffness_cap) - th[i]));
        d[i] = p * (1.0 - p / stiffness_cap);
        break;
      }
      case Kind::Alpha: {
        const double s = logistic(th[i]);
        d[i] = (kAlphaHi - kAlphaLo) * s * (1.0 - s);
        break;
      }
      case Kind::Linear: d[i] = scale[id]; break;
      case Kind::Ramp: {
        // One-sided at the bounds: the box optimizer needs the inward slope.
        const double v = th[i] * scale[id];
        d[i] = (v < lower_of(id) || v > ramp_upper(id, stiffness_cap)) ? 0.0 : scale[id];
        break;
      }
    }
  }
  return d;
}

double ParamTransform::kink_floor_at(const Eigen::VectorXd &th) const {
  if (!kink_floor) return -INFINITY;
  for (size_t i = 0; i < free.size(); ++i)
    if (free[i] == P_k_asym) return -std::fabs(th[i] * scale[P_k_asym]);
  return -INFINITY;
}

double ParamTransform::lower_of(ParamId id) const {
  return ramp_lower(id, signed_K0, stiffness_cap);
}

Eigen::MatrixXd ParamTransform::jacobian(const Eigen::VectorXd &th, const rtb_params &base) const {
  const Eigen::VectorXd d = dp_dtheta(th);
  Eigen::MatrixXd J = d.asDiagonal();
  auto index_of = [&](ParamId id) {
    for (size_t i = 0; i < free.size(); ++i)
      if (free[i] == id) return (Eigen::Index)i;
    return (Eigen::Index)-1;
  };
  const rtb_params p = to_params(th, base);
  // Row `row` += sign d floor(Kpa, Kr, sat_force, sat_disp) / dtheta.
  auto add_floor_row = [&](Eigen::Index row, double sign) {
    const K0Floor f = k0_floor(p);
    const std::pair<ParamId, double> deps[] = {
        {P_Kpa, f.d_Kpa}, {P_Kr, f.d_Kr}, {P_sat_force, f.d_sat_force}, {P_sat_disp, f.d_sat_disp}};
    for (const auto &dep : deps) {
      const Eigen::Index j = index_of(dep.first);
      if (j >= 0) J(row, j) += sign * dep.second * d[j];
    }
  };
  const Eigen::Index i0 = index_of(P_K0);
  // K0 held at a floor: -|k_asym| (kink_floor), or the static tangent's, which
  // follows Kpa, Kr and the softening spring.
  const double k0_boxed =
      i0 >= 0 ? std::fmin(std::fmax(th[i0] * scale[P_K0], lower_of(P_K0)), ramp_upper(P_K0, stiffness_cap))
              : 0.0;
  const Eigen::Index ia = index_of(P_k_asym);
  const double kink = kink_floor_at(th);
  if (i0 >= 0 && signed_K0 && k0_boxed < kink && kink > k0_floor(p).value) {
    J(i0, i0) = 0.0;  // K0 = -|k_asym|
    J(i0, ia) = -std::copysign(1.0, th[ia]) * d[ia];
  } else if (i0 >= 0 && signed_K0 && k0_boxed < k0_floor(p).value) {
    J(i0, i0) = 0.0;
    add_floor_row(i0, 1.0);
  }
  if (ia < 0) return J;
  // The same test as to_params: raw k_asym against the bound of the mapped
  // parameters, K0 - floor(Kpa, Kr, sat_force, sat_disp).
  const double raw = th[ia] * scale[P_k_asym];
  if (!(std::fabs(raw) > k_asym_bound(p))) return J;
  J.row(ia).setZero();
  if (!(k_asym_bound(p) > 0.0)) return J;  // pinned at 0
  if (i0 >= 0) J.row(ia) = J.row(i0);
  add_floor_row(ia, -1.0);
  J.row(ia) *= std::copysign(1.0, raw);
  return J;
}

Eigen::VectorXd ParamTransform::theta_gradient(const std::array<double, P_COUNT> &dJ_dp,
                                               const Eigen::VectorXd &theta,
                                               const rtb_params &base) const {
  Eigen::VectorXd g(theta.size());
  for (size_t i = 0; i < free.size(); ++i) g[(Eigen::Index)i] = dJ_dp[free[i]];
  return jacobian(theta, base).transpose() * g;
}

Eigen::VectorXd ParamTransform::lower() const {
  Eigen::VectorXd lo = Eigen::VectorXd::Constant((Eigen::Index)free.size(), -INFINITY);
  for (size_t i = 0; i < free.size(); ++i)
    if (kind_of(free[i], stiffness_cap) == Kind::Ramp)
      lo[(Eigen::Index)i] = lower_of(free[i]) / scale[free[i]];
  return lo;
}

Eigen::VectorXd ParamTransform::upper() const {
  Eigen::VectorXd hi = Eigen::VectorXd::Constant((Eigen::Index)free.size(), INFINITY);
  for (size_t i = 0; i < free.size(); ++i)
    if (kind_of(free[i], stiffness_cap) == Kind::Ramp)
      hi[(Eigen::Index)i] = ramp_upper(free[i], stiffness_cap) / scale[free[i]];
  return hi;
}

}  // namespace rtb
