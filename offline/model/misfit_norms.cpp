// misfit_norms.cpp -- see misfit_norms.h (eq. (27) of the paper).
#include "model/misfit_norms.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rtb {

namespace {
double ratio_sqrt(double num, double den) {
  if (den > 0.0) return std::sqrt(num / den);
  return num > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
}
}  // namespace

double MisfitNorms::relative_error() const { return ratio_sqrt(J, J0); }

double MisfitNorms::nrmse_percent() const {
  if (range > 0.0) return 100.0 * rms / range;
  return rms > 0.0 ? std::numeric_limits<double>::infinity() : 0.0;
}

std::vector<double> trapezoid_weights(const std::vector<double> &t) {
  const size_t n = t.size();
  std::vector<double> w(n, 0.0);
  for (size_t j = 0; j < n; ++j) {
    const double left = j > 0 ? t[j] - t[j - 1] : 0.0;
    const double right = j + 1 < n ? t[j + 1] - t[j] : 0.0;
    w[j] = 0.5 * (left + right);
  }
  return w;
}

MisfitNorms misfit_norms(const std::vector<double> &t, const std::vector<double> &F_model,
                         const std::vector<double> &F_exp,
                         const std::vector<unsigned char> &masked) {
  const size_t n = t.size();
  if (F_model.size() != n || F_exp.size() != n)
    throw std::invalid_argument("misfit_norms: time, model and measured force differ in length");
  if (n < 2) throw std::invalid_argument("misfit_norms: need at least 2 samples");
  if (!masked.empty() && masked.size() != n)
    throw std::invalid_argument("misfit_norms: mask and time differ in length");
  for (size_t i = 1; i < n; ++i)
    if (!(t[i] - t[i - 1] > 0.0)) throw std::invalid_argument("misfit_norms: time does not increase");
  const std::vector<double> w = trapezoid_weights(t);
  MisfitNorms m;
  double sum_e2 = 0.0, lo = INFINITY, hi = -INFINITY;
  for (size_t i = 0; i < n; ++i) {
    if (!masked.empty() && masked[i]) continue;
    ++m.samples;
    const double e = F_model[i] - F_exp[i], f = F_exp[i];
    m.J += 0.5 * w[i] * e * e;    // eq. (11) without the Tikhonov term
    m.J0 += 0.5 * w[i] * f * f;   // eq. (27)
    sum_e2 += e * e;
    lo = std::min(lo, f);
    hi = std::max(hi, f);
  }
  m.rms = m.samples ? std::sqrt(sum_e2 / (double)m.samples) : 0.0;
  m.range = m.samples ? hi - lo : 0.0;
  return m;
}

double combined_relative_error(const std::vector<MisfitNorms> &parts,
                               const std::vector<double> &weights) {
  if (!weights.empty() && weights.size() != parts.size())
    throw std::invalid_argument("combined_relative_error: one weight per part expected");
  double J = 0.0, J0 = 0.0;
  for (size_t i = 0; i < parts.size(); ++i) {
    const double w = weights.empty() ? 1.0 : weights[i];
    J += w * parts[i].J;
    J0 += w * parts[i].J0;
  }
  return ratio_sqrt(J, J0);
}

}  // namespace rtb
