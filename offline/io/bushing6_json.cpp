// bushing6_json.cpp -- six-axis parameter files (params_json.h).
#include <string>

#include "io/atomic_file.h"
#include "io/params_json.h"

namespace rtb {

rtb_bushing6_params bushing6_from_json(const nlohmann::json &doc, const std::string &origin) {
  if (!doc.is_object())
    throw InputError(origin + ": expected a JSON object at the top level, found " +
                     std::string(doc.type_name()));
  rtb_bushing6_params p;
  rtb_bushing6_params_default(&p, RTB_MODEL_RT);
  if (doc.contains("model")) {  // one bushing for every axis
    const rtb_params one = params_from_json(doc, origin);
    for (int a = 0; a < RTB_AXES; ++a) p.axis[a] = one;
    return p;
  }
  for (auto it = doc.begin(); it != doc.end(); ++it) {
    int axis = -1;
    for (int a = 0; a < RTB_AXES; ++a)
      if (it.key() == rtb_axis_name(a)) axis = a;
    if (axis < 0)
      throw InputError(origin + ": unknown key \"" + it.key() +
                       "\" (expected a single-axis document with \"model\", or axis names "
                       "x, y, z, rx, ry, rz)");
  }
  int on = 0;
  for (int a = 0; a < RTB_AXES; ++a) {
    p.active[a] = doc.contains(rtb_axis_name(a));
    if (!p.active[a]) continue;
    p.axis[a] = params_from_json(doc[rtb_axis_name(a)], origin + ": axis " + rtb_axis_name(a));
    ++on;
  }
  if (on == 0) throw InputError(origin + ": no axis given (keys x, y, z, rx, ry, rz)");
  return p;
}

rtb_bushing6_params read_bushing6_json(const std::string &path) {
  return bushing6_from_json(parse_json_text(read_file_bytes(path), path), path);
}

}  // namespace rtb
