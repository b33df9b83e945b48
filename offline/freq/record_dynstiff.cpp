// record_dynstiff.cpp -- see record_dynstiff.h.
#include "freq/record_dynstiff.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace rtb {

namespace {

struct Crossing {
  double t;     // interpolated time of the upward zero crossing
  size_t i;     // first sample at or after it
};

std::vector<Crossing> upward_crossings(const Record &r, double band) {
  std::vector<Crossing> out;
  bool armed = false;  // x has been below -band since the last crossing
  for (size_t i = 1; i < r.x.size(); ++i) {
    if (r.x[i] < -band) armed = true;
    if (armed && r.x[i - 1] < 0.0 && r.x[i] >= 0.0) {
      const double s = -r.x[i - 1] / (r.x[i] - r.x[i - 1]);
      out.push_back(Crossing{r.t[i - 1] + s * (r.t[i] - r.t[i - 1]), i});
      armed = false;
    }
  }
  return out;
}

}  // namespace

RecordDynStiff record_dynamic_stiffness(const Record &rec, const rtb_params *p,
                                        const SimOptions &sim) {
  RecordDynStiff out;
  out.path = rec.path;
  double xmax = 0.0;
  for (double v : rec.x) xmax = std::max(xmax, std::fabs(v));
  const std::vector<Crossing> c = upward_crossings(rec, 0.1 * xmax);
  // Peak |x| of each period, then the longest run at full amplitude.
  std::vector<double> peak;
  for (size_t k = 0; k + 1 < c.size(); ++k) {
    double m = 0.0;
    for (size_t i = c[k].i; i < c[k + 1].i; ++i) m = std::max(m, std::fabs(rec.x[i]));
    peak.push_back(m);
  }
  if (peak.empty())
    throw InputError(rec.path + ": no whole period of a sine found (needs two upward zero "
                                "crossings of the displacement)");
  const double top = *std::max_element(peak.begin(), peak.end());
  size_t best_a = 0, best_n = 0;
  for (size_t a = 0; a < peak.size();) {
    size_t b = a;
    while (b < peak.size() && peak[b] >= 0.95 * top) ++b;
    if (b - a > best_n) best_n = b - a, best_a = a;
    a = b > a ? b : a + 1;
  }
  const Crossing &c0 = c[best_a], &c1 = c[best_a + best_n];
  out.periods = (int)best_n;
  out.t_begin = c0.t;
  out.t_end = c1.t;
  out.freq = best_n / (c1.t - c0.t);
  const double w = 2.0 * M_PI * out.freq;
  const cplx X1 = fit_harmonic(rec.t, rec.x, w, c0.i, c1.i);
  out.amp = std::abs(X1);
  out.measured = complex_stiffness(fit_harmonic(rec.t, rec.F, w, c0.i, c1.i), X1);
  if (p) {
    const std::vector<double> F = simulate_force(*p, rec, sim);
    out.model = complex_stiffness(fit_harmonic(rec.t, F, w, c0.i, c1.i), X1);
    out.has_model = true;
  }
  return out;
}

}  // namespace rtb
