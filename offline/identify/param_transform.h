// param_transform.h -- unconstrained coordinates for the optimizers.
//
// Parameters that must stay strictly positive (Kpa, Kr, C0, maxwell_tau,
// backlash, sat_disp) are optimized as log p; alpha as a logistic image of
// (RTB_ALPHA_MIN, 1); signed parameters (k3, k_asym) scaled by a reference
// value. Log coordinates make the problem scale-free: a unit step is a
// relative change.
//
// Parameters for which 0 is an admissible and common optimum -- K0, and the
// sizes of the extensions (maxwell_k, viscous_c, mass, mullins, sat_force),
// which a fit on data without that effect drives to 0 -- are optimized
// linearly, p = scale theta, inside the box [0, upper] (K0 next to a
// softening spring or a kink: [-cap, upper], see signed_K0) that the trust-region
// optimizer enforces by projection. In log coordinates that optimum is
// infinitely far away: Gauss-Newton crawled towards it a few percent per
// iteration (60 iterations for a viscous term on delay data, each costing a
// tangent sweep), where the box reaches it in one projected step.
//
// Stiffness ceiling: with a finite `stiffness_cap` the stiffnesses (K0, Kpa,
// Kr, maxwell_k) map as p = cap e^t / (cap + e^t): log-like far below the cap,
// saturating at it. Without it an unidentifiable series spring runs off to
// 1e12 x the data's stiffness (seen on friction-damper data, where the
// optimum is a rigid Kpa), and F = Kpa (x - y1) then amplifies the round-off
// of y1 into forces of 1e9. At 1e3 x the secant stiffness the spring is rigid
// to 0.1% while the force round-off stays ~1e-13 relative.
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

  double stiffness_cap = 0.0;           // 0: no ceiling (pure log)
  // K0 may go negative (down to -(chain + sat_force/sat_disp), or -chain
  // with slack: rtb_params_check) when a softening spring is fitted with it:
  // a tanh that takes more than K0 (blindgen softening_s4: 0.8 of the
  // static stiffness, K0 = -435 N/mm), or when a kink k_asym |x| is
  // fitted with it.
  bool signed_K0 = false;
  // With a kink but no softening spring, K0 stays >= -|k_asym| as well: one
  // side may be softer than nothing (the chain holds it up), the other keeps
  // a spring of its own. Without it the kink's fit freed the core instead:
  // blindgen maxwell_s35's branch imitated by K0 = -7578 beside k_asym = -7
  // (Kpa 9630, Kr 1.6e6, alpha 0.80), a 0.1% asymmetry named first.
  bool kink_floor = false;

  ParamTransform(std::vector<ParamId> free_ids, const rtb_params &start,
                 double stiffness_cap = 0.0);
  Eigen::VectorXd to_theta(const rtb_params &p) const;
  rtb_params to_params(const Eigen::VectorXd &theta, const rtb_params &base) const;
  // dp_i / dtheta_i at theta of each coordinate's own map (the diagonal of
  // the Jacobian before the k_asym_bound clamp).
  Eigen::VectorXd dp_dtheta(const Eigen::VectorXd &theta) const;
  // The whole Jacobian dp_free / dtheta of to_params(theta, base): the
  // diagonal above, except where to_params clamps. A signed K0 held at its
  // floor follows Kpa, Kr and the softening spring (or -|k_asym|, kink_floor); k_asym clamped to +-k_asym_bound follows the
  // bound's row (or is constant 0) and not its own coordinate, so gradients through
  // the clamps are exact.
  Eigen::MatrixXd jacobian(const Eigen::VectorXd &theta, const rtb_params &base) const;
  // Chain rule: dJ/dtheta from dJ/dp (every ParamId) at theta, through the
  // whole Jacobian above (exact at the k_asym clamp).
  Eigen::VectorXd theta_gradient(const std::array<double, P_COUNT> &dJ_dp,
                                 const Eigen::VectorXd &theta, const rtb_params &base) const;
  // The box on theta (-inf/+inf where unbounded), for OptOptions.
  Eigen::VectorXd lower() const;
  Eigen::VectorXd upper() const;
  double lower_of(ParamId id) const;  // lower end of a Ramp parameter's box
  // -|k_asym| at theta when kink_floor holds, else -inf.
  double kink_floor_at(const Eigen::VectorXd &theta) const;
};

// rtb_params_check's bound on |k_asym|: the static
// tangent K0 + chain + sat_force/sat_disp (K0 on a slack strip with
// relax_width), 0 when that is negative.
double k_asym_bound(const rtb_params &p);

// K0 < 0 is admissible only next to a softening spring or a kink, and not on a slack
// strip with relax_width (rtb_params_check); a model without one (a cause
// switched off, a baseline restarted from a candidate's basin) takes K0 back
// to 0.
void admit_K0(rtb_params &p);

// Optimized linearly in a box with 0 as its lower bound (see above).
bool is_ramp(ParamId id);

// The stiffness ceiling for records: kStiffnessCapFactor x max|F| / max|x|.
constexpr double kStiffnessCapFactor = 1e3;
double stiffness_cap_for(const std::vector<Record> &recs);

// The default free set: the five RT parameters.
std::vector<ParamId> core_params();

}  // namespace rtb

#endif
