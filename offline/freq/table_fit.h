// table_fit.h -- identification from a dynamic-stiffness table (issue #13):
// minimize over p
//   J(p) = 1/2 sum_rows w [ (ln|K*(p)| - ln K_table)^2 + (arg K*(p) - delta_table)^2 ]
// (loss angle in radians: 1% of stiffness weighs as 0.57 deg; both are the
// relative error of the complex stiffness, ln K* = ln|K*| + i delta), where
// K*(p) is the last-period harmonic ratio of a fixed-discretization periodic
// run from rest (periodic_drive.h). The harmonic is a linear functional of
// the force samples of the last period, so each output's cotangent on force
// sample i is Re(lambda dF1/dF_i) with lambda = 1/F1 (ln|K*|) or -i/F1
// (arg K*), and the exact gradient is one adjoint sweep of the stepper
// (adjoint/step_linearization.h) through the whole run; the Gauss-Newton
// Jacobian is two sweeps per row.
#ifndef RTB_OFFLINE_FREQ_TABLE_FIT_H
#define RTB_OFFLINE_FREQ_TABLE_FIT_H

#include <Eigen/Dense>
#include <array>
#include <string>
#include <vector>

#include "freq/dynstiff_table.h"
#include "freq/periodic_drive.h"
#include "identify/identify.h"

namespace rtb {

// Residuals (2 per row of positive weight: ln-stiffness, then loss angle in
// rad) and, if jac, their exact Jacobian w.r.t. `free` (adjoint sweeps).
void table_residuals(const rtb_params &p, const DynStiffTable &t,
                     const std::vector<Discretization> &disc, const std::vector<ParamId> &free,
                     Eigen::VectorXd &r, Eigen::MatrixXd *jac, double newton_tol = 1e-12);

// J(p) above and, if grad, dJ/dp for every ParamId (one adjoint sweep per row).
double table_misfit(const rtb_params &p, const DynStiffTable &t,
                    const std::vector<Discretization> &disc, std::array<double, P_COUNT> *grad,
                    double newton_tol = 1e-12);

// Per row, the converged discretization at p (periodic_drive.h checks).
std::vector<Discretization> choose_discretizations(const rtb_params &p, const DynStiffTable &t,
                                                   const DynStiffOptions &o);

// Start point from the table alone (reasoning in table_fit.cpp).
rtb_params table_initial_guess(const DynStiffTable &t, int cells, std::string *note = nullptr);

struct TableFitOptions {
  std::vector<ParamId> free = core_params();
  Method method = Method::TrustRegion;
  int max_iter = 100;
  double chi2_tol = 0.01;   // optimizer.h: stop within ~0.1 sigma of the minimum
  DynStiffOptions conv;     // accuracy of the discretization (re-checked at the optimum)
  bool quiet = true;
};

struct TableFitResult {
  IdentifyResult fit;                    // params, iterations, uncertainty, ...
  std::vector<Discretization> disc;      // per row, as used in the final fit
  std::vector<ComplexStiffness> model;   // per row, of the identified p
  double rms_stiffness_rel = 0, max_stiffness_rel = 0;  // model vs table
  double rms_loss_deg = 0, max_loss_deg = 0;
  double disc_check_rel = 0, disc_check_deg = 0;  // fixed vs re-converged at the optimum
  int refits = 0;                        // refits after the discretization re-check
};

TableFitResult fit_dynstiff_table(const DynStiffTable &t, const rtb_params &start,
                                  const TableFitOptions &o);

}  // namespace rtb

#endif
