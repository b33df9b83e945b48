// params_json_fuzz.cpp -- the parameter JSON reader (offline/io/params_json.cpp)
// on any text: it either returns parameters the library accepts
// (rtb_params_validate == RTB_OK), which write back and read again to the
// same bits, or throws InputError starting with the origin. Anything else is
// a bug.
#include <cstdint>
#include <cstring>
#include <string>

#include "fuzz/fuzz_bytes.h"
#include "rtb_offline.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  using rtb_fuzz::fail;
  const std::string text(reinterpret_cast<const char *>(data), size);
  rtb_params p;
  try {
    p = rtb::params_from_json_text(text, "fuzz.json");
  } catch (const rtb::InputError &e) {
    if (std::string(e.what()).rfind("fuzz.json", 0) != 0) fail("InputError without the origin");
    return 0;
  } catch (...) {
    fail("the JSON reader threw something other than InputError");
  }
  if (rtb_params_validate(&p) != RTB_OK) fail("accepted parameters the library rejects");
  rtb_params q;
  try {
    q = rtb::params_from_json_text(rtb::params_to_json_text(p), "round trip");
  } catch (...) {
    fail("written parameters do not read back");
  }
  if (std::memcmp(&p, &q, sizeof p) != 0) fail("parameters changed in a write/read round trip");
  return 0;
}
