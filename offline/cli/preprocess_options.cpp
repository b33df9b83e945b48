// preprocess_options.cpp -- the command-line face of preprocess/: the
// options shared by identify, validate and diagnose.
#include <cmath>
#include <cstdio>

#include "cli/fit_common.h"

namespace rtb {
namespace cli {

std::vector<OptionSpec> preprocess_option_specs() {
  return {
      {"scale-time", "F", "multiply the time column by F (default 1)"},
      {"scale-displacement", "F", "multiply the displacement column by F (e.g. 25.4: in -> mm)"},
      {"scale-force", "F", "multiply the force column by F (e.g. 4.44822: kip -> kN)"},
      {"force-sign", "auto|1|-1",
       "sign convention of the force: -1 flips it (a compression-positive load cell); auto "
       "(default) flips it when the fit records' force falls as the displacement rises"},
      {"lowpass", "HZ", "zero-phase low-pass of the force (2nd-order Butterworth, forward-backward)"},
      {"decimate", "K", "keep every K-th sample after --lowpass: fit at the rate the element runs"},
      {"mask", "T0:T1", "leave t0+T0..t0+T1 s of every record out of the misfit", false, true},
      {"mask-reversals", "S", "leave S s after every displacement reversal out of the misfit"},
      {"weight", "W", "misfit weight of the matching --data file (give one per file)", false, true},
  };
}

CommandSpec with_preprocess_options(CommandSpec spec) {
  const std::vector<OptionSpec> pre = preprocess_option_specs();
  spec.options.insert(spec.options.end(), pre.begin(), pre.end());
  return spec;
}

Preprocess preprocess_from(const Args &a) {
  Preprocess pp;
  auto positive = [&](const char *name, double &v) {
    if (!a.has(name)) return;
    v = a.get_double(name, v);
    if (!(v > 0.0 && std::isfinite(v))) throw UsageError(std::string("--") + name + " must be > 0");
  };
  positive("scale-time", pp.time_scale);
  positive("scale-displacement", pp.disp_scale);
  positive("scale-force", pp.force_scale);
  positive("lowpass", pp.lowpass_hz);
  positive("mask-reversals", pp.mask_after_reversal);
  if (a.has("force-sign")) {
    const std::string s = a.get("force-sign");
    if (s == "auto") pp.force_sign = 0;
    else if (s == "1" || s == "+1") pp.force_sign = 1;
    else if (s == "-1") pp.force_sign = -1;
    else throw UsageError("--force-sign must be auto, 1 or -1 (got '" + s + "')");
  }
  if (a.has("decimate")) {
    const double k = a.get_double("decimate", 1.0);
    if (!(k >= 1.0 && k <= 1000.0 && k == std::floor(k)))
      throw UsageError("--decimate must be an integer from 1 to 1000");
    pp.decimate = (int)k;
  }
  if (a.has("mask"))
    for (const std::string &s : a.all("mask")) pp.masks.push_back(parse_time_window(s, "--mask"));
  if (a.has("weight"))
    for (const std::string &s : a.all("weight")) {
      char *end = nullptr;
      const double w = std::strtod(s.c_str(), &end);
      if (end == s.c_str() || *end != '\0' || !(w >= 0.0) || !std::isfinite(w))
        throw UsageError("--weight must be a finite number >= 0, got '" + s + "'");
      pp.weights.push_back(w);
    }
  return pp;
}

void resolve_force_sign(Preprocess &pp, const std::vector<Record> &fit, bool quiet) {
  if (pp.force_sign != 0) return;
  double corr = 0.0;
  pp.force_sign = force_sign_of(fit, &corr);
  if (pp.force_sign < 0 && !quiet)
    std::fprintf(stderr,
                 "note: the force falls as the displacement rises in the fit records "
                 "(correlation %.2f): read as a compression-positive load cell, the force's sign "
                 "is flipped (--force-sign 1 keeps it)\n",
                 corr);
}

}  // namespace cli
}  // namespace rtb
