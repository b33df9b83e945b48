// dynstiff_figure.cpp -- see dynstiff_figure.h.
#include "report/dynstiff_figure.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "report/gnuplot_figure.h"

namespace rtb {

namespace {

// Rows grouped by amplitude (a group holds amplitudes within 3% of its first).
std::vector<std::vector<DynStiffRow>> by_amplitude(std::vector<DynStiffRow> rows) {
  std::sort(rows.begin(), rows.end(), [](const DynStiffRow &a, const DynStiffRow &b) {
    return a.amp != b.amp ? a.amp < b.amp : a.freq < b.freq;
  });
  std::vector<std::vector<DynStiffRow>> g;
  for (const DynStiffRow &r : rows) {
    if (g.empty() || r.amp > 1.03 * g.back().front().amp) g.emplace_back();
    g.back().push_back(r);
  }
  for (auto &v : g)
    std::sort(v.begin(), v.end(), [](const DynStiffRow &a, const DynStiffRow &b) { return a.freq < b.freq; });
  return g;
}

std::string unit(const std::string &u) { return u.empty() ? "" : " [" + u + "]"; }

}  // namespace

void render_dynstiff_png(const std::string &png_path, const std::vector<DynStiffCurves> &sets,
                         const std::string &length_unit, const std::string &force_unit,
                         const std::string &freq_unit) {
  Figure k, d;
  k.title = "dynamic stiffness";
  d.title = "loss angle";
  k.xlabel = d.xlabel = "frequency" + unit(freq_unit);
  k.ylabel = "|K*|" + unit(force_unit.empty() || length_unit.empty() ? "" : force_unit + "/" + length_unit);
  d.ylabel = "loss angle [deg]";
  k.logx = d.logx = true;
  k.key = "outside right top vertical";  // one legend serves both panels
  d.key = "off";
  for (const DynStiffCurves &s : sets) {
    const std::vector<std::vector<DynStiffRow>> groups = by_amplitude(s.rows);
    for (size_t gi = 0; gi < groups.size(); ++gi) {
      Series sk, sd;
      char b[128];
      std::snprintf(b, sizeof b, "%s%sA = %.3g%s", s.label.c_str(), s.label.empty() ? "" : ", ",
                    groups[gi].front().amp, length_unit.empty() ? "" : (" " + length_unit).c_str());
      sk.label = sd.label = b;
      // One colour per amplitude, shared by every set.
      const std::string colour = " lc " + std::to_string(gi + 1);
      sk.style = sd.style = s.style + colour;
      for (const DynStiffRow &r : groups[gi]) {
        sk.x.push_back(r.freq);
        sk.y.push_back(r.stiffness);
        sd.x.push_back(r.freq);
        sd.y.push_back(r.loss_angle_deg);
      }
      k.series.push_back(sk);
      d.series.push_back(sd);
    }
  }
  render_png(png_path, {k, d}, 1500, 600);
}

}  // namespace rtb
