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

// "rt"/"sts", "sdirk2"/"be".
const char *model_name(int model);
const char *integrator_name(int integrator);

}  // namespace rtb

#endif
