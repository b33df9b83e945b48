// params_json.h -- parameter JSON helpers beyond rtb_offline.h
// (read_params_json, params_from_json_text, params_to_json_text).
#ifndef RTB_OFFLINE_IO_PARAMS_JSON_H
#define RTB_OFFLINE_IO_PARAMS_JSON_H

#include <nlohmann/json.hpp>
#include <string>

#include "rtb_offline.h"

namespace rtb {

// The parameter object {"model","cells","integrator","params":{...}} in key
// order, ready to embed in a richer document (identify's output).
nlohmann::ordered_json params_to_json(const rtb_params &p);

// Parses an already-parsed document (top-level keys other than model, cells,
// integrator, smoothing (eq. (14), optional, 0 = off) and params are ignored). `origin` names the source in messages.
rtb_params params_from_json(const nlohmann::json &doc, const std::string &origin);

// Parses JSON text; a syntax error is InputError("ORIGIN:LINE: invalid JSON: ...").
nlohmann::json parse_json_text(const std::string &text, const std::string &origin);

// Six axes (bushing6_json.cpp): either one single-axis document, applied to
// every axis, or an object {"x": {...}, "rz": {...}} of single-axis documents
// keyed by axis name (x y z rx ry rz); axes not named are off.
rtb_bushing6_params bushing6_from_json(const nlohmann::json &doc, const std::string &origin);
rtb_bushing6_params read_bushing6_json(const std::string &path);

// "rt"/"sts", "sdirk2"/"be".
const char *model_name(int model);
const char *integrator_name(int integrator);

}  // namespace rtb

#endif
