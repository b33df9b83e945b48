// cli_path.h -- where the tests find the `rtb` executable they run.
#ifndef RTB_TESTS_CLI_PATH_H
#define RTB_TESTS_CLI_PATH_H

#include <string>

namespace rtb_test {
#ifdef RTB_CLI_PATH
const std::string kRtb = RTB_CLI_PATH;
#else
const std::string kRtb = std::string(RTB_BINARY_DIR) + "/rtb";
#endif
}  // namespace rtb_test

#endif
