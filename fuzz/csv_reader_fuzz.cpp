// csv_reader_fuzz.cpp -- the record CSV reader (offline/io/csv_reader.cpp) on
// any bytes: it either returns a record that keeps the documented promises
// (at least kMinSamples rows, equal column lengths, finite values, strictly
// increasing time) or throws InputError naming "path:line:". Anything else --
// another exception, a crash, a sanitizer report -- is a bug.
#include <cmath>
#include <cstdint>
#include <string>

#include "fuzz/fuzz_bytes.h"
#include "offline/io/csv.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  using rtb_fuzz::fail;
  if (size == 0) return 0;
  rtb::CsvReadOptions opt;
  opt.require_force = (data[0] & 1) == 0;  // `rtb simulate` reads without force
  const std::string bytes(reinterpret_cast<const char *>(data) + 1, size - 1);
  rtb::Record r;
  try {
    r = rtb::parse_record_csv(bytes, "fuzz.csv", opt);
  } catch (const rtb::InputError &e) {
    const std::string what = e.what();
    if (what.rfind("fuzz.csv:", 0) != 0) fail("InputError without \"file:line:\"");
    return 0;
  } catch (...) {
    fail("the CSV reader threw something other than InputError");
  }
  const size_t n = r.t.size();
  if (n < (size_t)rtb::kMinSamples) fail("record shorter than kMinSamples");
  if (r.x.size() != n) fail("displacement column length differs from time");
  if (opt.require_force ? r.F.size() != n : !(r.F.empty() || r.F.size() == n))
    fail("force column length differs from time");
  for (size_t i = 0; i < n; ++i) {
    if (!std::isfinite(r.t[i]) || !std::isfinite(r.x[i])) fail("non-finite value accepted");
    if (!r.F.empty() && !std::isfinite(r.F[i])) fail("non-finite force accepted");
    if (i > 0 && !(r.t[i] > r.t[i - 1])) fail("non-increasing time accepted");
  }
  if (r.sha256.size() != 64) fail("sha256 is not 64 hex digits");
  return 0;
}
