// param_transform.h -- unconstrained coordinates for the optimizers.
//
// Stiffnesses and coefficients that must stay positive (K0, Kpa, Kr, C0,
// maxwell_k, maxwell_tau, viscous_c, mass, backlash) are optimized as log p;
// alpha as a logistic image of (RTB_ALPHA_MIN, 1); mullins of (0, 1); signed
// parameters (k3, k_asym) scaled by a reference value. Log coordinates also
// make the problem scale-free: a unit step is a relative change.
#ifndef RTB_OFFLINE_PARAM_TRANSFORM_H
#define RTB_OFFLINE_PARAM_TRANSFORM_H

#include <Eigen/Dense>
#include <array>
#include <vector>

#include "rtb_offline.h"

namespace rtb {

struct ParamTransform {
  std::vector<ParamId> free;
  std::array<double, P_COUNT> scale{};  // reference magnitude of signed params

  ParamTransform(std::vector<ParamId> free_ids, const rtb_params &start);
  Eigen::VectorXd to_theta(const rtb_params &p) const;
  rtb_params to_params(const Eigen::VectorXd &theta, const rtb_params &base) const;
  // dp_i / dtheta_i at theta (diagonal of the Jacobian).
  Eigen::VectorXd dp_dtheta(const Eigen::VectorXd &theta) const;
};

// The default free set: the five RT parameters.
std::vector<ParamId> core_params();

}  // namespace rtb

#endif
