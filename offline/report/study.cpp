// study.cpp -- run_study(): the numbers of one real-data study. The page
// itself is written by study_page.cpp.
#include "report/study.h"

#include <chrono>
#include <cmath>
#include <cstdio>

#include "diagnose/extended_fit.h"
#include "model/misfit_norms.h"

namespace rtb {

namespace {

MisfitNorms norms_of(const ExtModel &m, const Record &rec, const SimOptions &sim) {
  Eigen::VectorXd F;
  predict_extended(m, rec, sim, ExtFitSpec{}, F, nullptr);
  return misfit_norms(rec.t, std::vector<double>(F.data(), F.data() + F.size()), rec.F, rec.masked);
}

// Start values of a second extension stacked on the chosen one: positive
// parameters need a positive start in their log coordinate.
void seed_extra(const Candidate &c, const DataScales &sc, ExtModel &m) {
  for (ParamId id : c.extra)
    if (param_get(m.p, id) == 0.0) param_ref(m.p, id) = extra_start_value(id, sc);
  if (c.delay && m.delay == 0.0) m.delay = 2.0 * sc.dt;
}

}  // namespace

StudyResult run_study(const StudySpec &spec, const std::string &data_dir, bool quiet) {
  const auto t0 = std::chrono::steady_clock::now();
  StudyResult r;
  std::vector<Record> &fit = r.fit, &val = r.validation;
  for (const std::string &f : spec.fit_files) fit.push_back(read_record_csv(data_dir + "/" + f));
  for (const std::string &f : spec.validation_files) val.push_back(read_record_csv(data_dir + "/" + f));
  apply_preprocess(spec.pre, fit, true);
  apply_preprocess(spec.pre, val, false);
  DiagnoseOptions o = spec.diag;
  o.quiet = quiet;
  r.diag = diagnose(fit, val, o);
  const DiagnoseResult &D = r.diag;

  std::vector<MisfitNorms> fb, fe, vb, ve;
  std::vector<double> fw;
  auto add = [&](const Record &rec, bool validation) {
    FileFigures f;
    f.path = rec.path;
    f.validation = validation;
    const MisfitNorms b = norms_of(D.baseline, rec, o.misfit.sim), e = norms_of(D.extended, rec, o.misfit.sim);
    f.err_base = b.relative_error();
    f.err_ext = e.relative_error();
    f.nrmse_base = b.nrmse_percent();
    f.nrmse_ext = e.nrmse_percent();
    (validation ? vb : fb).push_back(b);
    (validation ? ve : fe).push_back(e);
    if (!validation) fw.push_back(rec.weight);
    r.files.push_back(f);
  };
  for (const Record &rec : fit) add(rec, false);
  for (const Record &rec : val) add(rec, true);
  r.err_fit_base = combined_relative_error(fb, fw);
  r.err_fit_ext = combined_relative_error(fe, fw);
  r.err_val_base = combined_relative_error(vb);
  r.err_val_ext = combined_relative_error(ve);

  // What is left after the extension: each listed candidate stacked on the
  // chosen cause, fitted jointly again.
  if (!D.causes.empty()) {
    const DataScales sc = data_scales(fit);
    std::vector<Candidate> causes;
    for (const Cause &c : D.causes) causes.push_back(c.cand);
    for (const std::string &name : spec.second_stage) {
      for (const Candidate &c : candidate_vocabulary()) {
        bool clash = c.name != name || !c.variant.empty();
        for (const Candidate &k : causes) clash = clash || candidates_conflict(c, k);
        if (clash) continue;
        std::vector<Candidate> with = causes;
        with.push_back(c);
        const ExtFitSpec s2 = combined_spec(with, sc);
        ExtModel m = D.extended;
        if (c.configure) c.configure(m.p, sc);
        seed_extra(c, sc, m);
        if (!quiet) std::fprintf(stderr, "report: %s + %s\n", D.cause.c_str(), name.c_str());
        const ExtFitResult f = fit_extended(fit, m, s2, o.misfit);
        SecondStage st;
        st.name = name;
        st.error_fit = f.error;
        MisfitOptions hold = o.misfit;
        hold.fit_from = 0.0;
        st.error_validation = extended_error(f.model, val, hold);
        st.effect = describe_effect(c, f.model);
        r.second.push_back(st);
      }
    }
  }
  r.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace rtb
