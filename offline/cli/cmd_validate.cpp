// cmd_validate.cpp -- `rtb validate`: the paper's relative error, eq. (27),
// sqrt(J/J0) with J = 1/2 int (F_model - F_exp)^2 dt, J0 = 1/2 int F_exp^2 dt,
// per record and overall (sqrt(sum J / sum J0)), plus NRMSE in %.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/cli.h"
#include "cli/fit_common.h"
#include "io/csv.h"
#include "io/params_json.h"
#include "model/forward.h"
#include "model/misfit_norms.h"
#include "rtb_offline.h"

namespace rtb {
namespace cli {

namespace {
// JSON cannot hold inf/nan: write null there.
nlohmann::ordered_json num_or_null(double v) {
  return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
}
}  // namespace

int run_validate(int argc, char **argv) {
  static const CommandSpec spec{
      "validate",
      "Relative error sqrt(J/J0) of a parameter set against measured records,\n"
      "eq. (27) of Puel et al. (2013): J = 1/2 int (F_model - F_exp)^2 dt,\n"
      "J0 = 1/2 int F_exp^2 dt (trapezoidal rule on each record's time grid).",
      {
          {"params", "FILE", "parameter JSON", true},
          {"data", "FILE", "measured CSV (time,displacement,force)", true, true},
          {"out", "FILE", "write the figures as JSON (\"error\" = overall, \"files\" = per file)"},
          {"ramp-time", "S", "ramp duration for records not starting at 0 (default: automatic)"},
          {"start", "auto|ramp|hold", "how the model reaches x[0] before the record: ramp from rest, or ramp and hold (a relaxed preload); auto: hold when |x[0]| > 5% of the record's reach"},
          {"quiet", nullptr, "do not print the table"},
      },
      "overall error = sqrt(sum J / sum J0) over all files.\n"
      "NRMSE = 100 * RMS(F_model - F_exp) / (max F_exp - min F_exp), per sample."};
  static const CommandSpec full = with_preprocess_options(spec);
  Args a;
  if (parse_or_help(full, argc, argv, a)) return kExitOk;

  const SimOptions opt = sim_options_from(a);
  const std::string params_path = a.get("params");
  const rtb_params p = read_params_json(params_path);

  // Read every file first: an input error anywhere stops before any work.
  std::vector<Record> recs;
  for (const std::string &path : a.all("data")) recs.push_back(read_record_csv(path));
  Preprocess pre = preprocess_from(a);
  resolve_force_sign(pre, recs, a.has("quiet"));
  apply_preprocess(pre, recs, true);

  std::vector<MisfitNorms> norms;
  int not_converged = 0;
  for (const Record &rec : recs) {
    const DriveGrid grid = make_drive_grid(rec, opt);
    const Trajectory tr = run_forward(p, grid, false);
    not_converged += tr.not_converged;
    const std::vector<double> F(tr.force.begin() + grid.first_sample, tr.force.end());
    norms.push_back(misfit_norms(rec.t, F, rec.F, rec.masked));
  }
  std::vector<double> weights;
  for (const Record &rec : recs) weights.push_back(rec.weight);
  const double overall = combined_relative_error(norms, weights);

  if (!a.has("quiet")) {
    size_t w = 4;
    for (const Record &r : recs) w = std::max(w, r.path.size());
    std::printf("%-*s  %8s  %12s  %10s\n", (int)w, "file", "samples", "sqrt(J/J0) %", "NRMSE %");
    for (size_t i = 0; i < recs.size(); ++i)
      std::printf("%-*s  %8zu  %12.4f  %10.4f\n", (int)w, recs[i].path.c_str(), norms[i].samples,
                  100.0 * norms[i].relative_error(), norms[i].nrmse_percent());
    std::printf("%-*s  %8s  %12.4f\n", (int)w, "overall", "", 100.0 * overall);
  }
  if (not_converged > 0)
    std::fprintf(stderr, "rtb validate: warning: %d step(s) did not reach the Newton tolerance\n",
                 not_converged);

  if (a.has("out")) {
    nlohmann::ordered_json j;
    j["tool"] = tool_version();
    j["params_file"] = {{"path", params_path}, {"sha256", sha256_file(params_path)}};
    j["parameters"] = params_to_json(p);
    j["norm"] = "sqrt(J/J0), J = 1/2 int (F_model - F_exp)^2 dt, J0 = 1/2 int F_exp^2 dt";
    j["error"] = num_or_null(overall);
    nlohmann::ordered_json files = nlohmann::ordered_json::array();
    for (size_t i = 0; i < recs.size(); ++i) {
      nlohmann::ordered_json f;
      f["path"] = recs[i].path;
      f["sha256"] = recs[i].sha256;
      f["error"] = num_or_null(norms[i].relative_error());
      f["samples"] = norms[i].samples;
      f["nrmse_percent"] = num_or_null(norms[i].nrmse_percent());
      f["J"] = norms[i].J;
      f["J0"] = norms[i].J0;
      if (!recs[i].units.empty()) f["units"] = recs[i].units;
      files.push_back(f);
    }
    j["files"] = files;
    j["preprocessing"] = preprocess_json(pre);
    write_file_atomic(a.get("out"), j.dump(2) + "\n");
  }
  return kExitOk;
}

}  // namespace cli
}  // namespace rtb
