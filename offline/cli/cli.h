// cli.h -- the `rtb` command line: subcommand table, option parsing and the
// subcommand entry points.
//
// Adding a subcommand: declare `int run_NAME(int argc, char **argv);` below
// and add one row to kSubcommands in cli/dispatch.cpp. argv[0] is the
// subcommand name; errors are reported by throwing (InputError / UsageError
// -> "rtb: error: ..." and exit 2; anything else -> exit 1), so a subcommand
// only returns 0 (or its own non-zero code).
#ifndef RTB_OFFLINE_CLI_CLI_H
#define RTB_OFFLINE_CLI_CLI_H

#include <cstdio>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "rtb_offline.h"

namespace rtb {
namespace cli {

// ---------------------------------------------------------------- exit codes
constexpr int kExitOk = 0;
constexpr int kExitFailure = 1;   // runtime failure (e.g. the stepper diverged)
constexpr int kExitUsage = 2;     // bad command line or bad input data

// Bad command line (unknown option, missing value, ...): exit 2.
struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// ---------------------------------------------------------------- subcommands
struct Subcommand {
  const char *name;
  const char *help;                  // one line, shown by `rtb --help`
  int (*run)(int argc, char **argv); // argv[0] = subcommand name
};

// Entry points (one per row of the table in dispatch.cpp).
int run_simulate(int argc, char **argv);
int run_validate(int argc, char **argv);
int run_info(int argc, char **argv);
int run_identify(int argc, char **argv);
int run_gradcheck(int argc, char **argv);
int run_diagnose(int argc, char **argv);
int run_demo(int argc, char **argv);
int run_paper_figures(int argc, char **argv);
int run_report(int argc, char **argv);
int run_header(int argc, char **argv);
int run_dynstiff(int argc, char **argv);

// The table, in display order.
const std::vector<Subcommand> &subcommands();

// main(): dispatch on argv[1], handle --help/--version, map exceptions to
// exit codes.
int main(int argc, char **argv);

// The tool's version string, "rtb X.Y.Z" (library version).
std::string tool_version();

// ---------------------------------------------------------------- options
// Declarative option parsing: "--name VALUE", "--name=VALUE" and flags.
struct OptionSpec {
  const char *name;      // without the leading "--"
  const char *metavar;   // nullptr: a flag without value
  const char *help;
  bool required = false;
  bool repeatable = false;
};

struct CommandSpec {
  const char *name;          // subcommand name
  const char *summary;       // first line of --help
  std::vector<OptionSpec> options;
  const char *details = nullptr;  // optional paragraph after the options
};

class Args {
 public:
  bool help = false;                    // --help / -h was given
  bool has(const std::string &name) const;
  // The (last) value; throws UsageError if absent and no default.
  std::string get(const std::string &name) const;
  std::string get(const std::string &name, const std::string &dflt) const;
  const std::vector<std::string> &all(const std::string &name) const;  // every value
  // Numeric values, with the option named in the UsageError.
  double get_double(const std::string &name, double dflt) const;
  long get_int(const std::string &name, long dflt) const;

  std::map<std::string, std::vector<std::string>> values;
  std::string command;
};

// Parses argv[1..argc-1] against spec (argv[0] is the subcommand name).
// Throws UsageError on unknown options, missing values, repeated
// non-repeatable options, positional arguments or missing required options
// (the latter not checked when --help is given).
Args parse_args(const CommandSpec &spec, int argc, char **argv);

// "usage: rtb NAME ..." plus one line per option.
std::string help_text(const CommandSpec &spec);

// Convenience: parse, print help if asked (returns true: caller returns 0).
bool parse_or_help(const CommandSpec &spec, int argc, char **argv, Args &out);

// The forward-model options shared by the subcommands (--ramp-time).
SimOptions sim_options_from(const Args &a);

}  // namespace cli
}  // namespace rtb

#endif
