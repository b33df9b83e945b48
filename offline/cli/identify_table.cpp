// identify_table.cpp -- see identify_table.h.
#include "cli/identify_table.h"

#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli/fit_common.h"
#include "freq/table_fit.h"
#include "io/header_writer.h"
#include "io/params_json.h"

namespace rtb {
namespace cli {

namespace {

nlohmann::ordered_json table_json(const TableFitResult &tr, const DynStiffTable &t) {
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (size_t k = 0; k < t.rows.size(); ++k) {
    const DynStiffRow &r = t.rows[k];
    rows.push_back({{"frequency", r.freq}, {"amplitude", r.amp}, {"stiffness", r.stiffness},
                    {"loss_angle_deg", r.loss_angle_deg}, {"weight", r.weight},
                    {"model_stiffness", tr.model[k].stiffness},
                    {"model_loss_angle_deg", tr.model[k].loss_angle_deg},
                    {"steps_per_cycle", tr.disc[k].steps_per_cycle},
                    {"cycles", tr.disc[k].cycles}});
  }
  return {{"path", t.path},
          {"sha256", t.sha256},
          {"rows", rows},
          {"rms_stiffness_error", tr.rms_stiffness_rel},
          {"max_stiffness_error", tr.max_stiffness_rel},
          {"rms_loss_angle_error_deg", tr.rms_loss_deg},
          {"max_loss_angle_error_deg", tr.max_loss_deg},
          {"discretization_check", {{"stiffness", tr.disc_check_rel}, {"loss_angle_deg", tr.disc_check_deg},
                                    {"refits", tr.refits}}},
          {"misfit", "1/2 sum w [(ln|K*| - ln K)^2 + (arg K* - delta [rad])^2]; error = rms "
                     "residual (relative error of K*)"}};
}

}  // namespace

int identify_from_table(const Args &a) {
  const DynStiffTable t = read_dynstiff_table(a.get("dynstiff"));
  const long cells = a.get_int("cells", RTB_DEFAULT_CELLS);
  if (cells < 1 || cells > RTB_MAX_CELLS)
    throw UsageError("--cells must be between 1 and " + std::to_string(RTB_MAX_CELLS));
  FitSetup fs;  // no records: the table stands in for them in the outputs
  fs.init = a.get("init", "table");
  std::string note;
  if (fs.init == "table" || fs.init == "sts") {
    fs.init = "table";
    fs.start = table_initial_guess(t, (int)cells, &note);
  } else {
    fs.start = read_params_json(fs.init);
    if (fs.start.model != RTB_MODEL_RT) throw InputError(fs.init + ": identify needs an \"rt\" model");
    if (a.has("cells")) fs.start.cells = (int)cells;
  }
  TableFitOptions o;
  if (a.has("free")) o.free = parse_param_list(a.get("free"));
  o.method = parse_method(a.get("method", "trust-region"));
  o.max_iter = (int)a.get_int("max-iter", 100);
  o.quiet = a.has("quiet");
  fs.opt.free = o.free;
  fs.opt.method = o.method;
  if (!o.quiet) std::fprintf(stderr, "identify --dynstiff: %zu rows; %s\n", t.rows.size(), note.c_str());
  const TableFitResult tr = fit_dynstiff_table(t, fs.start, o);
  const IdentifyResult &r = tr.fit;
  print_fit_summary(r, fs);
  std::printf("table: stiffness rms %.3f %% (max %.3f %%), loss angle rms %.3f deg (max %.3f deg)\n",
              100 * tr.rms_stiffness_rel, 100 * tr.max_stiffness_rel, tr.rms_loss_deg, tr.max_loss_deg);
  nlohmann::ordered_json j = fit_result_json(r, fs);
  j["error_per_file"] = nlohmann::ordered_json::array();
  j["dynstiff_table"] = table_json(tr, t);
  if (!note.empty()) j["table_start"] = note;
  write_file_atomic(a.get("out"), j.dump(2) + "\n");
  if (a.has("header")) {
    HeaderInfo hi = header_info_for(r, fs, a.get("name", "rtb_identified"));
    HeaderDataFile f;
    f.path = t.path;
    f.sha256 = t.sha256;
    f.samples = t.rows.size();
    f.error = r.error;
    hi.data_files.push_back(f);
    hi.provenance.push_back("dynamic-stiffness table fit (rtb identify --dynstiff)");
    write_file_atomic(a.get("header"), emit_parameter_header(r.params, hi));
  }
  return kExitOk;
}

}  // namespace cli
}  // namespace rtb
