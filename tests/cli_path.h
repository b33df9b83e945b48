// cli_path.h -- where the tests find the `rtb` executable they run, and how
// they quote its arguments for the shell.
#ifndef RTB_TESTS_CLI_PATH_H
#define RTB_TESTS_CLI_PATH_H

#include <string>

namespace rtb_test {
#ifdef RTB_CLI_PATH
const std::string kRtb = RTB_CLI_PATH;
#else
const std::string kRtb = std::string(RTB_BINARY_DIR) + "/rtb";
#endif

// One shell word: single quotes, with any ' inside closed, escaped, reopened.
inline std::string shell_quote(const std::string &s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}
}  // namespace rtb_test

#endif
