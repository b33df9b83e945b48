// study_page.cpp -- write_study_report(): the markdown page and the PNG
// figures of one real-data study (numbers from run_study()).
#include <algorithm>
#include <cmath>
#include <sstream>

#include "diagnose/extended_fit.h"
#include "io/atomic_file.h"
#include "io/number_text.h"
#include "report/gnuplot_figure.h"
#include "report/study.h"

namespace rtb {

namespace {

std::string g4(double v) { return std::isfinite(v) ? number_text("%.4g", v) : std::string("n/a"); }
std::string pc(double v) { return std::isfinite(v) ? number_text("%.2f", 100.0 * v) : std::string("n/a"); }

std::vector<double> predict(const ExtModel &m, const Record &rec, const SimOptions &sim) {
  Eigen::VectorXd F;
  predict_extended(m, rec, sim, ExtFitSpec{}, F, nullptr);
  return std::vector<double>(F.data(), F.data() + F.size());
}

// Parameter table: baseline (RT) against the extended model, with standard
// deviations ("inf": the data do not determine it).
std::string params_table(const StudyResult &r) {
  const DiagnoseResult &D = r.diag;
  std::ostringstream o;
  o << "| parameter | baseline RT | std. dev. | extended | std. dev. |\n|---|---|---|---|---|\n";
  const Uncertainty &u = D.baseline_fit.uncertainty;
  const ExtFitResult *ext = D.causes.empty() ? nullptr : &D.extended_fit;
  std::vector<std::string> names;
  for (ParamId id : u.ids) names.push_back(param_name(id));
  if (ext)
    for (const std::string &n : ext->names)
      if (std::find(names.begin(), names.end(), n) == names.end()) names.push_back(n);
  for (const std::string &n : names) {
    std::string bv = "-", bs = "-", ev = "-", es = "-";
    for (size_t i = 0; i < u.ids.size(); ++i)
      if (n == param_name(u.ids[i])) {
        bv = g4(param_get(D.baseline.p, u.ids[i]));
        bs = u.valid ? g4(u.stddev[(Eigen::Index)i]) : "n/a";
      }
    if (ext)
      for (size_t i = 0; i < ext->names.size(); ++i)
        if (ext->names[i] == n) {
          ev = g4(ext->value[(Eigen::Index)i]);
          es = ext->stddev_valid ? g4(ext->stddev[(Eigen::Index)i]) : "n/a";
        }
    o << "| " << n << " | " << bv << " | " << bs << " | " << ev << " | " << es << " |\n";
  }
  return o.str();
}

std::string errors_table(const StudyResult &r) {
  std::ostringstream o;
  o << "| record | role | sqrt(J/J0) baseline % | sqrt(J/J0) extended % | NRMSE baseline % | "
       "NRMSE extended % |\n|---|---|---|---|---|---|\n";
  for (const FileFigures &f : r.files)
    o << "| " << base_of(f.path) << " | " << (f.validation ? "validation" : "fit") << " | "
      << pc(f.err_base) << " | " << pc(f.err_ext) << " | " << number_text("%.2f", f.nrmse_base) << " | "
      << number_text("%.2f", f.nrmse_ext) << " |\n";
  o << "| **all fit records** | fit | **" << pc(r.err_fit_base) << "** | **" << pc(r.err_fit_ext)
    << "** | | |\n| **all validation records** | validation | **" << pc(r.err_val_base)
    << "** | **" << pc(r.err_val_ext) << "** | | |\n";
  return o.str();
}

std::string candidates_table(const DiagnoseResult &D) {
  std::ostringstream o;
  o << "| candidate | fit % | validation % | delta BIC | z | gain | verdict |\n"
       "|---|---|---|---|---|---|---|\n";
  for (const CandidateOutcome &c : D.candidates) {
    const bool j = c.joint;
    o << "| " << display_name(c.cand) << " | " << (j ? pc(c.fit.error) : "-") << " | "
      << (j ? pc(c.error_holdout) : "-") << " | " << (j ? number_text("%.4g", c.dbic) : "-") << " | "
      << (j ? number_text("%.3g", c.amplitude_z) : "-") << " | " << (j ? number_text("%.0f%%", 100 * c.gain) : "-")
      << " | " << (c.eligible ? "eligible" : c.why)
      << (c.origin.empty() ? std::string() : " (" + c.origin + ")") << " |\n";
  }
  return o.str();
}

std::string signatures(const DiagnoseResult &D) {
  std::ostringstream o;
  for (const RecordResiduals &rr : D.residuals) {
    o << "- `" << base_of(rr.path) << "` (" << (rr.holdout ? "validation" : "fit")
      << "): residual rms " << g4(rr.rms) << ", mean " << g4(rr.mean)
      << "; rms near reversals " << g4(rr.rms_near_reversal) << " vs elsewhere "
      << g4(rr.rms_elsewhere) << "; best explained by";
    for (size_t k = 0; k < rr.signatures.size() && k < 3; ++k)
      o << (k ? "," : "") << " " << rr.signatures[k].name << " ("
        << number_text("%.0f%%", 100 * rr.signatures[k].explained) << ")";
    o << "\n";
  }
  return o.str();
}

// Figures: a loop per fit record (at most `max_fit`); for each validation
// record force vs time, residuals vs time and the loop, side by side.
std::string figures(const StudySpec &spec, const StudyResult &r, const std::string &dir,
                    size_t max_fit) {
  const DiagnoseResult &D = r.diag;
  const std::string ext_label = "extended (" + D.cause + ")";
  const std::string X = "displacement [" + spec.length_unit + "]";
  const std::string F = "force [" + spec.force_unit + "]";
  std::ostringstream md;
  const std::vector<Record> &fit = r.fit, &val = r.validation;
  const SimOptions &sim = spec.diag.misfit.sim;
  auto series = [](const std::string &l, const std::vector<double> &x, const std::vector<double> &y,
                   const std::string &st) { return Series{l, x, y, st}; };
  const std::string meas = "lines lc rgb '#777777' lw 2", base = "lines lc rgb '#d62728'",
                    extd = "lines lc rgb '#1f77b4'";
  for (size_t k = 0; k < fit.size() && k < max_fit; ++k) {
    const Record &rec = fit[k];
    Figure f;
    f.title = base_of(rec.path) + " (fit)";
    f.xlabel = X;
    f.ylabel = F;
    f.series = {series("measured", rec.x, rec.F, meas),
                series("baseline RT", rec.x, predict(D.baseline, rec, sim), base),
                series(ext_label, rec.x, predict(D.extended, rec, sim), extd)};
    const std::string png = spec.name + "_fit_loop" + std::to_string(k + 1) + ".png";
    render_png(dir + "/" + png, {f});
    md << "![" << f.title << "](" << png << ")\n\n";
  }
  for (size_t k = 0; k < val.size(); ++k) {
    const Record &rec = val[k];
    const std::vector<double> Fb = predict(D.baseline, rec, sim), Fe = predict(D.extended, rec, sim);
    std::vector<double> t, rb, re;
    for (size_t i = 0; i < rec.t.size(); ++i) {
      const double tt = rec.t[i] - rec.t[0];
      if (spec.log_time_validation && !(tt > 0.0)) continue;
      t.push_back(tt);
      rb.push_back(Fb[i] - rec.F[i]);
      re.push_back(Fe[i] - rec.F[i]);
    }
    const size_t off = rec.t.size() - t.size();
    auto tail = [&](const std::vector<double> &v) { return std::vector<double>(v.begin() + (long)off, v.end()); };
    Figure ft, fr, fl;
    ft.title = base_of(rec.path) + " (validation)";
    ft.xlabel = fr.xlabel = spec.log_time_validation ? "time since start [s] (log)" : "time [s]";
    ft.logx = fr.logx = spec.log_time_validation;
    ft.ylabel = F;
    ft.series = {series("measured", t, tail(rec.F), meas), series("baseline RT", t, tail(Fb), base),
                 series(ext_label, t, tail(Fe), extd)};
    fr.title = "residual (model - measured)";
    fr.ylabel = F;
    fr.series = {series("baseline RT", t, rb, base), series(ext_label, t, re, extd)};
    fl.title = "force-displacement";
    fl.xlabel = X;
    fl.ylabel = F;
    fl.series = {series("measured", rec.x, rec.F, meas), series("baseline RT", rec.x, Fb, base),
                 series(ext_label, rec.x, Fe, extd)};
    const std::string png = spec.name + "_validation" + std::to_string(k + 1) + ".png";
    render_png(dir + "/" + png, {ft, fr, fl});
    md << "![" << ft.title << "](" << png << ")\n\n";
  }
  return md.str();
}

}  // namespace

void write_study_report(const StudySpec &spec, const StudyResult &r, const std::string &dir) {
  const DiagnoseResult &D = r.diag;
  std::ostringstream md;
  md << "# " << spec.title << "\n\n"
     << "Generated by `make report` (`build/rtb report`); do not edit by hand.\n\n"
     << spec.intro << "\n\n## Records\n\n";
  md << "Fit (identification):";
  for (const std::string &f : spec.fit_files) md << " `" << f << "`";
  md << "\n\nValidation (held out, never fitted):";
  for (const std::string &f : spec.validation_files) md << " `" << f << "`";
  md << "\n\nPreprocessing (also in the JSON of every command): `" << preprocess_json(spec.pre).dump()
     << "`\n\n## Verdict\n\n" << D.verdict << "\n\n"
     << "Error sqrt(J/J0) of eq. (27), all validation records: baseline RT "
     << pc(r.err_val_base) << "%, extended " << pc(r.err_val_ext) << "%. "
     << "The seed paper reports 3.11% on its own bushing (Table 6). The tests "
        "(`RealData.*`) hold its validation error under " << pc(spec.validation_bound) << "%.\n\n"
     << "## Parameters\n\nUnits: " << spec.length_unit << ", " << spec.force_unit
     << ", s. Standard deviations from the Gauss-Newton information (white noise assumed; "
        "real residuals are correlated, so they are lower bounds). \"inf\": the data do not "
        "determine the parameter (e.g. a stiffness driven to zero).\n\n"
     << params_table(r) << "\n## Errors per record\n\n"
     << "sqrt(J/J0) is eq. (27); NRMSE is 100 rms(F_model - F_measured) / (max F - min F).\n\n"
     << errors_table(r) << "\n## Candidates (diagnosis)\n\n" << candidates_table(D) << "\n";
  if (!r.second.empty()) {
    md << "## After the extension: does a second one help?\n\n"
       << "Each row stacks one more extension on `" << D.cause << "` and fits all jointly.\n\n"
       << "| added | fit % | validation % | effect |\n|---|---|---|---|\n";
    for (const SecondStage &s : r.second)
      md << "| " << s.name << " | " << pc(s.error_fit) << " | " << pc(s.error_validation) << " | "
         << s.effect << " |\n";
    md << "\n";
  }
  md << "## Residual signatures of the baseline\n\n" << signatures(D) << "\n";
  md << "## Figures\n\nGrey: measured; red: baseline RT; blue: extended model.\n\n"
     << figures(spec, r, dir, 4);
  md << "Wall times: [" << spec.name << "_timings.md](" << spec.name << "_timings.md).\n";
  write_file_atomic(dir + "/" + spec.name + ".md", md.str());
  std::ostringstream tm;
  tm << "# " << spec.title << ": wall times\n\nThis machine, `make report`; these differ from run "
        "to run, unlike every other generated file.\n\n"
     << "| step | s |\n|---|---|\n| baseline identification | "
     << number_text("%.1f", D.baseline_fit.wall_seconds) << " |\n| diagnosis (all candidates) | "
     << number_text("%.1f", D.wall_seconds) << " |\n| whole study | " << number_text("%.1f", r.wall_seconds) << " |\n";
  write_file_atomic(dir + "/" + spec.name + "_timings.md", tm.str());
}

}  // namespace rtb
