// cmd_diagnose.cpp -- `rtb diagnose`: what the RT model gets wrong in the
// data, its cause (one word of the vocabulary), the extended model and the
// held-out gain.
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli/cli.h"
#include "cli/diagnose_report.h"
#include "cli/fit_common.h"
#include "diagnose/diagnose.h"
#include "io/header_writer.h"
#include "io/params_json.h"

namespace rtb {
namespace cli {

namespace {

// A comma-separated list of vocabulary words (--only, --causes); an unknown
// word is a usage error, not a silently empty screen.
std::vector<std::string> word_list(const Args &a, const char *option) {
  std::vector<std::string> words;
  if (!a.has(option)) return words;
  const std::string s = a.get(option);
  size_t pos = 0;
  for (;;) {
    const size_t e = s.find(',', pos);
    const std::string w = s.substr(pos, e == std::string::npos ? std::string::npos : e - pos);
    if (!is_candidate_name(w))
      throw UsageError(std::string("--") + option + ": '" + w + "' is not a candidate (see --help)");
    words.push_back(w);
    if (e == std::string::npos) return words;
    pos = e + 1;
  }
}

}  // namespace

int run_diagnose(int argc, char **argv) {
  static const CommandSpec spec{
      "diagnose",
      "Fit the RT model, estimate the noise floor from the data, try every extension\n"
      "of the vocabulary (cubic_stiffness, asymmetry, maxwell, viscous, backlash\n"
      "(floating or held end), mullins, delay, inertia, offset, softening, slack,\n"
      "relaxation_spectrum, friction_asymmetry, stretch_relaxation) and name the causes\n"
      "that explain the held-out records, one after another while the next still\n"
      "pays; `none` when the residual is at the noise floor, `unexplained` (with the\n"
      "residual's signature) when it is above it and no candidate removes it.",
      {
          {"data", "FILE", "fit record CSV; repeat for several", true, true},
          {"holdout", "FILE", "held-out record CSV; repeat for several", false, true},
          {"cells", "N",
           "number of RT cells (default 15; a later cause must also beat 10, 12 and 20 "
           "cells, which the extended model may then take)"},
          {"fit-from", "S", "fit only samples from t0 + S on"},
          {"ramp-time", "S", "ramp from rest to x[0] for records not starting at 0 (default auto)"},
          {"start", "auto|ramp|hold",
           "how the model reaches x[0] before a record: ramp from rest, or ramp and hold (a "
           "relaxed preload); auto: hold when |x[0]| > 5% of the record's reach"},
          {"only", "LIST", "try only these candidates (comma separated)"},
          {"causes", "LIST",
           "what-if: fit these words in this order and accept them whatever the criteria say "
           "(still reported)"},
          {"min-gain", "G", "relative held-out error reduction a cause must bring (default 0.15)"},
          {"threads", "N", "candidate fits in parallel (default 2)"},
          {"out", "FILE", "JSON report", true},
          {"header", "FILE", "emit the extended model's C parameter header"},
          {"name", "IDENT", "name of the constant in the header (default rtb_extended)"},
          {"plot-dir", "DIR", "write residual/loop data files and gnuplot PNGs there"},
          {"quiet", nullptr, "no progress on stderr"},
      },
      "delay and offset are measurement-chain artefacts: they are estimated and\n"
      "corrected in the data, never put into the real-time element."};
  static const CommandSpec full = with_preprocess_options(spec);
  Args a;
  if (parse_or_help(full, argc, argv, a)) return kExitOk;
  DiagnoseOptions o;
  o.cells = (int)a.get_int("cells", RTB_DEFAULT_CELLS);
  if (o.cells < 1 || o.cells > RTB_MAX_CELLS) throw UsageError("--cells out of range");
  o.misfit.fit_from = a.get_double("fit-from", 0.0);
  o.misfit.sim = sim_options_from(a);
  o.min_gain = a.get_double("min-gain", o.min_gain);
  o.threads = (int)a.get_int("threads", 2);
  o.quiet = a.has("quiet");
  o.only = word_list(a, "only");
  o.imposed = word_list(a, "causes");
  for (size_t i = 0; i < o.imposed.size(); ++i)
    for (size_t j = 0; j < i; ++j)
      if (o.imposed[i] == o.imposed[j])
        throw UsageError("--causes: '" + o.imposed[i] + "' is imposed twice");
  std::string why;
  const std::string name = a.get("name", "rtb_extended");
  if (a.has("header") && !is_valid_header_name(name, &why)) throw UsageError("--name: " + why);
  std::vector<Record> fit, hold;
  for (const std::string &p : a.all("data")) fit.push_back(read_record_csv(p));
  if (a.has("holdout"))
    for (const std::string &p : a.all("holdout")) hold.push_back(read_record_csv(p));

  // Same preprocessing for held-out records, except the fit weights.
  Preprocess pre = preprocess_from(a);
  resolve_force_sign(pre, fit, o.quiet);
  apply_preprocess(pre, fit, true);
  apply_preprocess(pre, hold, false);

  const DiagnoseResult R = diagnose(fit, hold, o);
  print_diagnosis(R);
  nlohmann::ordered_json report = diagnosis_json(R, fit, hold);
  report["preprocessing"] = preprocess_json(pre);
  report["start"] = start_mode_name(o.misfit.sim.start);
  write_file_atomic(a.get("out"), report.dump(2) + "\n");
  if (a.has("header")) write_file_atomic(a.get("header"), diagnosis_header(R, fit, name));
  if (a.has("plot-dir")) write_diagnosis_plots(R, fit, hold, a.get("plot-dir"));
  return kExitOk;
}

}  // namespace cli
}  // namespace rtb
