// force_spikes.cpp -- see force_spikes.h.
#include "diagnose/force_spikes.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rtb {

namespace {
constexpr double kSpikeSigmas = 7.0;
constexpr double kQuietSigmas = 4.0;
constexpr double kMinOfRange = 0.01;
constexpr long kMinSpikes = 3;
constexpr double kMinSpikeFraction = 2e-4;

double robust_sigma(std::vector<double> e) {
  for (double &v : e) v = std::fabs(v);
  std::nth_element(e.begin(), e.begin() + (long)(e.size() / 2), e.end());
  return 1.4826 * e[e.size() / 2];
}

// The neighbour's second difference has the opposite sign at 20-80% of the
// centre's: what a one-sample excursion leaves (-1/2 of it, plus noise).
bool spike_neighbour(double centre, double side) {
  const double r = -side / centre;
  return r >= 0.2 && r <= 0.8;
}
}  // namespace

std::vector<SpikedRecord> mask_force_spikes(std::vector<Record> &recs) {
  std::vector<SpikedRecord> out;
  for (Record &rec : recs) {
    const size_t n = rec.F.size();
    if (n < 16) continue;
    const auto mm = std::minmax_element(rec.F.begin(), rec.F.end());
    const double range = *mm.second - *mm.first;
    if (!(range > 0.0)) continue;
    std::vector<double> e(n, 0.0);
    for (size_t k = 1; k + 1 < n; ++k) e[k] = rec.F[k] - 0.5 * (rec.F[k - 1] + rec.F[k + 1]);
    const double sigma = robust_sigma(std::vector<double>(e.begin() + 1, e.end() - 1));
    const double need = std::max(kSpikeSigmas * sigma, kMinOfRange * range);
    std::vector<size_t> at;
    double largest = 0.0;
    auto quiet = [&](size_t j) { return std::fabs(e[j]) <= kQuietSigmas * sigma; };
    for (size_t k = 3; k + 3 < n; ++k)
      if (std::fabs(e[k]) > need && spike_neighbour(e[k], e[k - 1]) && spike_neighbour(e[k], e[k + 1]) &&
          quiet(k - 3) && quiet(k - 2) && quiet(k + 2) && quiet(k + 3)) {
        at.push_back(k);
        largest = std::max(largest, std::fabs(e[k]));
      }
    const long min_count = std::max(kMinSpikes, (long)(kMinSpikeFraction * (double)n));
    if ((long)at.size() < min_count) continue;
    if (rec.masked.size() != n) rec.masked.assign(n, 0);
    for (size_t k : at) rec.masked[k] = 1;
    SpikedRecord s;
    s.file = rec.path;
    s.spikes = (long)at.size();
    s.largest = largest;
    s.largest_sigmas = sigma > 0.0 ? largest / sigma : INFINITY;
    out.push_back(s);
  }
  return out;
}

std::string spikes_text(const std::vector<SpikedRecord> &s, size_t n_records) {
  if (s.empty()) return "";
  long count = 0;
  double largest = 0.0, sig = 0.0;
  for (const SpikedRecord &r : s) {
    count += r.spikes;
    if (r.largest > largest) largest = r.largest, sig = r.largest_sigmas;
  }
  char b[320];
  std::snprintf(b, sizeof b,
                "the force channel has %ld isolated one-sample spikes in %zu of %zu records "
                "(largest %.4g, %.0f noise sigma; left out of the misfit): acquisition glitches, "
                "not the specimen",
                count, s.size(), n_records, largest, sig);
  return b;
}

}  // namespace rtb
