// param_ids.cpp -- names and accessors of the identifiable parameters,
// generated from the one field list RTB_PARAM_FIELDS (rt_bushing.h).
#include "rtb_offline.h"

namespace rtb {

#define RTB_FIT_NAME_FIT(name) #name,
#define RTB_FIT_NAME_SETTING(name)
#define RTB_FIT_NAME(name, rule, kind, unit, text) RTB_FIT_NAME_##kind(name)

const char *param_name(ParamId id) {
  static const char *const names[P_COUNT] = {RTB_PARAM_FIELDS(RTB_FIT_NAME)};
  return (id >= 0 && id < P_COUNT) ? names[id] : "?";
}

#define RTB_FIT_REF_FIT(name) case P_##name: return p.name;
#define RTB_FIT_REF_SETTING(name)
#define RTB_FIT_REF(name, rule, kind, unit, text) RTB_FIT_REF_##kind(name)

double &param_ref(rtb_params &p, ParamId id) {
  switch (id) {
    RTB_PARAM_FIELDS(RTB_FIT_REF)
    case P_COUNT: break;
  }
  throw std::logic_error("param_ref: bad id");
}

double param_get(const rtb_params &p, ParamId id) {
  return param_ref(const_cast<rtb_params &>(p), id);
}

}  // namespace rtb
