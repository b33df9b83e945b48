// preprocess.cpp -- see preprocess.h.
#include "preprocess/preprocess.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

namespace rtb {

bool Preprocess::active() const {
  return time_scale != 1.0 || disp_scale != 1.0 || force_scale != 1.0 || force_sign < 0 ||
         lowpass_hz > 0.0 ||
         decimate > 1 || !masks.empty() || mask_after_reversal > 0.0 || !weights.empty();
}

TimeWindow parse_time_window(const std::string &s, const std::string &option) {
  const size_t c = s.find(':');
  TimeWindow w;
  char *e0 = nullptr, *e1 = nullptr;
  if (c != std::string::npos) {
    const std::string a = s.substr(0, c), b = s.substr(c + 1);
    w.t0 = std::strtod(a.c_str(), &e0);
    w.t1 = std::strtod(b.c_str(), &e1);
    if (!a.empty() && !b.empty() && *e0 == '\0' && *e1 == '\0' && std::isfinite(w.t0) &&
        std::isfinite(w.t1) && w.t1 >= w.t0)
      return w;
  }
  throw InputError(option + ": expected T0:T1 in seconds with T0 <= T1, got '" + s + "'");
}

std::vector<size_t> displacement_reversals(const std::vector<double> &x, double band) {
  std::vector<size_t> rev;
  if (x.size() < 3) return rev;
  // dir: +1 rising, -1 falling, 0 not yet known; ext = running extreme.
  int dir = 0;
  size_t ext = 0;
  for (size_t i = 1; i < x.size(); ++i) {
    if (dir >= 0 && x[i] > x[ext]) { ext = i; if (dir == 0 && x[i] - x[0] > band) dir = 1; }
    else if (dir <= 0 && x[i] < x[ext]) { ext = i; if (dir == 0 && x[0] - x[i] > band) dir = -1; }
    if (dir == 1 && x[ext] - x[i] > band) { rev.push_back(ext); dir = -1; ext = i; }
    else if (dir == -1 && x[i] - x[ext] > band) { rev.push_back(ext); dir = 1; ext = i; }
  }
  return rev;
}

namespace {

// 2nd-order Butterworth low-pass by the bilinear transform with pre-warping,
// transposed direct form II, started in its steady state for the first input
// (no start-up transient for a record that begins at a constant force).
// Q = 1/sqrt(2) is the whole 2nd-order filter; a 4th-order Butterworth is
// the cascade Q = 0.5412, 1.3066 (poles at 22.5 and 67.5 degrees).
struct Biquad {
  double b0, b1, b2, a1, a2;
  Biquad(double dt, double fc, double Q = M_SQRT1_2) {
    const double K = std::tan(M_PI * fc * dt), K2 = K * K, r2 = 1.0 / Q;
    const double n = 1.0 / (1.0 + r2 * K + K2);
    b0 = K2 * n;
    b1 = 2.0 * b0;
    b2 = b0;
    a1 = 2.0 * (K2 - 1.0) * n;
    a2 = (1.0 - r2 * K + K2) * n;
  }
  void run(std::vector<double> &y) const {
    double z1 = (1.0 - b0) * y[0], z2 = (b2 - a2) * y[0];  // steady state, DC gain 1
    for (double &v : y) {
      const double u = v, out = b0 * u + z1;
      z1 = b1 * u - a1 * out + z2;
      z2 = b2 * u - a2 * out;
      v = out;
    }
  }
};

}  // namespace

std::vector<double> lowpass_zero_phase(const std::vector<double> &y, double dt, double fc,
                                       int order) {
  const size_t n = y.size();
  if (n < 2 || !(fc > 0.0)) return y;
  // Odd reflection at both ends (2 y0 - y[k]) over ~3 time constants of the
  // filter, so the forward-backward pass has no end transients.
  const size_t pad = std::min(n - 1, (size_t)std::ceil((order == 4 ? 5.0 : 3.0) / (fc * dt)));
  std::vector<double> e;
  e.reserve(n + 2 * pad);
  for (size_t k = pad; k >= 1; --k) e.push_back(2.0 * y[0] - y[k]);
  e.insert(e.end(), y.begin(), y.end());
  for (size_t k = 1; k <= pad; ++k) e.push_back(2.0 * y[n - 1] - y[n - 1 - k]);
  const std::vector<Biquad> sections =
      order == 4 ? std::vector<Biquad>{Biquad(dt, fc, 0.54119610014619698),
                                       Biquad(dt, fc, 1.3065629648763766)}
                 : std::vector<Biquad>{Biquad(dt, fc)};
  for (int pass = 0; pass < 2; ++pass) {
    for (const Biquad &f : sections) f.run(e);
    std::reverse(e.begin(), e.end());
  }
  return std::vector<double>(e.begin() + (long)pad, e.begin() + (long)(pad + n));
}

namespace {

void lowpass_record(Record &r, double fc) {
  std::vector<double> h(r.t.size() - 1);
  for (size_t i = 0; i + 1 < r.t.size(); ++i) h[i] = r.t[i + 1] - r.t[i];
  std::vector<double> s = h;
  std::nth_element(s.begin(), s.begin() + (long)(s.size() / 2), s.end());
  const double dt = s[s.size() / 2];
  for (size_t i = 0; i < h.size(); ++i)
    if (std::fabs(h[i] - dt) > 0.05 * dt)
      throw InputError(r.path + ": --lowpass needs a uniform time grid, but the step at t = " +
                       std::to_string(r.t[i]) + " s is " + std::to_string(h[i]) +
                       " s against a median of " + std::to_string(dt) + " s");
  if (!(fc < 0.5 / dt))
    throw InputError(r.path + ": --lowpass cut-off must be below the Nyquist frequency " +
                     std::to_string(0.5 / dt) + " Hz");
  r.F = lowpass_zero_phase(r.F, dt, fc);
}

// Every k-th sample from the first. The force must already be band-limited
// below the new Nyquist frequency, or decimation would alias.
void decimate_record(Record &r, int k, double lowpass_hz) {
  const double dt_new = k * (r.t.back() - r.t.front()) / (double)(r.t.size() - 1);
  if (!(lowpass_hz > 0.0 && lowpass_hz < 0.5 / dt_new))
    throw InputError(r.path + ": --decimate " + std::to_string(k) + " gives " +
                     std::to_string(1.0 / dt_new) + " Hz; it needs --lowpass below its Nyquist "
                     "frequency " + std::to_string(0.5 / dt_new) + " Hz (no aliasing)");
  Record d = r;
  d.t.clear();
  d.x.clear();
  d.F.clear();
  d.masked.clear();
  for (size_t i = 0; i < r.t.size(); i += (size_t)k) {
    d.t.push_back(r.t[i]);
    d.x.push_back(r.x[i]);
    d.F.push_back(r.F[i]);
    if (!r.masked.empty()) d.masked.push_back(r.masked[i]);
  }
  if ((int)d.t.size() < kMinSamples)
    throw InputError(r.path + ": --decimate " + std::to_string(k) + " leaves fewer than " +
                     std::to_string(kMinSamples) + " samples");
  r = std::move(d);
}

void mask_window(Record &r, double t0, double t1) {
  const double ts = r.t.front();
  for (size_t i = 0; i < r.t.size(); ++i)
    if (r.t[i] - ts >= t0 && r.t[i] - ts <= t1) r.masked[i] = 1;
}

}  // namespace

int force_sign_of(const std::vector<Record> &recs, double *corr) {
  double sxf = 0.0, sxx = 0.0, sff = 0.0;
  for (const Record &r : recs) {
    const size_t n = std::min(r.x.size(), r.F.size());
    if (n == 0) continue;
    double mx = 0.0, mf = 0.0;
    for (size_t i = 0; i < n; ++i) mx += r.x[i], mf += r.F[i];
    mx /= (double)n;
    mf /= (double)n;
    for (size_t i = 0; i < n; ++i) {
      const double dx = r.x[i] - mx, df = r.F[i] - mf;
      sxf += dx * df;
      sxx += dx * dx;
      sff += df * df;
    }
  }
  const double c = sxx > 0.0 && sff > 0.0 ? sxf / std::sqrt(sxx * sff) : 0.0;
  if (corr) *corr = c;
  return c < -0.2 ? -1 : 1;
}

void apply_preprocess(const Preprocess &pp, std::vector<Record> &recs, bool use_weights) {
  if (use_weights && !pp.weights.empty() && pp.weights.size() != recs.size())
    throw InputError("--weight given " + std::to_string(pp.weights.size()) +
                     " time(s) for " + std::to_string(recs.size()) + " --data file(s): give one per file");
  for (size_t k = 0; k < recs.size(); ++k) {
    Record &r = recs[k];
    for (double &v : r.t) v *= pp.time_scale;
    for (double &v : r.x) v *= pp.disp_scale;
    const double fs = pp.force_sign < 0 ? -pp.force_scale : pp.force_scale;
    for (double &v : r.F) v *= fs;
    if (pp.lowpass_hz > 0.0) lowpass_record(r, pp.lowpass_hz);
    if (pp.decimate > 1) decimate_record(r, pp.decimate, pp.lowpass_hz);
    if (!pp.masks.empty() || pp.mask_after_reversal > 0.0) {
      r.masked.assign(r.t.size(), 0);
      for (const TimeWindow &w : pp.masks) mask_window(r, w.t0, w.t1);
      if (pp.mask_after_reversal > 0.0) {
        const auto mm = std::minmax_element(r.x.begin(), r.x.end());
        const double t0 = r.t.front();
        for (size_t i : displacement_reversals(r.x, 0.01 * (*mm.second - *mm.first)))
          mask_window(r, r.t[i] - t0, r.t[i] - t0 + pp.mask_after_reversal);
      }
      if (std::count(r.masked.begin(), r.masked.end(), 0) < kMinSamples)
        throw InputError(r.path + ": the masks leave fewer than " + std::to_string(kMinSamples) +
                         " samples in the misfit");
    }
    if (use_weights && !pp.weights.empty()) r.weight = pp.weights[k];
  }
}

nlohmann::ordered_json preprocess_json(const Preprocess &pp) {
  nlohmann::ordered_json j;
  j["time_scale"] = pp.time_scale;
  j["displacement_scale"] = pp.disp_scale;
  j["force_scale"] = pp.force_scale;
  j["force_sign"] = pp.force_sign < 0 ? -1 : 1;
  j["lowpass_hz"] = pp.lowpass_hz;
  j["lowpass"] = pp.lowpass_hz > 0.0 ? "2nd-order Butterworth, forward-backward (zero phase)" : "off";
  j["decimate"] = pp.decimate;
  nlohmann::ordered_json m = nlohmann::ordered_json::array();
  for (const TimeWindow &w : pp.masks) m.push_back({w.t0, w.t1});
  j["masks_s"] = m;
  j["mask_after_reversal_s"] = pp.mask_after_reversal;
  j["weights"] = pp.weights;
  return j;
}

}  // namespace rtb
