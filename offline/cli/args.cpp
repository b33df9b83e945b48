// args.cpp -- declarative option parsing for the subcommands (cli.h).
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <string>

#include "cli/cli.h"

namespace rtb {
namespace cli {

namespace {
const std::vector<std::string> kNone;
}

bool Args::has(const std::string &name) const { return values.count(name) != 0; }

std::string Args::get(const std::string &name) const {
  auto it = values.find(name);
  if (it == values.end() || it->second.empty()) throw UsageError("missing option --" + name);
  return it->second.back();
}

std::string Args::get(const std::string &name, const std::string &dflt) const {
  auto it = values.find(name);
  return it == values.end() || it->second.empty() ? dflt : it->second.back();
}

const std::vector<std::string> &Args::all(const std::string &name) const {
  auto it = values.find(name);
  return it == values.end() ? kNone : it->second;
}

double Args::get_double(const std::string &name, double dflt) const {
  if (!has(name)) return dflt;
  const std::string s = get(name);
  char *end = nullptr;
  errno = 0;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end != '\0' || errno == ERANGE || !std::isfinite(v))
    throw UsageError("--" + name + " expects a number, got \"" + s + "\"");
  return v;
}

long Args::get_int(const std::string &name, long dflt) const {
  if (!has(name)) return dflt;
  const std::string s = get(name);
  char *end = nullptr;
  errno = 0;
  const long v = std::strtol(s.c_str(), &end, 10);
  if (s.empty() || *end != '\0' || errno == ERANGE)
    throw UsageError("--" + name + " expects an integer, got \"" + s + "\"");
  return v;
}

Args parse_args(const CommandSpec &spec, int argc, char **argv) {
  Args a;
  a.command = spec.name;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      a.help = true;
      continue;
    }
    if (arg.size() < 3 || arg.compare(0, 2, "--") != 0) {
      if (!arg.empty() && arg[0] == '-') throw UsageError("unknown option '" + arg + "'");
      throw UsageError("unexpected argument '" + arg + "' (options are given as --name VALUE)");
    }
    std::string name = arg.substr(2), value;
    bool has_value = false;
    const size_t eq = name.find('=');
    if (eq != std::string::npos) {
      value = name.substr(eq + 1);
      name = name.substr(0, eq);
      has_value = true;
    }
    const OptionSpec *opt = nullptr;
    for (const OptionSpec &o : spec.options)
      if (name == o.name) opt = &o;
    if (!opt) throw UsageError("unknown option '--" + name + "'");
    if (opt->metavar) {
      if (!has_value) {
        if (i + 1 >= argc) throw UsageError("option --" + name + " needs a value (" + opt->metavar + ")");
        value = argv[++i];
      }
    } else if (has_value) {
      throw UsageError("option --" + name + " takes no value");
    }
    auto &slot = a.values[name];
    if (!slot.empty() && !opt->repeatable)
      throw UsageError("option --" + name + " given more than once");
    slot.push_back(value);
  }
  if (!a.help)
    for (const OptionSpec &o : spec.options)
      if (o.required && !a.has(o.name)) throw UsageError(std::string("missing option --") + o.name);
  return a;
}

std::string help_text(const CommandSpec &spec) {
  std::string u = std::string("usage: rtb ") + spec.name;
  for (const OptionSpec &o : spec.options) {
    std::string item = std::string("--") + o.name + (o.metavar ? std::string(" ") + o.metavar : "");
    if (o.repeatable) item += " [" + item + " ...]";
    u += " " + (o.required ? item : "[" + item + "]");
  }
  u += "\n\n";
  u += spec.summary;
  u += "\n\noptions:\n";
  std::vector<std::string> lhs;
  size_t w = 6;  // "--help"
  for (const OptionSpec &o : spec.options) {
    lhs.push_back(std::string("--") + o.name + (o.metavar ? std::string(" ") + o.metavar : ""));
    w = std::max(w, lhs.back().size());
  }
  for (size_t i = 0; i < spec.options.size(); ++i) {
    std::string l = "  " + lhs[i] + std::string(w - lhs[i].size() + 2, ' ') + spec.options[i].help;
    if (spec.options[i].required) l += " (required)";
    if (spec.options[i].repeatable) l += " (repeatable)";
    u += l + "\n";
  }
  u += "  --help" + std::string(w - 6 + 2, ' ') + "show this help\n";
  if (spec.details) {
    u += "\n";
    u += spec.details;
    if (u.back() != '\n') u += "\n";
  }
  return u;
}

bool parse_or_help(const CommandSpec &spec, int argc, char **argv, Args &out) {
  out = parse_args(spec, argc, argv);
  if (out.help) {
    std::fputs(help_text(spec).c_str(), stdout);
    return true;
  }
  return false;
}

SimOptions sim_options_from(const Args &a) {
  SimOptions opt;
  if (a.has("ramp-time")) {
    opt.ramp_time = a.get_double("ramp-time", 0.0);
    if (!(opt.ramp_time > 0.0)) throw UsageError("--ramp-time must be > 0 (omit it for automatic)");
  }
  if (a.has("start")) {
    const std::string m = a.get("start");
    if (m == "auto") opt.start = StartMode::automatic;
    else if (m == "ramp") opt.start = StartMode::ramp;
    else if (m == "hold") opt.start = StartMode::hold;
    else throw UsageError("--start must be auto, ramp or hold (got '" + m + "')");
  }
  return opt;
}

}  // namespace cli
}  // namespace rtb
