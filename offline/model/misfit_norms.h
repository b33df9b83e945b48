// misfit_norms.h -- the relative error of the paper, eq. (27):
//   J  = 1/2 int (F_model - F_exp)^2 dt,   J0 = 1/2 int F_exp^2 dt,
//   error = sqrt(J / J0),
// integrated with the trapezoidal rule on the record's own (non-uniform)
// time grid; over several records, error = sqrt(sum w J / sum w J0).
// Shared by `rtb validate` and identify so both report the same figure.
#ifndef RTB_OFFLINE_MODEL_MISFIT_NORMS_H
#define RTB_OFFLINE_MODEL_MISFIT_NORMS_H

#include <cstddef>
#include <vector>

namespace rtb {

struct MisfitNorms {
  double J = 0.0;          // 1/2 int (F_model - F_exp)^2 dt (trapezoidal)
  double J0 = 0.0;         // 1/2 int F_exp^2 dt (trapezoidal)
  double rms = 0.0;        // sqrt(mean (F_model - F_exp)^2) over the samples
  double range = 0.0;      // max F_exp - min F_exp
  std::size_t samples = 0;
  // sqrt(J/J0); +inf if J0 == 0 and J > 0, 0 if both are 0.
  double relative_error() const;
  // 100 * rms / range (normalised RMS error in %); +inf if range == 0 < rms.
  double nrmse_percent() const;
};

// Trapezoidal quadrature weights of a time grid: int g dt ~ sum w_j g(t_j),
// w_j = (t_{j+1} - t_{j-1}) / 2 inside, half intervals at the ends. The one
// implementation of the integrals of eq. (11) and (27).
std::vector<double> trapezoid_weights(const std::vector<double> &t);

// All three vectors have the same length (>= 2) and t strictly increases.
// Throws std::invalid_argument otherwise. Samples with masked[i] != 0 (mask
// empty: none) are left out of every figure (weight 0 in the integrals).
MisfitNorms misfit_norms(const std::vector<double> &t, const std::vector<double> &F_model,
                         const std::vector<double> &F_exp,
                         const std::vector<unsigned char> &masked = {});

// sqrt(sum w_i J_i / sum w_i J0_i); weights empty = all 1.
double combined_relative_error(const std::vector<MisfitNorms> &parts,
                               const std::vector<double> &weights = {});

}  // namespace rtb

#endif
