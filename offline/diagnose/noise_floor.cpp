// noise_floor.cpp -- see noise_floor.h.
#include "diagnose/noise_floor.h"

#include <algorithm>
#include <cmath>

namespace rtb {

namespace {

// 1.4826 MAD of the fourth differences at lag L (binomial weights
// 1 -4 6 -4 1 on samples L apart): their standard deviation, robustly.
double d4_spread(const std::vector<double> &s, size_t L) {
  if (s.size() < 4 * L + 8) return 0.0;
  std::vector<double> d(s.size() - 4 * L);
  for (size_t i = 0; i < d.size(); ++i)
    d[i] = std::fabs(s[i] - 4.0 * s[i + L] + 6.0 * s[i + 2 * L] - 4.0 * s[i + 3 * L] + s[i + 4 * L]);
  std::nth_element(d.begin(), d.begin() + (long)(d.size() / 2), d.end());
  return 1.4826 * d[d.size() / 2];
}

// Variance of the fourth difference of unit noise with correlation a^|k|.
double q4(double a) { return 70.0 - 112.0 * a + 56.0 * a * a - 16.0 * a * a * a + 2.0 * a * a * a * a; }

}  // namespace

double white_noise_sigma(const std::vector<double> &s) {
  return s.size() < 12 ? 0.0 : d4_spread(s, 1) / std::sqrt(70.0);
}

double rest_band(const std::vector<double> &x, double scale) {
  return std::max(1e-3 * scale, 5.0 * white_noise_sigma(x));
}

namespace {

constexpr int kLags = 4;
constexpr double kBandLimitedFit = 0.02;  // log-variance scatter of a^|k| noise over the lags

// log sigma^2 fitted to the spreads m[L-1] of the fourth differences at lags
// 1..kLags for noise of correlation a^|k| (closed form: the mean of the
// per-lag values); *err gets their scatter about it.
double log_var_at(const double *m, double a, double *err) {
  double l[kLags], mean = 0.0;
  for (int L = 1; L <= kLags; ++L) {
    l[L - 1] = 2.0 * std::log(m[L - 1]) - std::log(q4(std::pow(a, L)));
    mean += l[L - 1] / kLags;
  }
  if (err) {
    *err = 0.0;
    for (double v : l) *err += (v - mean) * (v - mean);
  }
  return mean;
}

bool lag_spreads(const std::vector<double> &s, double *m) {
  for (int L = 1; L <= kLags; ++L)
    if (!((m[L - 1] = d4_spread(s, (size_t)L)) > 0.0)) return false;
  return true;
}

// 1.4826 MAD of the values themselves: noise and model error together.
double robust_spread(std::vector<double> c) {
  std::nth_element(c.begin(), c.begin() + (long)(c.size() / 2), c.end());
  const double med = c[c.size() / 2];
  for (double &v : c) v = std::fabs(v - med);
  std::nth_element(c.begin(), c.begin() + (long)(c.size() / 2), c.end());
  return 1.4826 * c[c.size() / 2];
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::nth_element(v.begin(), v.begin() + (long)(v.size() / 2), v.end());
  return v[v.size() / 2];
}

}  // namespace

double noise_correlation(const std::vector<double> &s) {
  double m[kLags];
  if (!lag_spreads(s, m)) return 0.0;
  double best_a = 0.0, best_err = INFINITY;
  for (int k = 0; k <= 80; ++k) {  // a grid search: one parameter, smooth misfit
    double err;
    log_var_at(m, 0.01 * k, &err);
    if (err < best_err) best_err = err, best_a = 0.01 * k;
  }
  // A spectral line (mains hum) also raises the spread with the lag, but
  // not as a^L does: band-limited noise fits the four lags to a scatter of
  // 0.0002-0.007 (4000 samples, corners 40-150 Hz at 1 kHz, 24 sequences),
  // a 50-60 Hz hum of 3 noise sigmas leaves 0.05-0.17 (of 1.5 sigmas
  // 0.006-0.045, with a = 0.14-0.21). Not band-limited noise: white.
  return best_err <= kBandLimitedFit ? best_a : 0.0;
}

double noise_sigma(const std::vector<double> &s, double a) {
  double m[kLags];
  if (a < kWhiteBelow || !lag_spreads(s, m)) return white_noise_sigma(s);
  // The noise is at most what the values hold: their own robust spread
  // (of noise and model error together). A residual of two noises, one
  // low-passed further (the displacement's, through stage 0's filter),
  // fits a^|k| only roughly, and the fit then overshoots (refgen
  // colored_noise_s2: 18.9 against a residual of 14.9 N rms).
  return std::min(std::exp(0.5 * log_var_at(m, a, nullptr)), robust_spread(s));
}

namespace {

// The residual of model m on each record.
std::vector<std::vector<double>> residuals(const ExtModel &m, const std::vector<Record> &recs,
                                           const MisfitOptions &opt) {
  ExtFitSpec none;
  none.free.clear();
  std::vector<std::vector<double>> out;
  for (const Record &rec : recs) {
    Eigen::VectorXd F;
    predict_extended(m, rec, opt.sim, none, F, nullptr);
    std::vector<double> e(rec.F.size());
    for (size_t j = 0; j < e.size(); ++j) e[j] = rec.F[j] - F[(Eigen::Index)j];
    out.push_back(std::move(e));
  }
  return out;
}

// The eq. (27) floor of records `recs` with residuals `e` and noise
// correlation a; sigma per record appended to *sigma.
double floor_error(const std::vector<Record> &recs, const std::vector<std::vector<double>> &e,
                   double a, double fit_from, std::vector<double> *sigma) {
  double Jn = 0.0, J0 = 0.0;
  for (size_t r = 0; r < recs.size(); ++r) {
    const double s = noise_sigma(e[r], a);
    sigma->push_back(s);
    const std::vector<double> w = quadrature_weights(recs[r], fit_from);
    for (size_t j = 0; j < w.size(); ++j) {
      Jn += 0.5 * w[j] * s * s;
      J0 += 0.5 * w[j] * recs[r].F[j] * recs[r].F[j];
    }
  }
  return J0 > 0.0 ? std::sqrt(Jn / J0) : 0.0;
}

// The median over residuals e of their noise correlation.
double median_correlation(const std::vector<std::vector<double>> &ef,
                          const std::vector<std::vector<double>> &eh) {
  std::vector<double> a;
  for (const auto *set : {&ef, &eh})
    for (const std::vector<double> &e : *set) a.push_back(noise_correlation(e));
  return median(a);
}

// The records with the recorded displacement put back; empty when it is
// theirs already (stage 0 did not filter).
std::vector<Record> as_recorded(const std::vector<Record> &recs, size_t first,
                                const std::vector<std::vector<double>> &recorded_x) {
  std::vector<Record> out;
  bool differs = false;
  for (size_t r = 0; r < recs.size(); ++r) {
    out.push_back(recs[r]);
    if (first + r >= recorded_x.size() || recorded_x[first + r].size() != recs[r].x.size())
      return {};  // not given for every record: the records' own
    differs = differs || recorded_x[first + r] != recs[r].x;
    out.back().x = recorded_x[first + r];
  }
  return differs ? out : std::vector<Record>{};
}

}  // namespace

// The correlation is the acquisition chain's, shared by every record: the
// median over the records. A model error that grows with the lag (the
// baseline's residual on a delay's step record: 0.46) is one record's, not
// the chain's, and must not raise the floor of the others.
NoiseFloor estimate_noise_floor(const ExtModel &m, const std::vector<Record> &fit,
                                const std::vector<Record> &holdout, const MisfitOptions &opt,
                                const std::vector<std::vector<double>> &recorded_x) {
  NoiseFloor nf;
  const std::vector<std::vector<double>> ef = residuals(m, fit, opt), eh = residuals(m, holdout, opt);
  double chain = median_correlation(ef, eh);
  const std::vector<Record> rf = as_recorded(fit, 0, recorded_x),
                            rh = as_recorded(holdout, fit.size(), recorded_x);
  if (!rf.empty() && (holdout.empty() || !rh.empty()))
    chain = std::max(chain, median_correlation(residuals(m, rf, opt), residuals(m, rh, opt)));
  nf.correlation = chain >= kWhiteBelow ? chain : 0.0;
  nf.error_fit = floor_error(fit, ef, nf.correlation, opt.fit_from, &nf.sigma_fit);
  nf.error_holdout = holdout.empty()
                         ? nf.error_fit
                         : floor_error(holdout, eh, nf.correlation, 0.0, &nf.sigma_holdout);
  return nf;
}

}  // namespace rtb
