// cmd_info.cpp -- `rtb info`: what the real-time library was built as.
#include <cstdio>

#include "cli/cli.h"
#include "rtb_offline.h"

namespace rtb {
namespace cli {

int run_info(int argc, char **argv) {
  static const CommandSpec spec{"info",
                                "Print the library version, ABI version, cell capacity and scalar "
                                "type.",
                                {{"json", nullptr, "print as JSON"}}};
  Args a;
  if (parse_or_help(spec, argc, argv, a)) return kExitOk;
  rtb_info info;
  rtb_get_info(&info);
  if (a.has("json")) {
    std::printf(
        "{\"tool\": \"%s\", \"version\": \"%s\", \"abi_version\": %d, \"max_cells\": %d, "
        "\"default_cells\": %d, \"scalar\": \"%s\", \"scalar_bytes\": %d}\n",
        tool_version().c_str(), info.version, info.abi_version, info.max_cells, RTB_DEFAULT_CELLS,
        info.scalar, info.scalar_bytes);
    return kExitOk;
  }
  std::printf("%s\n", tool_version().c_str());
  std::printf("library version  %s\n", info.version);
  std::printf("ABI version      %d\n", info.abi_version);
  std::printf("RTB_MAX_CELLS    %d (default %d)\n", info.max_cells, RTB_DEFAULT_CELLS);
  std::printf("scalar           %s (%d bytes)\n", info.scalar, info.scalar_bytes);
  if (info.abi_version != RTB_ABI_VERSION)
    std::printf("warning: header ABI %d differs from the library's %d\n", RTB_ABI_VERSION,
                info.abi_version);
  return kExitOk;
}

}  // namespace cli
}  // namespace rtb
