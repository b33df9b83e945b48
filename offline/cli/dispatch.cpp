// dispatch.cpp -- `rtb <subcommand> [options]`: the subcommand table and the
// mapping of exceptions to exit codes.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <exception>
#include <new>
#include <string>

#include "cli/cli.h"
#include "rtb_offline.h"

namespace rtb {
namespace cli {

// ---- the subcommand table: one row per subcommand, in display order ----
static const std::vector<Subcommand> kSubcommands = {
    {"demo", "built-in example: generate data with a hidden effect, identify, diagnose, emit a header",
     run_demo},
    {"identify", "identify the RT parameters from records (adjoint gradient), emit a C header",
     run_identify},
    {"diagnose", "find what the RT model gets wrong, name the cause, extend it, measure the gain",
     run_diagnose},
    {"header", "C parameter header of a parameter JSON, one axis or six (--axis x=fx.json ...)",
     run_header},
    {"dynstiff", "dynamic stiffness and loss angle vs frequency and amplitude (model or sine records)",
     run_dynstiff},
    {"simulate", "predict the force for a displacement record (CSV in, CSV out)", run_simulate},
    {"validate", "relative error sqrt(J/J0) of a parameter set against measured records",
     run_validate},
    {"gradcheck", "adjoint gradient vs finite differences, and the dot-product test",
     run_gradcheck},
    {"report", "real-data studies and paper figures into docs/results (make report)", run_report},
    {"paper-figures", "reproduce the paper's Figures 5, 6, 8, 9 as PNGs plus Markdown", run_paper_figures},
    {"info", "library version, ABI, capacity and scalar type", run_info},
};

const std::vector<Subcommand> &subcommands() { return kSubcommands; }

std::string tool_version() {
  rtb_info info;
  rtb_get_info(&info);
  return std::string("rtb ") + info.version;
}

namespace {

void print_main_help(FILE *f) {
  std::fprintf(f,
               "usage: rtb <subcommand> [options]\n"
               "\n"
               "Offline tool of rt_bushing: identify, validate and export parameters of the\n"
               "real-time rubber bushing model (Puel, Bourgeteau & Aubry 2013).\n"
               "\n"
               "subcommands:\n");
  size_t w = 0;
  for (const Subcommand &s : kSubcommands) w = std::max(w, std::strlen(s.name));
  for (const Subcommand &s : kSubcommands)
    std::fprintf(f, "  %-*s  %s\n", (int)w, s.name, s.help);
  std::fprintf(f,
               "\n"
               "`rtb <subcommand> --help` describes its options. Exit status: 0 success,\n"
               "1 failure, 2 bad command line or bad input (nothing is written).\n");
}

}  // namespace

int main(int argc, char **argv) {
  if (argc < 2) {
    print_main_help(stderr);
    return kExitUsage;
  }
  const std::string first = argv[1];
  if (first == "--help" || first == "-h" || first == "help") {
    if (first == "help" && argc >= 3) {
      // `rtb help NAME` == `rtb NAME --help`
      for (const Subcommand &s : kSubcommands)
        if (argv[2] == std::string(s.name)) {
          char help_flag[] = "--help";
          char *sub_argv[] = {argv[0], argv[2], help_flag, nullptr};
          return main(3, sub_argv);
        }
      std::fprintf(stderr, "rtb: error: unknown subcommand '%s' (see rtb --help)\n", argv[2]);
      return kExitUsage;
    }
    print_main_help(stdout);
    return kExitOk;
  }
  if (first == "--version" || first == "-V") {
    std::printf("%s\n", tool_version().c_str());
    return kExitOk;
  }
  const Subcommand *cmd = nullptr;
  for (const Subcommand &s : kSubcommands)
    if (first == s.name) cmd = &s;
  if (!cmd) {
    std::fprintf(stderr, "rtb: error: unknown %s '%s' (see rtb --help)\n",
                 first.compare(0, 1, "-") == 0 ? "option" : "subcommand", first.c_str());
    return kExitUsage;
  }
  try {
    return cmd->run(argc - 1, argv + 1);
  } catch (const UsageError &e) {
    std::fprintf(stderr, "rtb %s: error: %s\n(see rtb %s --help)\n", cmd->name, e.what(),
                 cmd->name);
    return kExitUsage;
  } catch (const InputError &e) {
    std::fprintf(stderr, "rtb: error: %s\n", e.what());
    return kExitUsage;
  } catch (const std::bad_alloc &) {
    std::fprintf(stderr, "rtb: error: out of memory\n");
    return kExitFailure;
  } catch (const std::exception &e) {
    std::fprintf(stderr, "rtb: error: %s\n", e.what());
    return kExitFailure;
  }
}

}  // namespace cli
}  // namespace rtb
