// force_clipping.cpp -- see force_clipping.h.
#include "diagnose/force_clipping.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace rtb {

namespace {
constexpr long kMinClipped = 5;
constexpr double kMinClippedFraction = 0.002;
// A quantized smooth peak also holds its top code for a while, but about as
// long as the next code below it; a clipped one holds it far longer.
constexpr double kOverNextCode = 4.0;

// Samples at the extreme value `ext` (side +1: maximum, -1: minimum), and at
// the nearest value inside it.
bool clipped_at(const std::vector<double> &F, double ext, double side, long need, long *count) {
  long at = 0, at_next = 0;
  double next = -INFINITY;  // in side-scaled units
  for (double f : F) {
    if (f == ext) { ++at; continue; }
    const double g = side * f;
    if (g > next) next = g, at_next = 1;
    else if (g == next) ++at_next;
  }
  *count = at;
  return at >= need && (double)at > kOverNextCode * (double)at_next;
}
}  // namespace

std::vector<ClippedRecord> mask_force_clipping(std::vector<Record> &recs) {
  std::vector<ClippedRecord> out;
  for (Record &rec : recs) {
    const size_t n = rec.F.size();
    if (n == 0) continue;
    const auto mm = std::minmax_element(rec.F.begin(), rec.F.end());
    const double lo = *mm.first, hi = *mm.second;
    if (!(hi > lo)) continue;  // a constant record is not clipped, it is empty
    const long need = std::max(kMinClipped, (long)(kMinClippedFraction * (double)n));
    long at_hi = 0, at_lo = 0;
    ClippedRecord c;
    c.file = rec.path;
    c.top = clipped_at(rec.F, hi, 1.0, need, &at_hi);
    c.bottom = clipped_at(rec.F, lo, -1.0, need, &at_lo);
    if (!c.top && !c.bottom) continue;
    c.level_top = hi;
    c.level_bottom = lo;
    if (rec.masked.size() != n) rec.masked.assign(n, 0);
    for (size_t i = 0; i < n; ++i)
      if ((c.top && rec.F[i] == hi) || (c.bottom && rec.F[i] == lo)) {
        rec.masked[i] = 1;
        ++c.samples;
      }
    out.push_back(c);
  }
  return out;
}

std::string clipping_text(const std::vector<ClippedRecord> &c, size_t n_records) {
  if (c.empty()) return "";
  double top = -INFINITY, bottom = INFINITY;
  bool any_top = false, any_bottom = false;
  long samples = 0;
  for (const ClippedRecord &r : c) {
    if (r.top) any_top = true, top = std::max(top, r.level_top);
    if (r.bottom) any_bottom = true, bottom = std::min(bottom, r.level_bottom);
    samples += r.samples;
  }
  char levels[96] = "";
  if (any_top && any_bottom) std::snprintf(levels, sizeof levels, "%.4g and %.4g", top, bottom);
  else std::snprintf(levels, sizeof levels, "%.4g", any_top ? top : bottom);
  char b[320];
  std::snprintf(b, sizeof b,
                "the force channel is clipped at %s in %zu of %zu records (%ld samples held at "
                "the extreme value, left out of the misfit): a saturated load cell or amplifier, "
                "not the specimen",
                levels, c.size(), n_records, samples);
  return b;
}

}  // namespace rtb
