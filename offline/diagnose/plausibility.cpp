// plausibility.cpp -- see plausibility.h.
#include "diagnose/plausibility.h"

#include "diagnose/noise_floor.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rtb {

namespace {

Eigen::VectorXd predict(const ExtModel &m, const Record &rec, const MisfitOptions &opt) {
  ExtFitSpec none;
  none.free.clear();
  Eigen::VectorXd F;
  predict_extended(m, rec, opt.sim, none, F, nullptr);
  return F;
}

// Samples at the start of the record before the displacement leaves its
// initial value by more than `tol`, when that value is near 0.
size_t at_rest_prefix(const Record &rec, double tol, double xscale) {
  if (std::fabs(rec.x[0]) > 0.01 * xscale) return 0;
  size_t i = 0;
  while (i < rec.x.size() && std::fabs(rec.x[i] - rec.x[0]) <= tol) ++i;
  return i;
}

std::string offset_contradiction(const ExtModel &fitted, const std::vector<Record> &recs,
                                 const std::vector<double> &sigma) {
  double xscale = 0.0;
  for (const Record &r : recs)
    for (double x : r.x) xscale = std::max(xscale, std::fabs(x));
  int checked = 0, contradicted = 0;
  double worst = 0.0;
  for (size_t k = 0; k < recs.size(); ++k) {
    const Record &r = recs[k];
    const double s = k < sigma.size() ? sigma[k] : 0.0;
    // At rest: within the displacement sensor's noise (rest_band), else no
    // record was checked and a drifting zero passed as an offset.
    const double xtol = rest_band(r.x, xscale);
    const size_t n = at_rest_prefix(r, xtol, xscale);
    if (n < 10) continue;
    double mean = 0.0;
    for (size_t i = 0; i < n; ++i) mean += r.F[i];
    mean /= (double)n;
    ++checked;
    // At rest at x = 0 the element's force is 0: the record's zero is `mean`.
    const double tol = 3.0 * s / std::sqrt((double)n) + 0.5 * s;
    if (std::fabs(mean - fitted.offset) > tol) {
      ++contradicted;
      worst = std::max(worst, mean);
    }
  }
  if (checked == 0 || 2 * contradicted <= checked) return "";
  char b[200];
  std::snprintf(b, sizeof b,
                "contradicted by the records' at-rest segments: %d of %d start at rest with a "
                "measured zero of %.3g, not the fitted offset %.3g",
                contradicted, checked, worst, fitted.offset);
  return b;
}

// Bounds of the check (fractions of the fitted delay), from the measured
// cases (docs/diagnosis_acceptance.md, session 23): by information, the
// least-squares shift over the fitted delay is 0.31-1.12 on the true
// delays of refgen seeds 1-8 and blindgen seeds 1, 3, 5, 7 (37 checks),
// 0.19 on the own generator's delay seed 5 (below), and 0.18-0.20 on the
// two false delays seen (blindgen maxwell_s1, the own generator's Maxwell
// seed 5); the peak
// differs from the shift by at most 0.49 of it on those true delays (a
// low-pass's, not a pure shift) and by 1.76 on the Maxwell seed.
constexpr double kLagLow = 0.2, kLagHigh = 3.0, kPeakAgree = 1.0;

// One record's evidence on a time shift tau of the measured force against
// the model's prediction Fm (F_meas(t) ~ Fm(t - tau)), read off their
// cross-correlation C: `info` = sum (dFm/dt)^2 is its curvature at 0, `slope`
// = -sum (F_meas - Fm) dFm/dt its slope there (so slope / info is the
// least-squares shift, one Newton step from 0), `peak` its peak [time].
// dFm/dt is a central difference over +-k samples, k ~ half the claimed
// shift: the displacement noise the model passes into Fm has a derivative
// energy falling as 1/k^2, and on a slow record at 1 ms it would otherwise
// outweigh the signal's (a 1 Hz sine with 0.3% noise: about 4x).
struct ShiftEvidence {
  double info = 0.0, slope = 0.0, peak = 0.0;
};

ShiftEvidence shift_evidence(const Record &r, const Eigen::VectorXd &Fm, double shift) {
  const long n = (long)r.t.size();
  const double h = (r.t.back() - r.t.front()) / (double)(n - 1);
  const int k = std::max(1, (int)std::lround(0.5 * shift / h));
  ShiftEvidence e;
  for (long i = k; i + k < n; ++i) {
    const double dF = (Fm[i + k] - Fm[i - k]) / (2.0 * k * h);
    e.info += dF * dF;
    e.slope -= (r.F[(size_t)i] - Fm[i]) * dF;
  }
  e.peak = xcorr_lag(r, Fm, std::max(3, (int)std::ceil(3.0 * shift / h)));
  return e;
}

// Two readings of the records' cross-correlation with the current model:
// * per sample: each record's peak, averaged by record length (the check
//   up to session 22). Sound where the shift is long against a record's
//   time scale (a 4 ms delay on 1-3 Hz sines), but a slow record's flat
//   correlation can peak anywhere, often at the search's edge.
// * by information: the least-squares shift over all records, each counting
//   by its information on a shift, and the correlation's peak weighted
//   alike, which must agree with it (shift_evidence).
// The data contradict a delay only when both readings do. Measured (session
// 23, docs/diagnosis_acceptance.md):
// * blindgen delay_s7 (true 2.74 ms, fitted 2.75): per sample -3.7 ms (the
//   sine steps and the relaxation at -8 ms); by information 0.85 ms, its
//   peak 0.78 ms. Named; it was `unexplained`.
// * the own generator's delay seed 5 (4.0 ms; 1 and 3 Hz sines, a
//   multisine, a triangle, a step): per sample 2.2 ms; by information 0.77
//   ms, its peak 2.85 ms (the baseline's dashpots took most of the delay at
//   those frequencies). Named, as before.
// * the own generator's Maxwell seed 5, 10 s records, a 1.64 ms "delay" as
//   second cause: per sample refused; by information 0.33 ms, its peak 0.91
//   ms. Not named, as before.
std::string delay_contradiction(const ExtModel &fitted, const ExtModel &current,
                                const std::vector<Record> &recs, const MisfitOptions &opt) {
  double info = 0.0, slope = 0.0, peak = 0.0, dt = 0.0, by_sample = 0.0, samples = 0.0;
  for (const Record &r : recs) {
    dt = std::max(dt, (r.t.back() - r.t.front()) / (double)(r.t.size() - 1));
    ExtModel m = current;
    m.delay = 0.0;
    const ShiftEvidence e = shift_evidence(r, predict(m, r, opt), fitted.delay);
    info += e.info;
    slope += e.slope;
    peak += e.info * e.peak;
    by_sample += e.peak * (double)r.t.size();
    samples += (double)r.t.size();
  }
  if (!(info > 0.0) || !(samples > 0.0)) return "";
  const double lag = slope / info, lag_peak = peak / info;
  by_sample /= samples;
  // The current model has absorbed part of a true delay into its dashpots,
  // so the lag it leaves is smaller than the fitted delay; what contradicts a
  // delay is a force that does not lag at all, or lags far more. The peak
  // is refined to about a quarter of a sample: a whole sample of slack let
  // the Maxwell seed above through.
  const double res = 0.25 * dt, low = kLagLow * fitted.delay, high = kLagHigh * fitted.delay + dt;
  if (by_sample > low - dt && by_sample < high) return "";
  // A shifted force leaves a residual shaped like -tau dF/dt, and the
  // correlation then peaks where its slope at 0 points. A leftover phase
  // that is not a shift (a dashpot's, a Maxwell branch's) spreads over the
  // frequencies and the two part.
  const bool shaped_like_a_shift = std::fabs(lag_peak - lag) <= kPeakAgree * std::max(lag, res);
  if (lag > low - res && lag < high && shaped_like_a_shift) return "";
  char b[300];
  std::snprintf(b, sizeof b,
                "contradicted by the cross-correlation: the force lags the model by %.3g s averaged "
                "over the samples, by %.3g s in least squares (the correlation peaking at %.3g s), "
                "not the fitted %.3g s",
                by_sample, lag, lag_peak, fitted.delay);
  return b;
}

std::string slack_contradiction(const ExtModel &fitted, const std::vector<Record> &recs,
                                const std::vector<double> &sigma, const MisfitOptions &opt) {
  long floating = 0, total = 0, near_zero = 0;
  for (size_t k = 0; k < recs.size(); ++k) {
    const Record &r = recs[k];
    const Eigen::VectorXd F = predict(fitted, r, opt);
    double range = 0.0;
    for (double f : r.F) range = std::max(range, std::fabs(f));
    const double s = k < sigma.size() ? sigma[k] : 0.0;
    for (size_t i = 0; i < r.F.size(); ++i) {
      ++total;
      if (std::fabs(F[(Eigen::Index)i] - fitted.offset) > 1e-9 * range) continue;
      ++floating;
      if (std::fabs(r.F[i] - fitted.offset) <= 5.0 * s + 0.02 * range) ++near_zero;
    }
  }
  if (floating >= total / 200 && 2 * near_zero >= floating) return "";
  char b[200];
  std::snprintf(b, sizeof b,
                "contradicted by the records: the fitted model floats free on %ld samples, the "
                "measured force is near zero on %ld of them",
                floating, near_zero);
  return b;
}

// Largest relative drop of the static law's tangent stiffness walking from
// 0 to x_end: max over x of (the largest tangent before x - the tangent at
// x) / that largest. The law is the element's own (rtb_static_force: the K0
// path with its elastic extensions and the relaxed cell chain); the tangent
// is its slope over 1/400 of the way.
double tangent_drop(const rtb_params &p, double x_end) {
  const int n = 400;
  if (x_end == 0.0) return 0.0;
  const double h = x_end / n;
  double F_prev = rtb_static_force(&p, 0.0), top = -INFINITY, drop = 0.0;
  for (int i = 1; i <= n; ++i) {
    const double F = rtb_static_force(&p, h * i), k = (F - F_prev) / h;
    F_prev = F;
    top = std::max(top, k);
    if (top > 0.0) drop = std::max(drop, (top - k) / top);
  }
  return drop;
}

// A softening spring earns its name only if the fitted elastic law softens:
// its tangent must drop somewhere over the measured displacements. Next to a
// cubic spring it can instead reshape a curve that only stiffens (refgen
// stiffening_quintic, 3 of 4 seeds: K0 -> 0 and a tanh in its place, the
// tangent within 0.4% of monotone).
std::string softening_contradiction(const ExtModel &fitted, const std::vector<Record> &recs) {
  double lo = 0.0, hi = 0.0;
  for (const Record &r : recs)
    for (double x : r.x) lo = std::min(lo, x), hi = std::max(hi, x);
  const double drop = std::max(tangent_drop(fitted.p, hi), tangent_drop(fitted.p, lo));
  if (drop >= 0.05) return "";
  char b[220];
  std::snprintf(b, sizeof b,
                "contradicted by its own fit: the fitted elastic law does not soften over the "
                "measured displacements (largest tangent drop %.1f%%, below 5%%); it reshapes a "
                "stiffening curve",
                100.0 * drop);
  return b;
}

}  // namespace

double xcorr_lag(const Record &rec, const Eigen::VectorXd &F, int max_lag) {
  const long n = (long)rec.F.size();
  // Both forces taken from the model's start level: a preloaded record's
  // static force would otherwise make the sum a near-constant whose edge
  // terms, not the dynamics, set the peak. (For a record that starts at rest
  // at 0 this is 0. Removing the means instead moved the lags of step
  // records and refused refgen's delay seed 6, which the sum names.)
  const double F0 = F.size() > 0 ? F[0] : 0.0;
  auto corr = [&](int lag) {  // sum (F_meas[i] - F0) (F_model[i - lag] - F0)
    double s = 0.0;
    for (long i = std::max<long>(0, lag); i < n && i - lag < n; ++i)
      s += (rec.F[(size_t)i] - F0) * (F[(Eigen::Index)(i - lag)] - F0);
    return s / (double)(n - std::abs(lag));
  };
  int best = 0;
  double cb = corr(0);
  for (int l = -max_lag; l <= max_lag; ++l) {
    const double c = corr(l);
    if (c > cb) { cb = c; best = l; }
  }
  double frac = 0.0;
  if (best > -max_lag && best < max_lag) {
    const double a = corr(best - 1), b = corr(best + 1);
    const double den = a - 2.0 * cb + b;
    if (den < 0.0) frac = 0.5 * (a - b) / den;
  }
  const double h = (rec.t.back() - rec.t.front()) / (double)(n - 1);
  return (best + frac) * h;
}

// A specimen pushes when a record's force goes below both 5% of the peak
// and its own noise: 6 robust sigma of the force's fourth differences
// (masked samples, spikes among them, left out). The bare 5% rule read the
// noise's extreme as a push: blindgen slack_s59 with 10 s records at 2 kHz,
// sigma 15 N, a minimum of -65.2 N (-4.4 sigma, the tail of 20 000 samples)
// against 5% of a 1301 N peak, 65.1 N; slack was excluded and the strip
// named a clearance plus a step-like softening spring.
std::string excluded_by_data(const Candidate &c, const std::vector<Record> &recs) {
  if (c.name != "slack") return "";
  double Fmax = 0.0;
  for (const Record &r : recs)
    for (double f : r.F) Fmax = std::max(Fmax, std::fabs(f));
  double push = 0.0, at = 0.0;  // the deepest push below the bar, and its force
  for (const Record &r : recs) {
    const double bar = std::max(0.05 * Fmax, 6.0 * white_noise_sigma(r.F));
    for (size_t i = 0; i < r.F.size(); ++i)
      if ((r.masked.empty() || !r.masked[i]) && -r.F[i] - bar > push) push = -r.F[i] - bar, at = r.F[i];
  }
  if (push <= 0.0) return "";
  char b[160];
  std::snprintf(b, sizeof b, "excluded by the data: the specimen pushes (force down to %.3g of %.3g)",
                at, Fmax);
  return b;
}

std::string contradiction(const Candidate &c, const ExtModel &fitted, const ExtModel &current,
                          const std::vector<Record> &recs, const std::vector<double> &sigma,
                          const MisfitOptions &opt) {
  if (c.offset) return offset_contradiction(fitted, recs, sigma);
  // A lead (the displacement channel lags) is not checked against the
  // current model's cross-correlation: RT's dashpots imitate a lead (to
  // first order a dashpot), and the baseline over-absorbed it on refgen
  // delay_displacement (the measured force then lagged it by up to 4.5 ms
  // against a true 4.8 ms lead). It must instead beat every physical word by
  // 25% (cause_round.cpp, demote_lead_twins).
  if (c.delay && fitted.delay_lead) return "";
  if (c.delay) return delay_contradiction(fitted, current, recs, opt);
  if (c.name == "slack") return slack_contradiction(fitted, recs, sigma, opt);
  if (c.name == "softening") return softening_contradiction(fitted, recs);
  return "";
}

}  // namespace rtb
