// fuzz_regression_test.cpp -- every input the fuzzers of fuzz/ crashed on,
// as a test of the behaviour it should have had (`make fuzz`; the seed
// corpus fuzz/corpus/ also keeps each reproducer, replayed by ctest).
#ifdef RTB_HAVE_OFFLINE
#include <gtest/gtest.h>

#include <string>

#include "rtb_offline.h"

namespace {

// params_json fuzzer, first seconds: a number literal beyond double range
// made nlohmann throw json::out_of_range (406), which is not a parse_error
// and escaped the reader as a non-InputError exception (the CLI then exited
// without naming the file and line).
TEST(FuzzRegression, JsonNumberBeyondDoubleRangeIsAnInputErrorWithItsLine) {
  const std::string text = "{\"model\":\"rt\",\n \"params\":{\"K0\":1e999}}\n";
  try {
    rtb::params_from_json_text(text, "p.json");
    FAIL() << "accepted 1e999";
  } catch (const rtb::InputError &e) {
    const std::string what = e.what();
    EXPECT_EQ(what.rfind("p.json:2: invalid JSON: ", 0), 0u) << what;
    EXPECT_NE(what.find("1e999"), std::string::npos) << what;
  }
}

}  // namespace
#endif
