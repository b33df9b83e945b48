// param_transform.cpp -- see param_transform.h.
#include "identify/param_transform.h"

#include <cmath>

namespace rtb {

namespace {
enum class Kind { Log, Alpha, Unit, Linear };
Kind kind_of(ParamId id) {
  switch (id) {
    case P_alpha: return Kind::Alpha;
    case P_mullins: return Kind::Unit;
    case P_k3:
    case P_k_asym: return Kind::Linear;
    default: return Kind::Log;
  }
}
constexpr double kAlphaLo = RTB_ALPHA_MIN, kAlphaHi = 1.0;
double logistic(double t) { return 1.0 / (1.0 + std::exp(-t)); }
}  // namespace

std::vector<ParamId> core_params() { return {P_K0, P_Kpa, P_Kr, P_C0, P_alpha}; }

ParamTransform::ParamTransform(std::vector<ParamId> free_ids, const rtb_params &start)
    : free(std::move(free_ids)) {
  for (ParamId id : free) {
    const double v = std::fabs(param_get(start, id));
    scale[id] = v > 0.0 ? v : 1.0;
  }
}

Eigen::VectorXd ParamTransform::to_theta(const rtb_params &p) const {
  Eigen::VectorXd th(free.size());
  for (size_t i = 0; i < free.size(); ++i) {
    const ParamId id = free[i];
    const double v = param_get(p, id);
    switch (kind_of(id)) {
      case Kind::Log: th[i] = std::log(std::fmax(v, 1e-300)); break;
      case Kind::Alpha: {
        const double u = std::fmin(std::fmax((v - kAlphaLo) / (kAlphaHi - kAlphaLo), 1e-9), 1 - 1e-9);
        th[i] = std::log(u / (1.0 - u));
        break;
      }
      case Kind::Unit: {
        const double u = std::fmin(std::fmax(v, 1e-9), 1 - 1e-9);
        th[i] = std::log(u / (1.0 - u));
        break;
      }
      case Kind::Linear: th[i] = v / scale[id]; break;
    }
  }
  return th;
}

rtb_params ParamTransform::to_params(const Eigen::VectorXd &th, const rtb_params &base) const {
  rtb_params p = base;
  for (size_t i = 0; i < free.size(); ++i) {
    const ParamId id = free[i];
    double &v = param_ref(p, id);
    switch (kind_of(id)) {
      case Kind::Log: v = std::exp(th[i]); break;
      case Kind::Alpha: v = kAlphaLo + (kAlphaHi - kAlphaLo) * logistic(th[i]); break;
      case Kind::Unit: v = logistic(th[i]); break;
      case Kind::Linear: v = th[i] * scale[id]; break;
    }
  }
  // Keep |k_asym| <= K0 (rtb_params_validate) by clamping.
  if (std::fabs(p.k_asym) > p.K0) p.k_asym = std::copysign(p.K0, p.k_asym);
  if (p.alpha >= 1.0) p.alpha = std::nextafter(1.0, 0.0);
  return p;
}

Eigen::VectorXd ParamTransform::dp_dtheta(const Eigen::VectorXd &th) const {
  Eigen::VectorXd d(free.size());
  for (size_t i = 0; i < free.size(); ++i) {
    const ParamId id = free[i];
    switch (kind_of(id)) {
      case Kind::Log: d[i] = std::exp(th[i]); break;
      case Kind::Alpha: {
        const double s = logistic(th[i]);
        d[i] = (kAlphaHi - kAlphaLo) * s * (1.0 - s);
        break;
      }
      case Kind::Unit: {
        const double s = logistic(th[i]);
        d[i] = s * (1.0 - s);
        break;
      }
      case Kind::Linear: d[i] = scale[id]; break;
    }
  }
  return d;
}

}  // namespace rtb
