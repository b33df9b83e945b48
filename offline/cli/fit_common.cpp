// fit_common.cpp -- see fit_common.h.
#include "cli/fit_common.h"

#include <cmath>
#include <cstdio>
#include <sstream>

#include "io/params_json.h"

namespace rtb {
namespace cli {

std::vector<OptionSpec> fit_option_specs(std::vector<OptionSpec> extra) {
  std::vector<OptionSpec> o = {
      {"data", "FILE", "record CSV (time,displacement,force); repeat for several", true, true},
      {"cells", "N", "number of RT cells (default 15)"},
      {"method", "M", "trust-region (default) or bfgs"},
      {"init", "sts|friction|FILE", "start point: STS loop inversion (default), a one-slider friction device, or a parameter JSON"},
      {"alpha0", "A", "alpha of the STS start, eq. (26) (default 0.2)"},
      {"fit-from", "S", "fit only samples from t0 + S on (stabilized cycles)"},
      {"ramp-time", "S", "ramp from rest to x[0] for records not starting at 0 (default auto)"},
      {"start", "auto|ramp|hold", "how the model reaches x[0] before the record: ramp from rest, or ramp and hold (a relaxed preload); auto: hold when |x[0]| > 5% of the record's reach"},
      {"free", "LIST", "parameters to fit, comma separated (default K0,Kpa,Kr,C0,alpha)"},
      {"reg-weight", "W", "Tikhonov term of eq. (11): R_i = W / |p0_i| toward the start p0"},
      {"max-iter", "N", "optimizer iteration limit (default 200)"},
      {"quiet", nullptr, "no progress on stderr"},
  };
  const std::vector<OptionSpec> pre = preprocess_option_specs();
  o.insert(o.end(), pre.begin(), pre.end());
  o.insert(o.end(), extra.begin(), extra.end());
  return o;
}

std::vector<ParamId> parse_param_list(const std::string &csv) {
  std::vector<ParamId> out;
  std::stringstream ss(csv);
  std::string item;
  while (std::getline(ss, item, ',')) {
    bool found = false;
    for (int i = 0; i < P_COUNT; ++i)
      if (item == param_name(ParamId(i))) {
        out.push_back(ParamId(i));
        found = true;
      }
    if (!found) throw UsageError("--free: unknown parameter '" + item + "'");
  }
  if (out.empty()) throw UsageError("--free: empty list");
  return out;
}

FitSetup parse_fit_setup(const Args &a) {
  FitSetup fs;
  const long cells = a.get_int("cells", RTB_DEFAULT_CELLS);
  if (cells < 1 || cells > RTB_MAX_CELLS)
    throw UsageError("--cells must be between 1 and " + std::to_string(RTB_MAX_CELLS));
  fs.opt.method = parse_method(a.get("method", "trust-region"));
  fs.opt.misfit.fit_from = a.get_double("fit-from", 0.0);
  if (fs.opt.misfit.fit_from < 0.0) throw UsageError("--fit-from must be >= 0");
  fs.opt.misfit.sim = sim_options_from(a);
  fs.opt.max_iter = (int)a.get_int("max-iter", 200);
  if (a.has("free")) fs.opt.free = parse_param_list(a.get("free"));
  fs.alpha0 = a.get_double("alpha0", 0.2);
  if (!(fs.alpha0 > 0.0 && fs.alpha0 < 1.0)) throw UsageError("--alpha0 must be in (0,1)");
  for (const std::string &path : a.all("data")) fs.recs.push_back(read_record_csv(path));
  fs.pre = preprocess_from(a);
  resolve_force_sign(fs.pre, fs.recs, a.has("quiet"));
  apply_preprocess(fs.pre, fs.recs, true);
  fs.init = a.get("init", "sts");
  if (fs.init == "sts") {
    fs.start = sts_initial_guess(fs.recs, (int)cells, fs.alpha0, fs.opt.misfit.fit_from,
                                 &fs.features, &fs.sts, &fs.sts_note);
    fs.sts_used = true;
  } else if (fs.init == "friction") {
    fs.start = friction_initial_guess(fs.recs, (int)cells, fs.opt.misfit.fit_from);
  } else {
    fs.start = read_params_json(fs.init);
    if (fs.start.model != RTB_MODEL_RT) throw InputError(fs.init + ": identify needs an \"rt\" model");
    if (a.has("cells")) fs.start.cells = (int)cells;
  }
  fs.reg_weight = a.get_double("reg-weight", 0.0);
  if (fs.reg_weight < 0.0) throw UsageError("--reg-weight must be >= 0");
  if (fs.reg_weight > 0.0)
    for (ParamId id : fs.opt.free) {
      const double v = param_get(fs.start, id);
      fs.opt.misfit.p0[id] = v;
      fs.opt.misfit.R[id] = fs.reg_weight / (v != 0.0 ? std::fabs(v) : 1.0);
    }
  return fs;
}

IdentifyResult run_fit(const FitSetup &fs, bool quiet) {
  IdentifyOptions o = fs.opt;
  o.quiet = quiet;
  if (!quiet && fs.sts_used) {
    const LoopFeatures &f = fs.features;
    std::fprintf(stderr,
                 "STS start (section 5.4): Tg1 %.6g  Tg2 %.6g  Fmax %.6g  Xmax %.6g  V0 %.6g  "
                 "(%d cycles)\n  STS: K0 %.6g  Kpa %.6g  Kr %.6g  Ff %.6g %s\n",
                 f.Tg1, f.Tg2, f.Fmax, f.Xmax, f.V0, f.cycles, fs.sts.K0, fs.sts.Kpa, fs.sts.Kr,
                 fs.sts.Ff, fs.sts_note.c_str());
  }
  if (!quiet) std::fprintf(stderr, "identify: %s, %zu record(s)\n", method_name(o.method), fs.recs.size());
  return identify(fs.recs, fs.start, o);
}

void print_fit_summary(const IdentifyResult &r, const FitSetup &fs) {
  std::printf("%-12s %14s %14s %12s\n", "parameter", "start", "identified", "std.dev");
  for (size_t i = 0; i < fs.opt.free.size(); ++i) {
    const ParamId id = fs.opt.free[i];
    std::printf("%-12s %14.6g %14.6g %12.3g\n", param_name(id), param_get(r.start, id),
                param_get(r.params, id),
                r.uncertainty.valid ? r.uncertainty.stddev[(Eigen::Index)i] : NAN);
  }
  std::printf("error sqrt(J/J0): %.4f %% -> %.4f %%  (%s, %d iterations, %d forward + %d adjoint "
              "solves, %d tangent sweeps, %.2f s)%s\n",
              100 * r.error_start, 100 * r.error, method_name(r.method), r.iterations,
              r.forward_solves, r.adjoint_solves, r.tangent_sweeps, r.wall_seconds,
              r.converged ? "" : "  NOT CONVERGED");
}

nlohmann::ordered_json uncertainty_json(const Uncertainty &u) {
  nlohmann::ordered_json j;
  j["valid"] = u.valid;
  j["noise_sigma"] = u.noise_sigma;
  nlohmann::ordered_json sd, corr;
  for (size_t i = 0; i < u.ids.size(); ++i) {
    sd[param_name(u.ids[i])] = u.valid ? u.stddev[(Eigen::Index)i] : 0.0;
    nlohmann::ordered_json row;
    for (size_t k = 0; k < u.ids.size(); ++k)
      row[param_name(u.ids[k])] = u.valid ? u.correlation((Eigen::Index)i, (Eigen::Index)k) : 0.0;
    corr[param_name(u.ids[i])] = row;
  }
  j["stddev"] = sd;
  j["correlation"] = corr;
  j["note"] = "Gauss-Newton (Fisher) covariance from the residuals, white-noise assumption";
  return j;
}

nlohmann::ordered_json fit_result_json(const IdentifyResult &r, const FitSetup &fs) {
  nlohmann::ordered_json j = params_to_json(r.params);
  j["error"] = r.error;
  j["error_start"] = r.error_start;
  j["error_per_file"] = r.error_per_record;
  j["J"] = r.J;
  j["J0"] = r.J0;
  j["method"] = method_name(r.method);
  j["converged"] = r.converged;
  j["message"] = r.message;
  j["iterations"] = r.iterations;
  j["forward_solves"] = r.forward_solves;
  j["adjoint_solves"] = r.adjoint_solves;
  j["tangent_sweeps"] = r.tangent_sweeps;
  j["wall_time_s"] = r.wall_seconds;
  j["uncertainty"] = uncertainty_json(r.uncertainty);
  nlohmann::ordered_json files = nlohmann::ordered_json::array();
  for (const Record &rec : fs.recs)
    files.push_back({{"path", rec.path}, {"sha256", rec.sha256}, {"samples", rec.t.size()}});
  j["data"] = files;
  j["start"] = params_to_json(r.start);
  j["init"] = fs.init;
  if (fs.sts_used)
    j["sts_features"] = {{"Tg1", fs.features.Tg1}, {"Tg2", fs.features.Tg2},
                         {"Fmax", fs.features.Fmax}, {"Xmax", fs.features.Xmax},
                         {"V0", fs.features.V0},     {"cycles", fs.features.cycles},
                         {"alpha0", fs.alpha0},      {"K0_S", fs.sts.K0},
                         {"Kpa_S", fs.sts.Kpa},      {"Kr_S", fs.sts.Kr},
                         {"Ff", fs.sts.Ff}};
  j["options"] = {{"fit_from", fs.opt.misfit.fit_from},
                  {"ramp_time", fs.opt.misfit.sim.ramp_time},
                  {"start", start_mode_name(fs.opt.misfit.sim.start)},
                  {"reg_weight", fs.reg_weight}};
  j["preprocessing"] = preprocess_json(fs.pre);
  j["tool"] = tool_version();
  return j;
}

HeaderInfo header_info_for(const IdentifyResult &r, const FitSetup &fs, const std::string &name) {
  HeaderInfo hi;
  hi.name = name;
  hi.tool_version = tool_version();
  for (size_t i = 0; i < fs.recs.size(); ++i) {
    HeaderDataFile f;
    f.path = fs.recs[i].path;
    f.sha256 = fs.recs[i].sha256;
    f.samples = fs.recs[i].t.size();
    if (i < r.error_per_record.size()) f.error = r.error_per_record[i];
    hi.data_files.push_back(f);
  }
  hi.error = r.error;
  if (r.uncertainty.valid)
    for (size_t i = 0; i < r.uncertainty.ids.size(); ++i)
      hi.std_devs[param_name(r.uncertainty.ids[i])] = r.uncertainty.stddev[(Eigen::Index)i];
  hi.provenance.push_back(std::string("method ") + method_name(r.method) + ", " +
                          std::to_string(r.iterations) + " iterations");
  if (fs.pre.active())
    hi.provenance.push_back("preprocessing " + preprocess_json(fs.pre).dump());
  return hi;
}

}  // namespace cli
}  // namespace rtb
