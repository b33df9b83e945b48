// diagnose_report.cpp -- see diagnose_report.h.
#include "cli/diagnose_report.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sys/stat.h>

#include "cli/cli.h"
#include "cli/fit_common.h"
#include "io/header_writer.h"
#include "io/params_json.h"

namespace rtb {
namespace cli {

namespace {

nlohmann::ordered_json ext_params_json(const ExtFitResult &f) {
  nlohmann::ordered_json j;
  for (size_t i = 0; i < f.names.size(); ++i) {
    nlohmann::ordered_json e = {{"value", f.value[(Eigen::Index)i]}};
    if (f.stddev_valid) e["stddev"] = f.stddev[(Eigen::Index)i];
    j[f.names[i]] = e;
  }
  return j;
}

nlohmann::ordered_json num(double v) {
  return std::isfinite(v) ? nlohmann::ordered_json(v) : nlohmann::ordered_json(nullptr);
}

}  // namespace

void print_diagnosis(const DiagnoseResult &R) {
  std::printf("%-2s %-22s %10s %10s %10s %8s %6s  %s\n", "r", "candidate", "fit %", "holdout %",
              "dBIC", "z", "gain", "verdict");
  std::printf("%-2s %-22s %10.3f %10.3f   (noise floor %.3f%% / %.3f%%)\n", "", "(plain RT)",
              100 * R.baseline_error_fit, 100 * R.baseline_error_holdout, 100 * R.floor.error_fit,
              100 * R.floor.error_holdout);
  for (const CandidateOutcome &c : R.candidates) {
    const std::string name = display_name(c.cand);
    std::printf("%-2d %-22s %10.3f %10.3f %10.4g %8.3g %5.0f%%  %s\n", c.round, name.c_str(),
                100 * c.fit.error, 100 * c.error_holdout, c.dbic, c.amplitude_z, 100 * c.gain,
                c.eligible ? "eligible" : c.why.c_str());
    if (!c.origin.empty()) std::printf("%-2s %-22s (%s)\n", "", "", c.origin.c_str());
  }
  if (!R.residuals.empty()) {
    const RecordResiduals &r = R.residuals.front();
    std::printf("baseline residual signatures (%s):", r.path.c_str());
    for (size_t i = 0; i < r.signatures.size() && i < 3; ++i)
      std::printf(" %s %.0f%%", r.signatures[i].name.c_str(), 100 * r.signatures[i].explained);
    std::printf("\n");
  }
  std::printf("%s  [%.1f s]\n", R.verdict.c_str(), R.wall_seconds);
}

nlohmann::ordered_json causes_json(const DiagnoseResult &R) {
  nlohmann::ordered_json a = nlohmann::ordered_json::array();
  for (const Cause &c : R.causes) {
    nlohmann::ordered_json e;
    e["name"] = c.cand.name;
    if (!c.cand.variant.empty()) e["variant"] = c.cand.variant;
    e["physical"] = c.cand.physical;
    e["description"] = c.description;
    nlohmann::ordered_json sizes;
    for (size_t i = 0; i < c.names.size(); ++i)
      sizes[c.names[i]] = {{"value", c.value[i]}, {"stddev", num(c.stddev[i])}};
    e["size"] = sizes;
    e["gain"] = num(c.gain);
    e["error_holdout"] = num(c.error_holdout);
    if (c.paired) e["paired"] = true;  // stage 5e: neither paid alone at the baseline
    if (c.on_fit_records) {  // the held-out records were at their floor
      e["judged_on"] = "fit";
      e["error_fit"] = num(c.error_fit);
      e["error_fit_before"] = num(c.error_fit_before);
    }
    a.push_back(e);
  }
  return a;
}

nlohmann::ordered_json diagnosis_json(const DiagnoseResult &R, const std::vector<Record> &fit,
                                      const std::vector<Record> &hold) {
  nlohmann::ordered_json j;
  j["cause"] = R.cause;
  j["causes"] = causes_json(R);
  j["imposed"] = R.imposed;  // --causes: a what-if, not a diagnosis
  // Earlier causes a later one made redundant (stage 5d).
  nlohmann::json dropped = nlohmann::json::array();
  for (const DiagnoseResult::Dropped &d : R.dropped)
    dropped.push_back({{"name", d.name}, {"error_holdout_without", d.error_without},
                       {"error_holdout_with", d.error_with}});
  j["dropped"] = dropped;
  // Causes withdrawn because what they leave is a slow trend over time.
  nlohmann::json withdrawn = nlohmann::json::array();
  for (const Cause &c : R.withdrawn)
    withdrawn.push_back({{"name", c.cand.name}, {"description", c.description},
                         {"error_holdout", c.error_holdout}});
  j["withdrawn"] = withdrawn;
  nlohmann::ordered_json clip = nlohmann::ordered_json::array();
  for (const ClippedRecord &c : R.clipping)
    clip.push_back({{"file", c.file},
                    {"top", c.top},
                    {"bottom", c.bottom},
                    {"level_top", c.level_top},
                    {"level_bottom", c.level_bottom},
                    {"samples", c.samples}});
  j["clipping"] = clip;
  nlohmann::ordered_json spikes = nlohmann::ordered_json::array();
  for (const SpikedRecord &s : R.spikes)
    spikes.push_back({{"file", s.file},
                      {"samples", s.spikes},
                      {"largest", s.largest},
                      {"largest_sigmas", s.largest_sigmas}});
  j["spikes"] = spikes;
  j["verdict"] = R.verdict;
  j["physical"] = R.causes.empty() || R.causes.front().cand.physical;
  j["noise_floor"] = {{"error_fit", R.floor.error_fit},
                      {"error_holdout", R.floor.error_holdout},
                      {"sigma_fit", R.floor.sigma_fit},
                      {"sigma_holdout", R.floor.sigma_holdout},
                      {"baseline_ratio_holdout", num(R.baseline_error_holdout / R.floor.error_holdout)},
                      {"extended_ratio_holdout", num(R.extended_error_holdout / R.floor.error_holdout)},
                      {"noise_correlation", R.floor.correlation},
                      {"method", R.floor.correlation > 0.0
                                     ? "1.4826 MAD of the 4th differences of the residual at lags "
                                       "1-4, fitted with band-limited noise (correlation a^|k|)"
                                     : "1.4826 MAD of the 4th differences of the residual / sqrt(70)"}};
  j["displacement_filter"] = {{"cutoff_hz", R.denoise.cutoff_hz},
                              {"record_cutoff_hz", R.denoise.record_cutoff_hz},
                              {"sigma_x", R.denoise.sigma_x},
                              {"sigma_F", R.denoise.sigma_F},
                              {"noise_ratio", R.denoise.noise_ratio},
                              {"correlation", R.denoise.correlation}};
  j["residual_above_floor"] = R.residual_above_floor;
  if (R.residual_above_floor)
    j["signature"] = {{"text", R.signature.text},
                      {"dominant_hz", R.signature.dominant_hz},
                      {"dominant_share", R.signature.dominant_share},
                      {"input_share_at_dominant", R.signature.input_share},
                      {"trend_share", R.signature.trend_share},
                      {"stiffness_drift_share", R.signature.drift_share},
                      {"record_scale_share", R.signature.record_scale_share},
                      {"record_scale_spread", R.signature.record_scale_spread},
                      {"where", R.signature.where}};
  j["baseline"] = {{"params", params_to_json(R.baseline.p)},
                   {"error_fit", R.baseline_error_fit},
                   {"error_holdout", num(R.baseline_error_holdout)},
                   {"uncertainty", uncertainty_json(R.baseline_fit.uncertainty)}};
  nlohmann::ordered_json ext = {{"params", params_to_json(R.extended.p)},
                                {"error_fit", R.extended_error_fit},
                                {"error_holdout", num(R.extended_error_holdout)},
                                {"delay", R.extended.delay},
                                {"delay_lowpass", R.extended.delay_lowpass},
                                {"delay_lead", R.extended.delay_lead},
                                {"offset", R.extended.offset}};
  if (!R.causes.empty()) ext["fitted"] = ext_params_json(R.extended_fit);
  nlohmann::ordered_json recs = nlohmann::ordered_json::array();
  for (const RecordFigures &f : R.extended_records)
    recs.push_back({{"file", f.file}, {"role", f.holdout ? "holdout" : "fit"},
                    {"error", num(f.error)}, {"nrmse", num(f.nrmse)}});
  ext["records"] = recs;
  j["extended"] = ext;
  j["gain"] = num(R.gain);
  j["baseline_error_holdout_trimmed"] = num(R.baseline_error_holdout_trimmed);
  j["extended_error_holdout_trimmed"] = num(R.extended_error_holdout_trimmed);
  j["selection"] = "per round, the lowest trimmed held-out error among candidates with z >= 3, "
                   "delta BIC >= 10, trimmed gain >= 15% (10% for later causes) or, near the noise "
                   "floor, >= 5% removing half the excess over the floor, not contradicted by the data, "
                   "fewer parameters preferred within 10%; rounds continue while the residual is above 1.3x the noise floor";
  j["holdout_used"] = R.has_holdout;
  nlohmann::ordered_json cs = nlohmann::ordered_json::array();
  for (const CandidateOutcome &c : R.candidates) {
    nlohmann::ordered_json e;
    e["name"] = c.cand.name;
    if (!c.cand.variant.empty()) e["variant"] = c.cand.variant;
    e["round"] = c.round;
    e["physical"] = c.cand.physical;
    e["fitted_jointly"] = c.joint;
    std::string amp = c.cand.extra.empty()
                          ? (c.cand.delay ? "delay" : (c.cand.offset ? "offset" : c.cand.name))
                          : param_name(c.cand.extra[0]);
    if (c.joint) {
      e["params"] = ext_params_json(c.fit);
      e["error_fit"] = num(c.fit.error);
    } else {  // screened out: the score-test estimate, the model held
      e["params"] = {{amp, {{"value", c.screen.value}}}};
      e["error_fit"] = num(R.baseline_error_fit * std::sqrt(std::fmax(0.0, 1.0 - c.screen.dJ)));
    }
    e["screen"] = {{"amplitude", c.screen.value}, {"z", num(c.screen.z)},
                   {"misfit_reduction", num(c.screen.dJ)},
                   {"model_reduction", num(c.screen.dJ_model)}, {"plausible", c.screen.plausible}};
    e["error_holdout"] = num(c.error_holdout);
    e["error_holdout_trimmed"] = num(c.error_holdout_trimmed);
    e["criterion"] = {{"delta_bic", num(c.dbic)}, {"holdout_gain", num(c.gain)},
                      {"amplitude_z", num(c.amplitude_z)}};
    e["eligible"] = c.eligible;
    if (!c.eligible) e["why_not"] = c.why;
    if (!c.origin.empty()) e["origin"] = c.origin;
    e["iterations"] = c.fit.iterations;
    e["seconds"] = {{"screen", c.screen.seconds}, {"joint_fit", c.fit_seconds}};
    cs.push_back(e);
  }
  j["candidates"] = cs;
  j["residuals"] = residuals_json(R.residuals);
  nlohmann::ordered_json files = nlohmann::ordered_json::array();
  for (const Record &r : fit) files.push_back({{"path", r.path}, {"sha256", r.sha256}, {"role", "fit"}});
  for (const Record &r : hold) files.push_back({{"path", r.path}, {"sha256", r.sha256}, {"role", "holdout"}});
  j["data"] = files;
  j["wall_time_s"] = R.wall_seconds;
  j["time_split_s"] = {{"baseline", R.seconds_baseline}, {"screen", R.seconds_screen},
                       {"joint_fits", R.seconds_joint}};
  j["tool"] = tool_version();
  return j;
}

std::string diagnosis_header(const DiagnoseResult &R, const std::vector<Record> &fit,
                             const std::string &name) {
  HeaderInfo hi;
  hi.name = name;
  hi.tool_version = tool_version();
  for (const Record &r : fit) {
    HeaderDataFile f;
    f.path = r.path;
    f.sha256 = r.sha256;
    f.samples = r.t.size();
    hi.data_files.push_back(f);
  }
  hi.error = R.extended_error_fit;
  hi.provenance.push_back("rtb diagnose: " + R.verdict);
  if (!R.causes.empty()) {
    const ExtFitResult &f = R.extended_fit;
    if (f.stddev_valid)
      for (size_t i = 0; i < f.names.size(); ++i)
        hi.std_devs[f.names[i]] = f.stddev[(Eigen::Index)i];
    bool artefact = false;
    for (const Cause &c : R.causes) artefact = artefact || !c.cand.physical;
    if (artefact)
      hi.provenance.push_back("measurement artefact corrected in the data (delay " +
                              std::to_string(R.extended.delay) + " s" +
                              (R.extended.delay_lowpass ? " as a first-order low-pass" : "") +
                              (R.extended.delay_lead ? " of the displacement channel" : "") +
                              ", offset " +
                              std::to_string(R.extended.offset) + "); not part of the element");
  }
  return emit_parameter_header(R.extended.p, hi);
}

void write_diagnosis_plots(const DiagnoseResult &R, const std::vector<Record> &fit,
                           const std::vector<Record> &hold, const std::string &dir) {
  ::mkdir(dir.c_str(), 0755);
  MisfitOptions mo;
  ExtFitSpec none;
  none.free.clear();
  int k = 0;
  std::string script = "set terminal pngcairo size 900,600\nset datafile separator ','\n";
  for (const std::vector<Record> *set : {&fit, &hold})
    for (const Record &rec : *set) {
      Eigen::VectorXd Fb, Fe;
      predict_extended(R.baseline, rec, mo.sim, none, Fb, nullptr);
      predict_extended(R.extended, rec, mo.sim, none, Fe, nullptr);
      std::string csv = "time,displacement,measured,baseline,extended\n";
      char line[256];
      for (size_t i = 0; i < rec.t.size(); ++i) {
        std::snprintf(line, sizeof line, "%.9g,%.9g,%.9g,%.9g,%.9g\n", rec.t[i], rec.x[i], rec.F[i],
                      Fb[(Eigen::Index)i], Fe[(Eigen::Index)i]);
        csv += line;
      }
      const std::string base = dir + "/record" + std::to_string(k++);
      write_file_atomic(base + ".csv", csv);
      script += "set output '" + base + "_loop.png'\nset title '" + rec.path +
                " (" + (set == &fit ? "fit" : "holdout") + ")' noenhanced\nset xlabel 'displacement'\n"
                "set ylabel 'force'\nplot '" + base + ".csv' skip 1 u 2:3 w l t 'measured', '' skip 1 u 2:4 w l t 'RT', "
                "'' skip 1 u 2:5 w l t 'extended: " + R.cause + "'\n";
      script += "set output '" + base + "_residual.png'\nset xlabel 'time'\nset ylabel 'measured - model'\n"
                "plot '" + base + ".csv' skip 1 u 1:($3-$4) w l t 'RT', '' skip 1 u 1:($3-$5) w l t 'extended'\n";
    }
  write_file_atomic(dir + "/plots.gp", script);
  if (std::system("command -v gnuplot >/dev/null 2>&1") == 0) {
    const std::string cmd = "gnuplot '" + dir + "/plots.gp' 2>/dev/null";
    if (std::system(cmd.c_str()) != 0) std::fprintf(stderr, "rtb diagnose: gnuplot failed\n");
  }
}

}  // namespace cli
}  // namespace rtb
