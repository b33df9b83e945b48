// noise_floor.cpp -- see noise_floor.h.
#include "diagnose/noise_floor.h"

#include <algorithm>
#include <cmath>

namespace rtb {

double white_noise_sigma(const std::vector<double> &s) {
  if (s.size() < 12) return 0.0;
  std::vector<double> d(s.size() - 4);
  for (size_t i = 0; i + 4 < s.size(); ++i)  // binomial weights 1 -4 6 -4 1
    d[i] = std::fabs(s[i] - 4.0 * s[i + 1] + 6.0 * s[i + 2] - 4.0 * s[i + 3] + s[i + 4]);
  std::nth_element(d.begin(), d.begin() + (long)(d.size() / 2), d.end());
  return 1.4826 * d[d.size() / 2] / std::sqrt(70.0);
}

double floor_error(const ExtModel &m, const std::vector<Record> &recs, const MisfitOptions &opt,
                   std::vector<double> *sigma) {
  ExtFitSpec none;
  none.free.clear();
  double Jn = 0.0, J0 = 0.0;
  for (const Record &rec : recs) {
    Eigen::VectorXd F;
    predict_extended(m, rec, opt.sim, none, F, nullptr);
    std::vector<double> e(rec.F.size());
    for (size_t j = 0; j < e.size(); ++j) e[j] = rec.F[j] - F[(Eigen::Index)j];
    const double s = white_noise_sigma(e);
    if (sigma) sigma->push_back(s);
    const std::vector<double> w = quadrature_weights(rec, opt.fit_from);
    for (size_t j = 0; j < e.size(); ++j) {
      Jn += 0.5 * w[j] * s * s;
      J0 += 0.5 * w[j] * rec.F[j] * rec.F[j];
    }
  }
  return J0 > 0.0 ? std::sqrt(Jn / J0) : 0.0;
}

NoiseFloor estimate_noise_floor(const ExtModel &m, const std::vector<Record> &fit,
                                const std::vector<Record> &holdout, const MisfitOptions &opt) {
  NoiseFloor nf;
  nf.error_fit = floor_error(m, fit, opt, &nf.sigma_fit);
  MisfitOptions all = opt;
  all.fit_from = 0.0;
  nf.error_holdout = holdout.empty() ? nf.error_fit : floor_error(m, holdout, all, &nf.sigma_holdout);
  return nf;
}

}  // namespace rtb
