// cmd_header.cpp -- `rtb header`: the C parameter header of a parameter JSON,
// for one axis (rtb_params) or six (rtb_bushing6_params):
//   rtb header --params p.json --out bushing.h
//   rtb header --axis x=fx.json --axis rz=mz.json --out bushing6.h
//   rtb header --bushing6 bushing6.json --out bushing6.h
// The constant is named after the output file unless --name is given.
#include <cstdio>
#include <string>

#include "cli/cli.h"
#include "io/atomic_file.h"
#include "io/header_writer.h"
#include "io/params_json.h"
#include "rtb_offline.h"

namespace rtb {
namespace cli {
namespace {

// "bushing6" for ".../bushing6.h".
std::string stem(const std::string &path) {
  const size_t slash = path.find_last_of('/');
  std::string s = slash == std::string::npos ? path : path.substr(slash + 1);
  const size_t dot = s.find_last_of('.');
  return dot == std::string::npos ? s : s.substr(0, dot);
}

std::string source_of(const std::string &path) {
  return path + " (sha256 " + sha256_file(path) + ")";
}

// --axis AXIS=FILE, repeatable: the named axes are on, the others off.
std::string six_axis_from_flags(const Args &a, const std::string &name) {
  Bushing6HeaderInfo info;
  info.name = name;
  info.tool_version = tool_version();
  rtb_bushing6_params p;
  rtb_bushing6_params_default(&p, RTB_MODEL_RT);
  for (int k = 0; k < RTB_AXES; ++k) p.active[k] = 0;
  for (const std::string &spec : a.all("axis")) {
    const size_t eq = spec.find('=');
    int axis = -1;
    for (int k = 0; k < RTB_AXES && eq != std::string::npos; ++k)
      if (spec.compare(0, eq, rtb_axis_name(k)) == 0 && eq == std::string(rtb_axis_name(k)).size())
        axis = k;
    if (axis < 0)
      throw UsageError("--axis " + spec + ": expected AXIS=FILE with AXIS one of x y z rx ry rz");
    if (p.active[axis]) throw UsageError("--axis: axis " + spec.substr(0, eq) + " given twice");
    const std::string file = spec.substr(eq + 1);
    p.axis[axis] = read_params_json(file);
    p.active[axis] = 1;
    info.sources[axis] = source_of(file);
  }
  return emit_bushing6_header(p, info);
}

std::string six_axis_from_file(const std::string &path, const std::string &name) {
  Bushing6HeaderInfo info;
  info.name = name;
  info.tool_version = tool_version();
  const rtb_bushing6_params p = read_bushing6_json(path);
  for (int k = 0; k < RTB_AXES; ++k)
    if (p.active[k]) info.sources[k] = source_of(path);
  return emit_bushing6_header(p, info);
}

}  // namespace

int run_header(int argc, char **argv) {
  static const CommandSpec spec{
      "header",
      "Write the C parameter header of a parameter JSON: one axis (rtb_params) or a\n"
      "six-axis bushing (rtb_bushing6_params). Exact to the bit, reproducible bytes,\n"
      "compiles as C99 and C++.",
      {
          {"params", "FILE", "single-axis parameter JSON -> rtb_params constant"},
          {"axis", "AXIS=FILE", "six-axis: parameter JSON of one axis (x y z rx ry rz); "
                                "axes not given are off",
           false, true},
          {"bushing6", "FILE", "six-axis JSON: {\"x\": {...}, \"rz\": {...}}, or one "
                               "single-axis document for all six axes"},
          {"out", "FILE", "the header to write", true},
          {"name", "IDENT", "name of the constant (default: the output file's name)"},
          {"quiet", nullptr, "print nothing on success"},
      },
      "Give exactly one of --params, --axis (repeatable) and --bushing6."};
  Args a;
  if (parse_or_help(spec, argc, argv, a)) return kExitOk;
  const int modes = a.has("params") + a.has("axis") + a.has("bushing6");
  if (modes != 1) throw UsageError("give exactly one of --params, --axis and --bushing6");
  const std::string out = a.get("out");
  const std::string name = a.get("name", stem(out));
  std::string why;
  if (!is_valid_header_name(name, &why))
    throw UsageError("constant name \"" + name + "\" (from " +
                     (a.has("name") ? std::string("--name") : "the output file name") +
                     "): " + why + "; choose one with --name");

  std::string text;
  if (a.has("params")) {
    HeaderInfo info;
    info.name = name;
    info.tool_version = tool_version();
    info.provenance.push_back("parameters: " + source_of(a.get("params")));
    text = emit_parameter_header(read_params_json(a.get("params")), info);
  } else if (a.has("axis")) {
    text = six_axis_from_flags(a, name);
  } else {
    text = six_axis_from_file(a.get("bushing6"), name);
  }
  write_file_atomic(out, text);
  if (!a.has("quiet")) std::printf("wrote %s (constant %s)\n", out.c_str(), name.c_str());
  return kExitOk;
}

}  // namespace cli
}  // namespace rtb
