// sts_init.cpp -- see sts_init.h.
#include "identify/sts_init.h"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>

namespace rtb {

namespace {

// Reversal points of x with a dead band (a turn counts only after x has moved
// back by `band`), so noise on the displacement cannot fake a reversal.
std::vector<size_t> reversals(const std::vector<double> &x, size_t from, double band) {
  std::vector<size_t> out;
  if (x.size() < from + 3) return out;
  int dir = 0;
  size_t ext = from;
  for (size_t i = from + 1; i < x.size(); ++i) {
    if (dir >= 0 && x[i] > x[ext]) { ext = i; if (dir == 0 && x[i] - x[from] > band) dir = 1; }
    else if (dir <= 0 && x[i] < x[ext]) { ext = i; if (dir == 0 && x[from] - x[i] > band) dir = -1; }
    if (dir == 1 && x[ext] - x[i] > band) { out.push_back(ext); dir = -1; ext = i; }
    else if (dir == -1 && x[i] - x[ext] > band) { out.push_back(ext); dir = 1; ext = i; }
  }
  return out;
}

// Least-squares polynomial through (x_i - x_rev, F_i), i in [a, b]: returns
// its value and slope at x = x_rev.
bool fit_at(const Record &r, size_t a, size_t b, double xrev, int degree, double &F0,
            double &slope) {
  const Eigen::Index n = (Eigen::Index)(b - a + 1);
  if (n < 2 * (degree + 1)) return false;
  Eigen::MatrixXd A(n, degree + 1);
  Eigen::VectorXd y(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const double u = r.x[a + k] - xrev;
    double pw = 1.0;
    for (int d = 0; d <= degree; ++d, pw *= u) A(k, d) = pw;
    y[k] = r.F[a + k];
  }
  const Eigen::VectorXd c = A.colPivHouseholderQr().solve(y);
  F0 = c[0];
  slope = c[1];
  return std::isfinite(F0) && std::isfinite(slope);
}

}  // namespace

LoopFeatures detect_loop_features(const Record &rec, double fit_from, double window) {
  size_t from = 0;
  while (from < rec.t.size() && rec.t[from] < rec.t[0] + fit_from) ++from;
  double xlo = INFINITY, xhi = -INFINITY;
  for (size_t i = from; i < rec.x.size(); ++i) {
    xlo = std::min(xlo, rec.x[i]);
    xhi = std::max(xhi, rec.x[i]);
  }
  const std::vector<size_t> rv = reversals(rec.x, from, 0.1 * (xhi - xlo));
  LoopFeatures f;
  double sTg1 = 0, sTg2 = 0, sF = 0, sX = 0, sV = 0;
  int nTg = 0;
  // A complete cycle spans three consecutive reversals; each inner branch
  // (between two reversals) gives Tg1 at its start and Tg2 at its end. Tg1
  // comes from a quadratic over `window` of the travel (the tangent turns
  // fast after a cusp); Tg2 from a quadratic over twice that (the approach
  // to a cusp is nearly straight), whose value at the reversal also gives a
  // denoised peak force.
  for (size_t k = 0; k + 2 < rv.size(); ++k) {
    const size_t r0 = rv[k], r1 = rv[k + 1], r2 = rv[k + 2];
    const double travel = std::fabs(rec.x[r1] - rec.x[r0]);
    double path = 0.0;
    for (size_t i = r0 + 1; i <= r2; ++i) path += std::fabs(rec.x[i] - rec.x[i - 1]);
    sV += path / (rec.t[r2] - rec.t[r0]);
    double Frev[2] = {0, 0};
    bool ok = true;
    int side = 0;
    for (auto [a, b] : {std::pair<size_t, size_t>{r0, r1}, {r1, r2}}) {
      size_t e = a;  // Tg1: first window of travel after reversal a
      while (e < b && std::fabs(rec.x[e] - rec.x[a]) <= window * travel) ++e;
      size_t s = b;  // Tg2: last 2 windows of travel before reversal b
      while (s > a && std::fabs(rec.x[b] - rec.x[s]) <= 2.0 * window * travel) --s;
      double F1, t1, F2, t2;
      if (fit_at(rec, a, e, rec.x[a], 2, F1, t1) && fit_at(rec, s, b, rec.x[b], 2, F2, t2)) {
        sTg1 += t1;
        sTg2 += t2;
        ++nTg;
        Frev[side] = F2;
      } else {
        ok = false;
      }
      ++side;
    }
    if (!ok) continue;
    // Half peak-to-peak between the reversal at r1 and the one at r2.
    sX += 0.5 * std::fabs(rec.x[r2] - rec.x[r1]);
    sF += 0.5 * std::fabs(Frev[1] - Frev[0]);
    ++f.cycles;
  }
  if (f.cycles == 0 || nTg == 0)
    throw InputError(rec.path + ": no complete hysteresis cycle found for the STS initial values");
  f.Tg1 = sTg1 / nTg;
  f.Tg2 = sTg2 / nTg;
  f.Xmax = sX / f.cycles;
  f.Fmax = sF / f.cycles;
  f.Ksec = f.Fmax / f.Xmax;
  f.V0 = sV / std::max(1, nTg / 2);
  return f;
}

StsParams invert_sts(const LoopFeatures &f, int N) {
  // Eq. (20) as printed gives the peak-to-peak force of the loop, not its
  // amplitude (checked by hand for N = 3 and by simulation, tests/
  // physics_test.cpp), so eq. (21)-(24) hold with peak-to-peak F and X.
  const double T1 = f.Tg1, T2 = f.Tg2, F = 2.0 * f.Fmax, X = 2.0 * f.Xmax;
  const double den = 2.0 * F - (T1 + T2) * X;
  StsParams s;
  s.K0 = (F * (T1 + T2) - 2.0 * T1 * T2 * X) / den;                           // eq. (21)
  s.Kpa = (T1 - T2) * (F - T1 * X) / den;                                      // eq. (22)
  s.Kr = -(N - 1) * (T1 - T2) * (F - T1 * X) * (F - T2 * X) / (den * den);    // eq. (23)
  s.Ff = (F - T1 * X) * (F - T2 * X) / (N * den);                              // eq. (24)
  return s;
}

// Eq. (21)-(24) are solved together: when one of them comes out negative the
// loop is no STS loop (a nearly elliptic one makes their common denominator
// small) and the others are as far off (tests/identify_test.cpp,
// StsInit.NonPhysicalInversionTakesTheFallbacksForAll). All NaN: no loop
// was inverted (sts_initial_guess's generic start).
static bool non_physical(const StsParams &s) {
  auto pos = [](double v) { return std::isfinite(v) && v > 0.0; };
  const bool inverted = !(std::isnan(s.K0) && std::isnan(s.Kpa) && std::isnan(s.Kr) && std::isnan(s.Ff));
  return inverted && !(std::isfinite(s.K0) && s.K0 >= 0.0 && pos(s.Kpa) && pos(s.Kr) && pos(s.Ff));
}

rtb_params rt_start_from_sts(const StsParams &inverted, const LoopFeatures &f, int cells,
                             double alpha0, std::string *note) {
  const bool off = non_physical(inverted);
  if (off && note) *note += "eq. (21)-(24) give a non-physical set: eq. (25) fallbacks for all; ";
  const StsParams s = off ? StsParams{NAN, NAN, NAN, NAN} : inverted;
  rtb_params p;
  rtb_params_default(&p, RTB_MODEL_RT);
  p.cells = cells;
  auto pos = [&](double v, double fallback, const char *name) {
    if (std::isfinite(v) && v > 0.0) return v;
    if (note && !off) *note += std::string(name) + " from eq. (21)-(24) not positive; ";
    return fallback;
  };
  p.K0 = std::isfinite(s.K0) && s.K0 >= 0.0 ? s.K0 : 0.5 * f.Ksec;  // eq. (25)
  p.Kpa = pos(s.Kpa, std::fmax(f.Tg1 - p.K0, 0.5 * f.Ksec), "Kpa");
  p.Kr = pos(s.Kr, cells * p.Kpa, "Kr");
  // A measured loop still gives the sliding level, the peak force that K0
  // does not carry, shared by the cells (as friction_initial_guess reads
  // it); without a loop, a tenth of the peak force.
  const double level = off ? f.Fmax - p.K0 * f.Xmax : 0.1 * f.Fmax;
  const double Ff = pos(s.Ff, level / cells, "Ff");
  p.alpha = alpha0;
  p.C0 = Ff / std::pow(std::fmax(f.V0, 1e-300), alpha0);  // eq. (26)
  return p;
}

rtb_params sts_initial_guess(const std::vector<Record> &recs, int cells, double alpha0,
                             double fit_from, LoopFeatures *feat, StsParams *sts,
                             std::string *note) {
  // Use the record whose stabilized loop is largest (the STS inversion assumes
  // N-1 cells sliding, i.e. a large amplitude).
  LoopFeatures best;
  bool have = false;
  std::string why;
  for (const Record &r : recs) {
    try {
      const LoopFeatures f = detect_loop_features(r, fit_from);
      if (!have || f.Xmax > best.Xmax) best = f;
      have = true;
    } catch (const InputError &e) {
      why = e.what();
    }
  }
  StsParams s;
  if (!have) {
    // Single ramps, load-unload records, relaxation tests: no loop to invert.
    // A generic start from the secant stiffness instead (the NaN STS values
    // take rt_start_from_sts's fallbacks: K0 = Ksec/2, Kpa = Tg1 - K0, ...).
    double sv = 0.0, n = 0.0;
    for (const Record &r : recs)
      for (size_t i = 0; i < r.t.size(); ++i) {
        best.Fmax = std::fmax(best.Fmax, std::fabs(r.F[i]));
        best.Xmax = std::fmax(best.Xmax, std::fabs(r.x[i]));
        if (i > 0) {
          sv += std::fabs(r.x[i] - r.x[i - 1]);
          n += r.t[i] - r.t[i - 1];
        }
      }
    if (!(best.Fmax > 0.0 && best.Xmax > 0.0 && sv > 0.0))
      throw InputError("initial values: the records neither move nor load (" + why + ")");
    best.Ksec = best.Fmax / best.Xmax;
    best.Tg1 = 3.0 * best.Ksec;
    best.Tg2 = 0.5 * best.Ksec;
    best.V0 = sv / n;
    s.K0 = s.Kpa = s.Kr = s.Ff = NAN;
    if (note) *note += "no complete cycle in any record (" + why + "): generic start from the secant stiffness; ";
  } else {
    s = invert_sts(best, cells);
  }
  if (feat) *feat = best;
  if (sts) *sts = s;
  return rt_start_from_sts(s, best, cells, alpha0, note);
}

rtb_params friction_initial_guess(const rtb_params &sts_start, const LoopFeatures &f) {
  rtb_params p = sts_start;
  const double alpha = 0.02;  // rate-independent to within 2% per decade of velocity
  p.K0 = std::fmax(f.Tg2, 0.0);
  p.Kpa = std::fmax(f.Tg1 - p.K0, 0.5 * f.Ksec);
  p.Kr = 1e-3 * p.Kpa;
  const double level = f.Fmax - p.K0 * f.Xmax;
  p.alpha = alpha;
  p.C0 = (level > 0.0 ? level : 0.5 * f.Fmax) / std::pow(std::fmax(f.V0, 1e-300), alpha);
  return p;
}

rtb_params friction_initial_guess(const std::vector<Record> &recs, int cells, double fit_from) {
  LoopFeatures f;
  const rtb_params sts = sts_initial_guess(recs, cells, 0.2, fit_from, &f);
  return friction_initial_guess(sts, f);
}

}  // namespace rtb
