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
#include <string>

#include "io/atomic_file.h"
#include "io/number_text.h"

namespace rtb {
namespace {

struct Key {
  const char *name;
  double rtb_params::*field;
  const char *rule;  // what the library requires of it (RTB_PARAM_FIELDS rule)
};

const char *rule_text(const char *rule) {
  const std::string r = rule;
  if (r == "POSITIVE") return "must be > 0";
  if (r == "NONNEG") return "must be >= 0";
  if (r == "ALPHA") return "must satisfy RTB_ALPHA_MIN <= alpha < 1 (use model \"sts\" for the friction limit)";
  if (r == "FRACTION") return "must be in [0, 1)";
  if (r == "FLAG") return "must be 0 or 1";
  if (r == "SIGNED_FRACTION") return "must be in (-1, 1)";
  return "";
}

// Every numeric key of "params", in output order: the fields of rtb_params
// (RTB_PARAM_FIELDS) except the top-level model setting "smoothing".
#define RTB_JSON_KEY(name, rule, kind, unit, text) {#name, &rtb_params::name, #rule},
const Key kAllFields[] = {RTB_PARAM_FIELDS(RTB_JSON_KEY)};
#undef RTB_JSON_KEY

bool in_params(const Key &k) { return std::string(k.name) != "smoothing"; }

bool required(const Key &k, int model) {
  const std::string n = k.name;
  if (n == "K0" || n == "Kpa" || n == "Kr") return true;
  if (model == RTB_MODEL_RT) return n == "C0" || n == "alpha";
  return n == "Ff";
}

std::string num(double v) { return number_text("%.17g", v); }

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
  for (const Key &k : kAllFields) p.*(k.field) = 0.0;

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
    for (const Key &k : kAllFields) known = known || (in_params(k) && it.key() == k.name);
    if (!known) {
      std::string list;
      for (const Key &k : kAllFields)
        if (in_params(k)) list += (list.empty() ? "" : ", ") + std::string(k.name);
      fail("params: unknown key \"" + it.key() + "\" (known: " + list + ")");
    }
  }
  for (const Key &k : kAllFields) {
    if (!in_params(k)) continue;
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
    p.*(k.field) = v;
  }

  // The library's own check names the offending field.
  const char *bad = "";
  const rtb_status st = rtb_params_check(&p, &bad);
  if (st != RTB_OK) {
    const Key *k = nullptr;
    for (const Key &c : kAllFields)
      if (std::string(c.name) == bad) k = &c;
    if (!k) fail(std::string("invalid parameters: ") + bad + ": " + rtb_status_message(st));
    const std::string key = in_params(*k) ? std::string("params.") + bad : std::string(bad);
    std::string why = rtb_status_message(st);
    if (std::string(bad) == "k_asym") why = "|params.k_asym| must not exceed the static tangent K0 + 1/(1/Kpa + cells/Kr) + sat_force/sat_disp (K0 on a slack strip with relax_width)";
    else if (std::string(bad) == "K0") why = p.slack != 0.0 && p.relax_width > 0.0
                ? "must be >= 0 for a slack specimen with relax_width (a floating end needs a law that rises again)"
                : "must be >= -(1/(1/Kpa + cells/Kr) + sat_force/sat_disp): the static stiffness at x = 0 must not be negative";
    else if (std::string(bad) == "maxwell_tau") why = "must be > 0 when params.maxwell_k > 0";
    else if (std::string(bad) == "sat_disp" && p.sat_force > 0.0) why = "must be > 0 when params.sat_force > 0";
    else if (std::string(bad) == "spec_tau_min") why = "must be > 0 when the relaxation spectrum is on";
    else if (std::string(bad) == "spec_tau_max") why = "must be >= params.spec_tau_min";
    else if (std::string(bad) == "fric_asym" && p.model == RTB_MODEL_STS) why = "applies to the RT dashpot only (must be 0 for model \"sts\")";
    else if (std::string(bad) == "backlash_held" && p.slack != 0.0) why = "a slack specimen floats free: backlash_held must be 0";
    else if (*rule_text(k->rule)) why = rule_text(k->rule);
    const double v = p.*(k->field);
    const std::string rule = k->rule;
    if ((rule == "POSITIVE" || rule == "NONNEG") && v < 0.0) why = "is negative (" + why + ")";
    if (rule == "ALPHA" && !(v > 0.0 && v < 1.0)) why = "is outside (0,1); " + why;
    fail(key + " = " + num(v) + ": " + why + " (invalid parameters: " + rtb_status_message(st) + ")");
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
  } catch (const nlohmann::json::exception &e) {
    // Not a syntax error but a value the parser cannot hold (a number
    // literal beyond double range: out_of_range.406), found by fuzzing. Its
    // message quotes the literal; name the line where it first appears.
    std::string what = e.what();
    const size_t q0 = what.find('\''), q1 = what.rfind('\'');
    size_t line = 1;
    if (q0 != std::string::npos && q1 > q0) {
      const size_t at = text.find(what.substr(q0 + 1, q1 - q0 - 1));
      for (size_t i = 0; at != std::string::npos && i < at; ++i) line += text[i] == '\n';
    }
    const size_t tag = what.find("] ");
    if (tag != std::string::npos) what = what.substr(tag + 2);
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
  for (const Key &k : kAllFields) {
    if (!in_params(k)) continue;
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
