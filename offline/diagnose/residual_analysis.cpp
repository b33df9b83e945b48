// residual_analysis.cpp -- see residual_analysis.h.
#include "diagnose/residual_analysis.h"

#include <algorithm>
#include <cmath>

namespace rtb {

namespace {

double rms_of(const std::vector<double> &e, const std::vector<char> &mask, char want) {
  double s = 0;
  long n = 0;
  for (size_t i = 0; i < e.size(); ++i)
    if (mask[i] == want) {
      s += e[i] * e[i];
      ++n;
    }
  return n ? std::sqrt(s / n) : 0.0;
}

RecordResiduals analyze_one(const ExtModel &m, const Record &rec, bool holdout,
                            const MisfitOptions &opt) {
  RecordResiduals out;
  out.path = rec.path;
  out.holdout = holdout;
  ExtFitSpec none;
  none.free.clear();
  Eigen::VectorXd F;
  predict_extended(m, rec, opt.sim, none, F, nullptr);
  const size_t n = rec.t.size();
  const std::vector<double> w = quadrature_weights(rec, opt.fit_from);
  std::vector<double> e(n), v(n, 0.0), a(n, 0.0), dF(n, 0.0);
  double J = 0, J0 = 0, sw = 0, se = 0;
  for (size_t i = 0; i < n; ++i) {
    e[i] = rec.F[i] - F[(Eigen::Index)i];
    J += w[i] * e[i] * e[i];
    J0 += w[i] * rec.F[i] * rec.F[i];
    sw += w[i];
    se += w[i] * e[i];
  }
  out.error = J0 > 0 ? std::sqrt(J / J0) : 0;
  out.rms = sw > 0 ? std::sqrt(J / sw) : 0;
  out.mean = sw > 0 ? se / sw : 0;
  for (size_t i = 1; i + 1 < n; ++i) {
    const double h0 = rec.t[i] - rec.t[i - 1], h1 = rec.t[i + 1] - rec.t[i];
    v[i] = (rec.x[i + 1] - rec.x[i - 1]) / (h0 + h1);
    a[i] = 2.0 * ((rec.x[i + 1] - rec.x[i]) / h1 - (rec.x[i] - rec.x[i - 1]) / h0) / (h0 + h1);
    dF[i] = (F[(Eigen::Index)i + 1] - F[(Eigen::Index)i - 1]) / (h0 + h1);
  }
  struct Feat {
    const char *name;
    std::vector<double> f;
  };
  std::vector<Feat> feats = {{"x", rec.x}, {"v", v}, {"a", a}, {"|x|", {}}, {"x^3", {}},
                             {"sign(v)", {}}, {"F_model", {}}, {"dF_model/dt", dF},
                             {"constant", std::vector<double>(n, 1.0)}};
  for (size_t i = 0; i < n; ++i) {
    feats[3].f.push_back(std::fabs(rec.x[i]));
    feats[4].f.push_back(rec.x[i] * rec.x[i] * rec.x[i]);
    feats[5].f.push_back(v[i] > 0 ? 1.0 : (v[i] < 0 ? -1.0 : 0.0));
    feats[6].f.push_back(F[(Eigen::Index)i]);
  }
  for (const Feat &ft : feats) {
    double sff = 0, sef = 0, sf = 0;
    for (size_t i = 0; i < n; ++i) {
      sff += w[i] * ft.f[i] * ft.f[i];
      sef += w[i] * e[i] * ft.f[i];
      sf += w[i] * ft.f[i];
    }
    Signature s;
    s.name = ft.name;
    if (sff > 0 && J > 0) {
      s.coefficient = sef / sff;
      s.explained = sef * sef / (sff * J);
      const double mf = sf / sw, me = se / sw;
      const double cov = sef / sw - mf * me, vf = sff / sw - mf * mf, ve = J / sw - me * me;
      s.correlation = (vf > 0 && ve > 0) ? cov / std::sqrt(vf * ve) : 0.0;
    }
    if (s.name == "dF_model/dt") out.delay_estimate = -s.coefficient;  // e ~ -d dF/dt
    out.signatures.push_back(s);
  }
  std::sort(out.signatures.begin(), out.signatures.end(),
            [](const Signature &p, const Signature &q) { return p.explained > q.explained; });
  // Where: first loading (|x| at its running maximum), near reversals
  // (within 5% of the peak-to-peak travel after a velocity sign change).
  double xmax = 0, lo = INFINITY, hi = -INFINITY;
  for (double x : rec.x) {
    lo = std::min(lo, x);
    hi = std::max(hi, x);
  }
  const double band = 0.05 * (hi - lo);
  std::vector<char> first(n, 0), nearrev(n, 0), quad(n, 0);
  double xrev = rec.x[0];
  int dir = 0;
  for (size_t i = 0; i < n; ++i) {
    const double ax = std::fabs(rec.x[i]);
    if (ax >= xmax) {
      first[i] = 1;
      xmax = ax;
    }
    const int d = v[i] > 0 ? 1 : (v[i] < 0 ? -1 : dir);
    if (d != dir && i > 0) xrev = rec.x[i];
    dir = d;
    nearrev[i] = std::fabs(rec.x[i] - xrev) < band ? 1 : 0;
    quad[i] = (char)((rec.x[i] >= 0 ? 0 : 2) + (v[i] >= 0 ? 0 : 1));
  }
  out.rms_first_loading = rms_of(e, first, 1);
  out.rms_later = rms_of(e, first, 0);
  out.rms_near_reversal = rms_of(e, nearrev, 1);
  out.rms_elsewhere = rms_of(e, nearrev, 0);
  for (int q = 0; q < 4; ++q) out.rms_quadrant[q] = rms_of(e, quad, (char)q);
  // When: RMS per tenth of the record's duration.
  std::vector<char> dec(n);
  const double T = rec.t.back() - rec.t.front();
  for (size_t i = 0; i < n; ++i)
    dec[i] = (char)std::min(9, (int)(10.0 * (rec.t[i] - rec.t.front()) / (T > 0 ? T : 1)));
  for (int d = 0; d < 10; ++d) out.rms_time_decile.push_back(rms_of(e, dec, (char)d));
  return out;
}

}  // namespace

std::vector<RecordResiduals> analyze_residuals(const ExtModel &m, const std::vector<Record> &fit,
                                               const std::vector<Record> &holdout,
                                               const MisfitOptions &opt) {
  std::vector<RecordResiduals> out;
  for (const Record &r : fit) out.push_back(analyze_one(m, r, false, opt));
  MisfitOptions all = opt;
  all.fit_from = 0.0;
  for (const Record &r : holdout) out.push_back(analyze_one(m, r, true, all));
  return out;
}

nlohmann::ordered_json residuals_json(const std::vector<RecordResiduals> &rs) {
  nlohmann::ordered_json a = nlohmann::ordered_json::array();
  for (const RecordResiduals &r : rs) {
    nlohmann::ordered_json j;
    j["path"] = r.path;
    j["role"] = r.holdout ? "holdout" : "fit";
    j["error"] = r.error;
    j["rms"] = r.rms;
    j["mean"] = r.mean;
    nlohmann::ordered_json sig = nlohmann::ordered_json::array();
    for (const Signature &s : r.signatures)
      sig.push_back({{"feature", s.name}, {"explained", s.explained},
                     {"correlation", s.correlation}, {"coefficient", s.coefficient}});
    j["signatures"] = sig;
    j["delay_estimate"] = r.delay_estimate;
    j["rms_first_loading"] = r.rms_first_loading;
    j["rms_later_cycles"] = r.rms_later;
    j["rms_near_reversal"] = r.rms_near_reversal;
    j["rms_elsewhere"] = r.rms_elsewhere;
    j["rms_quadrant"] = {{"loading_x_pos", r.rms_quadrant[0]}, {"unloading_x_pos", r.rms_quadrant[1]},
                         {"loading_x_neg", r.rms_quadrant[2]}, {"unloading_x_neg", r.rms_quadrant[3]}};
    j["rms_time_decile"] = r.rms_time_decile;
    a.push_back(j);
  }
  return a;
}

}  // namespace rtb
