// identify.h -- identification of the RT parameters (sections 4 and 5):
// minimize the misfit of eq. (11) over several records from a start point,
// then estimate the parameters' standard deviations and correlations.
#ifndef RTB_OFFLINE_IDENTIFY_H
#define RTB_OFFLINE_IDENTIFY_H

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "adjoint/misfit_gradient.h"
#include "identify/param_transform.h"

namespace rtb {

enum class Method { TrustRegion, Bfgs };
Method parse_method(const std::string &s);  // "trust-region" | "bfgs"; throws InputError
const char *method_name(Method m);

struct IdentifyOptions {
  Method method = Method::TrustRegion;
  MisfitOptions misfit;
  std::vector<ParamId> free = core_params();
  int max_iter = 200;
  // Restarts from the converged point, +-0.4 (log units) along the least
  // determined direction of the Gauss-Newton Hessian; the lowest misfit wins.
  // With noise the misfit has secondary minima along the Kr-C0 ridge.
  int restarts = 2;
  // Converged when the next step would gain less than this many noise-variance
  // units of chi^2 (optimizer.h); 0: relative tolerance 1e-10 only.
  double chi2_tol = 0.01;
  bool quiet = true;  // progress lines on stderr when false
};

struct Uncertainty {
  std::vector<ParamId> ids;
  Eigen::VectorXd stddev;        // of each parameter, in its own unit
  Eigen::MatrixXd correlation;
  double noise_sigma = 0.0;      // estimated force noise standard deviation
  bool valid = false;            // false if the information matrix is singular
};

struct IdentifyResult {
  rtb_params start{}, params{};
  Method method = Method::TrustRegion;
  double error_start = 0.0, error = 0.0;  // sqrt(J/J0), eq. (27)
  double J = 0.0, J0 = 0.0;
  std::vector<double> error_per_record;
  int iterations = 0;
  int forward_solves = 0, adjoint_solves = 0, tangent_sweeps = 0;
  double wall_seconds = 0.0;
  bool converged = false;
  std::string message;
  int restart_improved = 0;  // restarts that found a lower misfit
  Uncertainty uncertainty;
};

IdentifyResult identify(const std::vector<Record> &recs, const rtb_params &start,
                        const IdentifyOptions &opt);

// Fisher-information (Gauss-Newton) covariance at p from the residuals:
// sandwich form for non-uniform quadrature weights, white-noise assumption.
Uncertainty estimate_uncertainty(const rtb_params &p, const std::vector<Record> &recs,
                                 const MisfitOptions &opt, const std::vector<ParamId> &ids);

// The covariance core of estimate_uncertainty: residuals r_j = sqrt(w_j) e_j
// and rows sqrt(w_j) dF_j/dp; group[j] names the record of row j, whose
// noise level is estimated separately (records differ in noise). Returns
// false if the information is singular.
bool sandwich_covariance(const Eigen::VectorXd &r, const Eigen::MatrixXd &Jw,
                         const Eigen::VectorXd &w, const std::vector<int> &group,
                         Eigen::VectorXd &stddev, Eigen::MatrixXd *correlation,
                         double *noise_sigma = nullptr);
// Rows per record after masking, as the group vector above, with weights.
void row_groups(const std::vector<Record> &recs, double fit_from, std::vector<double> &w,
                std::vector<int> &group);

}  // namespace rtb

#endif
