// params_json.cpp -- parameter files (format in rtb_offline.h).
//
// {"model":"rt"|"sts", "cells":15, "integrator":"sdirk2"|"be", "smoothing":s,
//  "params":{"K0":..,"Kpa":..,"Kr":..,"C0":..,"alpha":.., extensions..., "Ff":..}}
// "smoothing" (eq. (14), >= 0, [1/velocity]) is a model setting like the
// integrator, not an identified parameter: optional, absent = 0 = off, and
// written only when nonzero (so unsmoothed files are unchanged).
// Errors are InputError("FILE: ..."), naming the offending key; the last check
// is rtb_params_validate itself, so a file accepted here is accepted by the
// real-time library.
#include "io/params_json.h"

#include <cmath>
#include <cstdio>
#include <string>

#include "io/atomic_file.h"

namespace rtb {
namespace {

struct Key {
  const char *name;
  double rtb_params::*field;
  enum Rule { positive, nonneg, any, alpha, fraction } rule;
};

// Every numeric key of "params", in output order.
const Key kKeys[] = {
    {"K0", &rtb_params::K0, Key::nonneg},
    {"Kpa", &rtb_params::Kpa, Key::positive},
    {"Kr", &rtb_params::Kr, Key::positive},
    {"C0", &rtb_params::C0, Key::positive},
    {"alpha", &rtb_params::alpha, Key::alpha},
    {"Ff", &rtb_params::Ff, Key::positive},
    {"k3", &rtb_params::k3, Key::any},
    {"k_asym", &rtb_params::k_asym, Key::any},
    {"maxwell_k", &rtb_params::maxwell_k, Key::nonneg},
    {"maxwell_tau", &rtb_params::maxwell_tau, Key::nonneg},
    {"viscous_c", &rtb_params::viscous_c, Key::nonneg},
    {"mass", &rtb_params::mass, Key::nonneg},
    {"backlash", &rtb_params::backlash, Key::nonneg},
    {"mullins", &rtb_params::mullins, Key::fraction},
    {"sat_force", &rtb_params::sat_force, Key::nonneg},
    {"sat_disp", &rtb_params::sat_disp, Key::nonneg},
};

bool required(const Key &k, int model) {
  const std::string n = k.name;
  if (n == "K0" || n == "Kpa" || n == "Kr") return true;
  if (model == RTB_MODEL_RT) return n == "C0" || n == "alpha";
  return n == "Ff";
}

std::string num(double v) {
  char buf[40];
  std::snprintf(buf, sizeof buf, "%.17g", v);
  return buf;
}

std::string type_name(const nlohmann::json &j) { return j.type_name(); }

}  // namespace

const char *model_name(int model) {
  return model == RTB_MODEL_RT ? "rt" : model == RTB_MODEL_STS ? "sts" : "?";
}
const char *integrator_name(int integrator) {
  return integrator == RTB_INTEGRATOR_SDIRK2 ? "sdirk2"
         : integrator == RTB_INTEGRATOR_BE   ? "be"
                                             : "?";
}

rtb_params params_from_json(const nlohmann::json &doc, const std::string &origin) {
  auto fail = [&](const std::string &what) -> void { throw InputError(origin + ": " + what); };
  if (!doc.is_object()) fail("expected a JSON object at the top level, found " + type_name(doc));

  rtb_params p;
  rtb_params_default(&p, RTB_MODEL_RT);
  // Start from zero: only what the file says (or the documented defaults).
  for (const Key &k : kKeys) p.*(k.field) = 0.0;

  // model
  if (!doc.contains("model")) fail("missing key \"model\" (\"rt\" or \"sts\")");
  const nlohmann::json &jm = doc["model"];
  if (!jm.is_string()) fail("\"model\" must be a string (\"rt\" or \"sts\"), found " + type_name(jm));
  const std::string m = jm.get<std::string>();
  if (m == "rt" || m == "RT")
    p.model = RTB_MODEL_RT;
  else if (m == "sts" || m == "STS")
    p.model = RTB_MODEL_STS;
  else
    fail("\"model\": unknown model \"" + m + "\" (expected \"rt\" or \"sts\")");

  // cells
  p.cells = RTB_DEFAULT_CELLS;
  if (doc.contains("cells")) {
    const nlohmann::json &jc = doc["cells"];
    double c = 0.0;
    if (jc.is_number()) c = jc.get<double>();
    if (!jc.is_number() || c != std::floor(c))
      fail("\"cells\" must be an integer, found " + jc.dump());
    if (c < 1 || c > RTB_MAX_CELLS)
      fail("\"cells\" = " + jc.dump() + " is outside 1.." + std::to_string(RTB_MAX_CELLS));
    p.cells = (int)c;
  }

  // integrator
  p.integrator = RTB_INTEGRATOR_SDIRK2;
  if (doc.contains("integrator")) {
    const nlohmann::json &ji = doc["integrator"];
    if (!ji.is_string()) fail("\"integrator\" must be a string (\"sdirk2\" or \"be\")");
    const std::string s = ji.get<std::string>();
    if (s == "sdirk2")
      p.integrator = RTB_INTEGRATOR_SDIRK2;
    else if (s == "be")
      p.integrator = RTB_INTEGRATOR_BE;
    else
      fail("\"integrator\": unknown integrator \"" + s + "\" (expected \"sdirk2\" or \"be\")");
  }

  // smoothing, eq. (14)
  p.smoothing = 0.0;
  if (doc.contains("smoothing")) {
    const nlohmann::json &js = doc["smoothing"];
    if (!js.is_number()) fail("\"smoothing\" must be a number (>= 0, 0 = off), found " + js.dump());
    const double v = js.get<double>();
    if (!std::isfinite(v)) fail("\"smoothing\" is not finite");
    if (v < 0.0) fail("\"smoothing\" = " + num(v) + " is negative (must be >= 0, 0 = off)");
    p.smoothing = v;
  }

  // params
  if (!doc.contains("params")) fail("missing key \"params\"");
  const nlohmann::json &jp = doc["params"];
  if (!jp.is_object()) fail("\"params\" must be an object, found " + type_name(jp));
  for (auto it = jp.begin(); it != jp.end(); ++it) {
    bool known = false;
    for (const Key &k : kKeys) known = known || it.key() == k.name;
    if (!known) {
      std::string list;
      for (const Key &k : kKeys) list += (list.empty() ? "" : ", ") + std::string(k.name);
      fail("params: unknown key \"" + it.key() + "\" (known: " + list + ")");
    }
  }
  for (const Key &k : kKeys) {
    const std::string key = std::string("params.") + k.name;
    if (!jp.contains(k.name)) {
      if (required(k, p.model))
        fail("missing key \"" + key + "\" (required for model \"" + model_name(p.model) + "\")");
      continue;
    }
    const nlohmann::json &jv = jp[k.name];
    if (!jv.is_number()) fail(key + " must be a number, found " + jv.dump());
    const double v = jv.get<double>();
    if (!std::isfinite(v)) fail(key + " is not finite");
    switch (k.rule) {
      case Key::positive:
        if (v < 0.0) fail(key + " = " + num(v) + " is negative (must be > 0)");
        if (v == 0.0 && required(k, p.model)) fail(key + " = 0 (must be > 0)");
        break;
      case Key::nonneg:
        if (v < 0.0) fail(key + " = " + num(v) + " is negative (must be >= 0)");
        break;
      case Key::alpha:
        if (p.model == RTB_MODEL_RT || v != 0.0) {
          if (!(v > 0.0 && v < 1.0))
            fail(key + " = " + num(v) + " is outside (0,1)");
          if (p.model == RTB_MODEL_RT && v < RTB_ALPHA_MIN)
            fail(key + " = " + num(v) + " is below RTB_ALPHA_MIN = " + num(RTB_ALPHA_MIN) +
                 " (use model \"sts\" for the friction limit)");
        }
        break;
      case Key::fraction:
        if (!(v >= 0.0 && v < 1.0)) fail(key + " = " + num(v) + " is outside [0,1)");
        break;
      case Key::any:
        break;
    }
    p.*(k.field) = v;
  }

  const rtb_status st = rtb_params_validate(&p);
  if (st != RTB_OK) {
    std::string hint;
    if (std::fabs(p.k_asym) > p.K0) hint = " (|params.k_asym| must not exceed params.K0)";
    else if (p.maxwell_k > 0.0 && !(p.maxwell_tau > 0.0))
      hint = " (params.maxwell_tau must be > 0 when params.maxwell_k > 0)";
    fail(std::string("invalid parameters: ") + rtb_status_message(st) + hint);
  }
  return p;
}

nlohmann::json parse_json_text(const std::string &text, const std::string &origin) {
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(text);
  } catch (const nlohmann::json::parse_error &e) {
    // Turn the byte offset into a line number.
    size_t line = 1;
    const size_t end = std::min((size_t)e.byte, text.size());
    for (size_t i = 0; i + 1 < end; ++i) line += text[i] == '\n';
    std::string what = e.what();
    const size_t colon = what.find(": ", what.find("parse error"));
    if (colon != std::string::npos) what = what.substr(colon + 2);
    throw InputError(origin + ":" + std::to_string(line) + ": invalid JSON: " + what);
  }
  return doc;
}

rtb_params params_from_json_text(const std::string &text, const std::string &origin) {
  return params_from_json(parse_json_text(text, origin), origin);
}

rtb_params read_params_json(const std::string &path) {
  return params_from_json_text(read_file_bytes(path), path);
}

nlohmann::ordered_json params_to_json(const rtb_params &p) {
  nlohmann::ordered_json j;
  j["model"] = model_name(p.model);
  j["cells"] = p.cells;
  j["integrator"] = integrator_name(p.integrator);
  if (p.smoothing != 0.0) j["smoothing"] = p.smoothing;
  nlohmann::ordered_json jp = nlohmann::ordered_json::object();
  for (const Key &k : kKeys) {
    const double v = p.*(k.field);
    // Core keys of the other model are written only when set.
    const bool core = std::string(k.name) == "C0" || std::string(k.name) == "alpha" ||
                      std::string(k.name) == "Ff";
    if (core && !required(k, p.model) && v == 0.0) continue;
    jp[k.name] = v;
  }
  j["params"] = jp;
  return j;
}

std::string params_to_json_text(const rtb_params &p) {
  // nlohmann writes doubles with the shortest representation that reads back
  // to the same value (round-trip exact, like %.17g but without the noise).
  return params_to_json(p).dump(2) + "\n";
}

}  // namespace rtb
