// cmd_identify.cpp -- `rtb identify`: fit the RT parameters to measured
// records (sections 4-5), report the fit and its uncertainty, optionally emit
// the C parameter header.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <sstream>

#include "cli/cli.h"
#include "cli/fit_common.h"
#include "cli/identify_table.h"
#include "identify/identify.h"
#include "identify/sts_init.h"
#include "io/header_writer.h"
#include "io/params_json.h"

namespace rtb {
namespace cli {

namespace {

// The fit options with --data optional: --dynstiff TABLE replaces it.
CommandSpec identify_spec() {
  CommandSpec spec{
      "identify",
      "Identify p = (K0, Kpa, Kr, C0, alpha) from force/displacement records by\n"
      "minimizing eq. (11) with the exact adjoint gradient of the stepper, or from a\n"
      "dynamic-stiffness table (--dynstiff).",
      fit_option_specs({
          {"out", "FILE", "parameter JSON with fit, uncertainty and provenance", true},
          {"header", "FILE", "also emit the C parameter header"},
          {"name", "IDENT", "name of the constant in the header (default rtb_identified)"},
          {"smoothing", "S", "fit the eq. (14) smoothed model, s [1/velocity] (default 0 = off)"},
          {"dynstiff", "TABLE", "fit a table frequency,amplitude,stiffness,loss_angle_deg[,weight] "
                                "instead of records (--init table: start from the table)"},
      }),
      "--init sts (default) derives the start from the STS loop features, eq. (17)-(26),\n"
      "and prints them (the paper's Table 5). --init friction starts from a one-slider\n"
      "friction device (a Jenkins element from the same features): for devices that\n"
      "slide, where the STS start can end in a viscous basin. Records that do not start at x = 0 are\n"
      "preceded by a linear ramp from rest (not part of the misfit). With --dynstiff the\n"
      "misfit is the relative error of the complex stiffness (ln|K*|, loss angle in rad)\n"
      "over periodic runs from rest, its gradient the adjoint through those runs."};
  for (OptionSpec &o : spec.options)
    if (std::string(o.name) == "data") o.required = false;
  return spec;
}

}  // namespace

int run_identify(int argc, char **argv) {
  static const CommandSpec spec = identify_spec();
  Args a;
  if (parse_or_help(spec, argc, argv, a)) return kExitOk;
  if (a.has("name")) {
    std::string why;
    if (!is_valid_header_name(a.get("name"), &why)) throw UsageError("--name: " + why);
  }
  if (a.has("dynstiff")) {
    if (a.has("data")) throw UsageError("--dynstiff excludes --data");
    return identify_from_table(a);
  }
  if (!a.has("data")) throw UsageError("missing required option --data (or --dynstiff TABLE)");
  FitSetup fs = parse_fit_setup(a);
  fs.start.smoothing = a.get_double("smoothing", fs.start.smoothing);  // eq. (14); a setting
  if (fs.start.smoothing < 0.0) throw UsageError("--smoothing must be >= 0 (0 = off)");
  const IdentifyResult r = run_fit(fs, a.has("quiet"));
  print_fit_summary(r, fs);
  nlohmann::ordered_json j = fit_result_json(r, fs);
  write_file_atomic(a.get("out"), j.dump(2) + "\n");
  if (a.has("header")) {
    HeaderInfo hi = header_info_for(r, fs, a.get("name", "rtb_identified"));
    write_file_atomic(a.get("header"), emit_parameter_header(r.params, hi));
  }
  return kExitOk;  // non-convergence is reported in the JSON and the summary
}

}  // namespace cli
}  // namespace rtb
