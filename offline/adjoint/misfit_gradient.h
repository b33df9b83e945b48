// misfit_gradient.h -- the misfit of eq. (11) over several records, its exact
// adjoint gradient (one backward sweep per record), the residual Jacobian by
// tangent sweeps (Gauss-Newton / Fisher information), and the dot-product
// test of eq. (15)-(16).
#ifndef RTB_OFFLINE_MISFIT_GRADIENT_H
#define RTB_OFFLINE_MISFIT_GRADIENT_H

#include <Eigen/Dense>
#include <array>
#include <vector>

#include "model/forward.h"
#include "rtb_offline.h"

namespace rtb {

struct MisfitOptions {
  SimOptions sim;
  double fit_from = 0.0;                 // [time] samples before t0 + fit_from are masked
  std::array<double, P_COUNT> R{};       // Tikhonov weights (0 = none), eq. (11)
  std::array<double, P_COUNT> p0{};      // Tikhonov reference values
  int threads = 1;  // records simulated in parallel by the extended fits (diagnose)
};

// Trapezoidal quadrature weights of eq. (11)/(27) on the record's own time
// grid, times the record weight, zero before t0 + fit_from.
std::vector<double> quadrature_weights(const Record &rec, double fit_from);

struct MisfitValue {
  double J = 0.0;    // eq. (11), including the Tikhonov term
  double J0 = 0.0;   // eq. (27)
  std::vector<double> J_rec, J0_rec;      // per record (no Tikhonov)
  std::array<double, P_COUNT> grad{};     // dJ/dp for every ParamId
  long forward_steps = 0, newton_iterations = 0;
  int forward_solves = 0, adjoint_solves = 0;
  double error() const;                   // sqrt(J/J0)
};

// J and (if want_grad) its exact gradient by the discrete adjoint sweep.
MisfitValue misfit(const rtb_params &p, const std::vector<Record> &recs,
                   const MisfitOptions &opt, bool want_grad);

// Keeps the last forward run of each record with its trace, so that a
// trust-region trial point that is accepted does not need a second forward
// solve for its Jacobian. One cache per optimization; entries are per record.
class SensitivityCache {
 public:
  struct Entry {
    rtb_params p{};
    double tol = 0, ramp = 0;
    StartMode start = StartMode::automatic;
    bool valid = false;
    DriveGrid grid;
    Trajectory tr;
  };
  Entry &entry(const Record *rec);  // create all entries before threading
  void prepare(const std::vector<Record> &recs);

 private:
  std::vector<std::pair<const Record *, Entry>> entries_;
};

// Model force at the record's samples and (if jac) its sensitivities
// dF_j/dp for the parameters in `free`, by tangent sweeps (exact).
void record_sensitivities(const rtb_params &p, const Record &rec, const SimOptions &sim,
                          const std::vector<ParamId> &free, Eigen::VectorXd &F,
                          Eigen::MatrixXd *jac, SensitivityCache *cache = nullptr);

// Weighted residuals r_j = sqrt(omega_j) (F_j - F_exp_j), stacked over records
// (masked samples dropped), and their Jacobian w.r.t. `free` by tangent sweeps.
void residual_jacobian(const rtb_params &p, const std::vector<Record> &recs,
                       const MisfitOptions &opt, const std::vector<ParamId> &free,
                       Eigen::VectorXd &r, Eigen::MatrixXd *jac,
                       SensitivityCache *cache = nullptr);

// Dot-product test, eq. (15)-(16), generalized: random state sources a_i and
// parameter direction dp through the tangent model give (dF, dy); random
// cotangents (Fbar, ybar) through the adjoint give (abar, pbar). Returns
// |<Fbar,dF> + <ybar,dy> - <abar,a> - <pbar,dp>| / max(|lhs|, |rhs|).
double dot_product_test(const rtb_params &p, const Record &rec, const SimOptions &sim,
                        unsigned seed);

}  // namespace rtb

#endif
