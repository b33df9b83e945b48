// extended_fit.h -- least-squares fit of an extended model: the RT element
// with any of its physical extensions free, plus two measurement-chain
// artefacts that act on the predicted force only and never enter the
// real-time element:
//   F_pred(t) = F_model(t - delay) + offset,
// or, with the second definition of the delay (a load-cell amplifier's
// bandwidth), F_model through a first-order low-pass of time constant
// `delay` (its group delay at low frequency) instead of the pure lag.
#ifndef RTB_OFFLINE_EXTENDED_FIT_H
#define RTB_OFFLINE_EXTENDED_FIT_H

#include <Eigen/Dense>
#include <array>
#include <string>
#include <vector>

#include "adjoint/misfit_gradient.h"
#include "identify/identify.h"

namespace rtb {

struct ExtModel {
  rtb_params p{};
  double delay = 0.0;   // [time] force channel lags displacement by `delay` (>= 0)
  bool delay_lowpass = false;  // the lag is a first-order low-pass of time constant `delay`
  bool delay_lead = false;     // the force leads by `delay` instead: the displacement
                               // channel lags (a filtered or late position sensor)
  double offset = 0.0;  // [force] constant sensor offset
};

struct ExtFitSpec {
  std::vector<ParamId> free = core_params();
  bool fit_delay = false, fit_offset = false;
  std::array<double, P_COUNT> scale{};  // typical size of signed params starting at 0
  double delay_scale = 1e-3, offset_scale = 1.0;
  int max_iter = 60;
  int robust_max_iter = 20;  // the refit after masking starts at the first fit's optimum
  double chi2_tol = 0.01;  // convergence, in noise-variance units (OptOptions)
  // Outlier-robust refit: after a first fit, samples whose residual exceeds
  // robust_k robust standard deviations (1.4826 MAD) are masked and the fit
  // repeated, if they are at most robust_max_fraction of the samples (isolated
  // spikes, e.g. a discrete acceleration at an ideal input corner or a
  // machine transient); a systematic misfit is never masked. 0 disables.
  double robust_k = 6.0;
  double robust_max_fraction = 0.01;
  // Restarts of the first fit along its least determined direction
  // (restart_sloppy, optimizer.h); 0 (the joint fits): none.
  int restarts = 0;
};

struct ExtFitResult {
  ExtModel model;
  double error = 0.0;        // sqrt(J/J0) on the fit records
  double J = 0.0, J0 = 0.0;
  long samples = 0;          // residuals in the misfit
  int iterations = 0;
  bool converged = false;
  std::vector<std::string> names;  // free parameter names, then delay, offset
  Eigen::VectorXd value, stddev;   // same order as names
  bool stddev_valid = false;
  long masked = 0;                 // samples masked by the robust refit
};

// Predicted force at the record's samples and its sensitivities (columns:
// spec.free, then delay, then offset when fitted).
void predict_extended(const ExtModel &m, const Record &rec, const SimOptions &sim,
                      const ExtFitSpec &spec, Eigen::VectorXd &F, Eigen::MatrixXd *jac,
                      SensitivityCache *cache = nullptr);

ExtFitResult fit_extended(const std::vector<Record> &recs, const ExtModel &start,
                          const ExtFitSpec &spec, const MisfitOptions &opt);

// The records as the element would see them: the model's force-channel
// artefacts removed, F_corrected(t) = F(t + delay) - offset (linear
// interpolation; the last `delay` seconds hold the final sample). A
// low-pass channel is undone by the same shift, its low-frequency
// equivalent: inverting the filter would amplify the noise by ~2 delay/dt,
// and the corrected records only start a refit (diagnose stage 5c).
std::vector<Record> artefact_corrected(const std::vector<Record> &recs, const ExtModel &m);

// The records as the cell chain and K0 see them: artefacts removed as
// above, and the static force of the elastic extensions beyond its tangent
// at x = 0 (bushing_force.h: k2 x^2 + k3 x^3 + k_asym |x| + sat_force
// (tanh(x/d) - x/d), on the recorded x) subtracted. The STS loop inversion
// of the raw records reads a softening spring's curvature as the chain's
// sliding; of these, as the chain it is (blindgen softening_s33: Kr 67 800
// from the raw records, 22 200 from these, the generator's 21 100).
std::vector<Record> chain_records(const std::vector<Record> &recs, const ExtModel &m);

// The elastic extensions' tangent at x = 0 that chain_records leaves in the
// force (sat_force / sat_disp): a start from their STS inversion takes it
// off K0.
double elastic_tangent_at_rest(const rtb_params &p);

// sqrt(sum J / sum J0) of a model on records (eq. (27)), and its J, J0.
// trim > 0 drops that fraction of the largest squared residuals of each
// record from J (a robust variant used to select causes, never reported as
// the eq. (27) figure).
double extended_error(const ExtModel &m, const std::vector<Record> &recs,
                      const MisfitOptions &opt, double *J = nullptr, double *J0 = nullptr,
                      double trim = 0.0);

}  // namespace rtb

#endif
