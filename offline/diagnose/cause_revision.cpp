// cause_revision.cpp -- stages 5c-5d of the diagnosis (diagnose.h): once a
// cause is accepted, its model is refitted from the STS start (the joint fit
// began in the basin that had absorbed the missing cause), and an earlier
// cause the new one made redundant is dropped. Also the report entry of an
// accepted cause.
#include <cmath>
#include <cstdio>

#include "diagnose/diagnose_stages.h"
#include "identify/sts_init.h"

namespace rtb {
namespace diag {

// Stage 5c: the accepted cause's joint fit started from the model without
// it, whose core parameters compensated for the missing cause; that basin
// can hold the fit (refgen offset_s6: held-out 4.89% after the offset, 3.40%
// for a fresh RT fit of the offset-corrected records, and two more words were
// accepted for the difference). Refit from the STS start of the records the
// element sees (artefacts removed), extension sizes kept; the refit replaces
// `fit` (true) when its fit misfit is lower by refit_margin.
bool refit_from_sts(const Current &cur, const Context &cx, ExtFitResult &fit) {
  const DiagnoseOptions &opt = cx.opt;
  ExtModel start = cur.model;
  const rtb_params sts = sts_initial_guess(artefact_corrected(cx.fit, cur.model), opt.cells,
                                           opt.alpha0, opt.misfit.fit_from);
  for (ParamId id : core_params()) param_ref(start.p, id) = param_get(sts, id);
  ExtFitResult again;
  try {
    again = fit_extended(cx.fit, start, cur.spec, opt.misfit);
  } catch (const std::exception &) {
    return false;  // the accepted fit stands
  }
  if (!(again.error < (1.0 - opt.refit_margin) * cur.error_fit)) return false;
  if (!opt.quiet)
    std::fprintf(stderr, "diagnose: refit from the STS start found a better basin (fit %.3f%% -> "
                 "%.3f%%)\n", 100 * cur.error_fit, 100 * again.error);
  fit = again;
  return true;
}

// Stage 5d: does each earlier cause still pay now that a later one is in?
// A simpler word can stand in for the real one first and the real one
// follow (refgen relaxation_spectrum_s4: a single Maxwell branch, then the
// spectrum, 1.49% held out; the spectrum refitted without the branch 1.63%,
// floor 1.29%, so the branch is dropped). An earlier cause
// whose removal (its sizes zeroed, the rest refitted) keeps the held-out
// error within what a further cause must gain (gain_suffices with
// min_gain_next, as when it was accepted) is dropped. Only words switched
// off by zeroing their sizes are tried (not a held clearance, slack or the
// spectrum, whose settings come with them). Returns the index dropped, or -1.
int drop_redundant(Current &cur, const Context &cx, DiagnoseResult &R) {
  const DiagnoseOptions &opt = cx.opt;
  for (size_t i = 0; i + 1 < cur.causes.size(); ++i) {
    const Candidate &c = cur.causes[i];
    if (c.configure) continue;
    std::vector<Candidate> keep = cur.causes;
    keep.erase(keep.begin() + (long)i);
    ExtModel start = cur.model;
    for (ParamId id : c.extra) param_ref(start.p, id) = 0.0;
    if (c.delay) start.delay = 0.0;
    if (c.offset) start.offset = 0.0;
    const ExtFitSpec spec = combined_spec(keep, cx.sc);
    ExtFitResult f;
    try {
      f = fit_extended(cx.fit, start, spec, opt.misfit);
    } catch (const std::exception &) {
      continue;
    }
    const Current without = make_current(f.model, spec, keep, cx);
    const double gain = 1.0 - cur.error_holdout_trimmed / without.error_holdout_trimmed;
    if (gain_suffices(gain, without.error_holdout, cur.error_holdout, cx.floor_sel,
                      opt.min_gain_next, opt))
      continue;
    if (!opt.quiet)
      std::fprintf(stderr, "diagnose: %s no longer pays after %s (held-out %.3f%% without it, "
                   "%.3f%% with it): dropped\n", c.name.c_str(), cur.causes.back().name.c_str(),
                   100 * without.error_holdout, 100 * cur.error_holdout);
    R.dropped.push_back({c.name, without.error_holdout, cur.error_holdout});
    R.extended_fit = f;
    cur = without;
    return (int)i;
  }
  return -1;
}

Cause make_cause(const CandidateOutcome &co, const Current &before) {
  Cause c;
  c.cand = co.cand;
  c.description = describe_effect(co.cand, co.fit.model);
  std::vector<std::string> own;
  for (ParamId id : co.cand.extra) own.push_back(param_name(id));
  if (co.cand.delay) own.push_back("delay");
  if (co.cand.offset) own.push_back("offset");
  for (const std::string &n : own)
    for (size_t i = 0; i < co.fit.names.size(); ++i)
      if (co.fit.names[i] == n) {
        c.names.push_back(n);
        c.value.push_back(co.fit.value[(Eigen::Index)i]);
        c.stddev.push_back(co.fit.stddev_valid ? co.fit.stddev[(Eigen::Index)i] : NAN);
      }
  c.error_holdout = co.error_holdout;
  c.gain = 1.0 - co.error_holdout / before.error_holdout;
  return c;
}

}  // namespace diag
}  // namespace rtb
