// noise_floor.h -- how small the residual can get: the white-noise level of
// the measurement, estimated from the data itself.
//
// The baseline residual e = F_measured - F_model carries (a) the model's
// error, smooth in time like the input, and (b) white noise: the force
// sensor's and the displacement sensor's (the model, driven by a noisy x,
// returns K x_noise). Fourth differences of e remove (a) -- a component at
// frequency f is scaled by (2 sin(pi f dt))^4, 1e-3 at f = fs/30 -- and keep
// (b) with variance 70 sigma^2, so sigma = 1.4826 MAD(d4 e) / sqrt(70);
// the median ignores the few large differences at input corners or steps.
// The floor is the eq. (27) error that noise alone would give on a set of
// records: sqrt(sum_r w_r sigma_r^2 T_r / (2 J0)).
#ifndef RTB_OFFLINE_NOISE_FLOOR_H
#define RTB_OFFLINE_NOISE_FLOOR_H

#include <vector>

#include "diagnose/extended_fit.h"

namespace rtb {

// Robust white-noise standard deviation of uniformly sampled values.
double white_noise_sigma(const std::vector<double> &s);

struct NoiseFloor {
  std::vector<double> sigma_fit, sigma_holdout;  // per record [force]
  double error_fit = 0.0, error_holdout = 0.0;   // eq. (27) floor of each set
};

// The floor of model m's residual on each set (holdout may be empty).
NoiseFloor estimate_noise_floor(const ExtModel &m, const std::vector<Record> &fit,
                                const std::vector<Record> &holdout, const MisfitOptions &opt);

// sigma of each record's residual under model m and the set's eq. (27) floor.
double floor_error(const ExtModel &m, const std::vector<Record> &recs, const MisfitOptions &opt,
                   std::vector<double> *sigma);

}  // namespace rtb

#endif
