// csv_out.cpp -- records as CSV in the column conventions of several rigs,
// and the scenario's truth as JSON. Every file is written to a temporary
// name and renamed, so a failure never leaves a partial file.
#include <cstdio>
#include <sstream>
#include <stdexcept>

#include "refgen.h"

namespace refgen {
namespace {

void write_atomic(const std::string &path, const std::string &text) {
  const std::string tmp = path + ".partial";
  std::FILE *f = std::fopen(tmp.c_str(), "wb");
  if (!f) throw std::runtime_error("cannot write " + tmp);
  const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
  if (std::fclose(f) != 0 || !ok || std::rename(tmp.c_str(), path.c_str()) != 0) {
    std::remove(tmp.c_str());
    throw std::runtime_error("cannot write " + path);
  }
}

std::string fmt(const char *f, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, v);
  return buf;
}

const char *kind_name(Kind k) {
  switch (k) {
    case Kind::triangle: return "triangle";
    case Kind::sine: return "sine";
    case Kind::step: return "ramp_and_hold";
    case Kind::multisine: return "multisine";
    case Kind::random: return "random";
  }
  return "?";
}

}  // namespace

// Column conventions (all accepted by the tool's CSV reader, offline/io/csv_reader.cpp):
//   0 time_s,disp_mm,force_N      1 t,x,F      2 Time (s),Displacement [mm],Force [N]
//   3 time,stroke_mm,load_N,temperature_C (an extra channel)
//   4 force_N,disp_mm,time_s (other order)
void write_record_csv(const std::string &path, const Samples &r, int style) {
  static const char *const kHeader[5] = {
      "time_s,disp_mm,force_N", "t,x,F", "Time (s),Displacement [mm],Force [N]",
      "time,stroke_mm,load_N,temperature_C", "force_N,disp_mm,time_s"};
  if (style < 0 || style > 4) throw std::invalid_argument("column style must be 0..4");
  std::string out = "# refgen record (independent reference generator)\n# units: s, mm, N\n";
  out += kHeader[style];
  out += '\n';
  for (size_t k = 0; k < r.t.size(); ++k) {
    const std::string t = fmt("%.6f", r.t[k]), x = fmt("%.7g", r.x[k]), F = fmt("%.7g", r.F[k]);
    if (style == 4) out += F + "," + x + "," + t + "\n";
    else if (style == 3) out += t + "," + x + "," + F + ",23.0\n";
    else out += t + "," + x + "," + F + "\n";
  }
  write_atomic(path, out);
}

void write_truth_json(const std::string &path, const Scenario &sc,
                      const std::vector<Samples> &records) {
  const Specimen &s = sc.specimen;
  const Chain &c = sc.chain;
  std::ostringstream o;
  o.precision(10);
  o << "{\n  \"generator\": \"refgen\",\n  \"seed\": " << sc.seed << ",\n  \"effects\": [";
  for (size_t i = 0; i < sc.effects.size(); ++i)
    o << (i ? ", " : "") << "\"" << sc.effects[i] << "\"";
  o << "],\n  \"expected\": [";
  for (size_t i = 0; i < sc.effects.size(); ++i)
    o << (i ? ", " : "") << "\"" << expected_word(sc.effects[i]) << "\"";
  o << "],\n  \"amplitude_mm\": " << sc.amplitude << ",\n  \"specimen\": {\"K0\": " << s.K0
    << ", \"Kpa\": " << s.Kpa << ", \"Kr\": " << s.Kr << ", \"C0\": " << s.C0
    << ", \"alpha\": " << s.alpha << ", \"N\": " << s.N << ", \"c0_neg_ratio\": " << s.c0_neg_ratio
    << ", \"cubic\": " << s.cubic << ", \"asym\": " << s.asym << ", \"soft_k\": " << s.soft_k
    << ", \"soft_x\": " << s.soft_x << ", \"soft_tanh\": " << (s.soft_tanh ? "true" : "false")
    << ", \"quad\": " << s.quad << ", \"quintic\": " << s.quintic
    << ", \"mullins\": " << s.mullins << ", \"mullins_erf\": " << (s.mullins_erf ? "true" : "false")
    << ", \"viscous\": " << s.viscous << ", \"mass\": " << s.mass << ", \"gap\": \""
    << (s.gap == Gap::none ? "none" : s.gap == Gap::floating ? "floating" : "held")
    << "\", \"half_gap\": " << s.half_gap << ", \"slack\": " << (s.slack ? "true" : "false")
    << ", \"drift_rate\": " << s.drift_rate << ", \"branches\": [";
  for (size_t j = 0; j < s.branches.size(); ++j)
    o << (j ? ", " : "") << "{\"k\": " << s.branches[j].k << ", \"tau\": " << s.branches[j].tau << "}";
  o << "]},\n  \"chain\": {\"servo_order\": " << c.servo_order << ", \"servo_hz\": " << c.servo_hz
    << ", \"dt\": " << c.dt << ", \"substeps\": " << c.substeps << ", \"force_noise\": "
    << c.force_noise << ", \"disp_noise\": " << c.disp_noise << ", \"delay\": " << c.delay
    << ", \"force_lowpass_hz\": " << c.force_lowpass_hz << ", \"disp_delay\": " << c.disp_delay
    << ", \"offset\": " << c.offset << ", \"zero_drift\": " << c.zero_drift << ", \"preload\": " << c.preload << ", \"force_sign\": " << c.force_sign << ", \"noise_hz\": " << c.noise_hz << ", \"hum\": " << c.hum << ", \"clip\": " << c.clip
    << ", \"spikes\": " << c.spikes << ", \"spike_rate\": " << c.spike_rate
    << ", \"column_style\": " << sc.column_style << "},\n  \"records\": [";
  std::vector<const Samples *> fit, hold;
  for (size_t i = 0; i < sc.records.size(); ++i) {
    const RecordSpec &r = sc.records[i];
    (r.holdout ? hold : fit).push_back(&records[i]);
    o << (i ? ",\n    " : "\n    ") << "{\"file\": \"" << r.name << ".csv\", \"role\": \""
      << (r.holdout ? "holdout" : "fit") << "\", \"kind\": \"" << kind_name(r.cmd.kind)
      << "\", \"amp\": " << r.cmd.amp << ", \"hz\": " << r.cmd.hz << ", \"stiffness\": " << r.stiffness
      << ", \"noise_floor\": " << noise_floor({&records[i]}) << "}";
  }
  o << "\n  ],\n  \"noise_floor_fit\": " << noise_floor(fit)
    << ",\n  \"noise_floor_holdout\": " << noise_floor(hold) << "\n}\n";
  write_atomic(path, o.str());
}

}  // namespace refgen
