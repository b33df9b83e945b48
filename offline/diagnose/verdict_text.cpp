// verdict_text.cpp -- stage 6 of the diagnosis (diagnose.h): the verdict
// sentence (causes, or `none` at the noise floor, or `unexplained` with the
// residual's signature) and the per-record figures of the report.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "diagnose/diagnose_stages.h"
#include "io/number_text.h"

namespace rtb {
namespace diag {

namespace {

std::string pct(double e) { return number_text("%.2f%%", 100.0 * e); }

}  // namespace

std::string verdict_text(const DiagnoseResult &R) {
  std::string v = R.imposed ? "imposed causes (what-if, not selected): " : "cause: ";
  const std::string clipped = clipping_text(R.clipping, R.extended_records.size());
  const std::string spiked = spikes_text(R.spikes, R.extended_records.size());
  if (R.causes.empty() && !clipped.empty()) {
    v += "unexplained (" + clipped + (spiked.empty() ? "" : "; " + spiked) + ")";
  } else if (R.causes.empty() && !spiked.empty()) {
    v += "unexplained (" + spiked + ")";
  } else if (R.causes.empty() && R.cause == "unexplained") {
    char b[200];
    std::snprintf(b, sizeof b, "unexplained (residual %.1fx the noise floor of %s; %s): ",
                  R.baseline_error_holdout / std::max(R.floor.error_holdout, 1e-300),
                  pct(R.floor.error_holdout).c_str(),
                  R.withdrawn.empty() ? "no candidate removes it" : "no time-invariant word removes it");
    v += b + R.signature.text;
    if (!R.withdrawn.empty()) {
      v += "; ";
      for (size_t i = 0; i < R.withdrawn.size(); ++i) v += (i ? " + " : "") + R.withdrawn[i].cand.name;
      std::snprintf(b, sizeof b,
                    " would take it to %s but leave that trend: a time-invariant word only "
                    "compensates it, so none is named",
                    pct(R.withdrawn.back().error_holdout).c_str());
      v += b;
    }
  } else if (R.causes.empty()) {
    v += "none (the residual is at the noise floor of " + pct(R.floor.error_holdout) + ")";
  } else {
    for (size_t i = 0; i < R.causes.size(); ++i) v += (i ? " + " : "") + R.causes[i].description;
    if (R.causes.front().paired) v += " (the first two as a pair: neither pays alone)";
  }
  if (R.extended.p.cells != R.baseline.p.cells) {  // other_cells_explain
    char b[160];
    std::snprintf(b, sizeof b, ", on a chain of %d cells (the data prefer it to %d)",
                  (int)R.extended.p.cells, (int)R.baseline.p.cells);
    v += b;
  }
  v += std::string("; ") + (R.has_holdout ? "holdout" : "fit") + " error " +
       pct(R.baseline_error_holdout);
  v += std::string(" -> ") + pct(R.extended_error_holdout);
  char g[200];
  std::snprintf(g, sizeof g, " (gain %.0f%%)", 100.0 * R.gain);
  v += g;
  // The causes were selected on the held-out error trimmed of isolated
  // spikes. Where the plain figure rises while the trimmed one falls, a few
  // samples carry the difference (an inertia term at ideal input corners,
  // where the measured force has one-sample spikes the model reproduces
  // shifted): both figures are given, so the negative gain is not read as
  // the whole story.
  if (!R.causes.empty() && R.gain < 0.0 &&
      R.extended_error_holdout_trimmed < R.baseline_error_holdout_trimmed)
    v += "; trimmed of isolated spikes (the selection's figure) " +
         pct(R.baseline_error_holdout_trimmed) + " -> " + pct(R.extended_error_holdout_trimmed) +
         ": the rise is in a few samples";
  for (const Cause &c : R.causes)
    if (c.on_fit_records)
      v += "; " + c.cand.name + " judged on the fit records (" + pct(c.error_fit_before) + " -> " +
           pct(c.error_fit) + ", floor " + pct(R.floor.error_fit) +
           "): the held-out ones are at their noise floor and show none of it";
  if (!R.causes.empty() && !clipped.empty()) v += "; and " + clipped;
  if (!R.causes.empty() && !spiked.empty()) v += "; and " + spiked;
  if (!R.causes.empty() && R.residual_above_floor) {
    const double ratio = R.extended_error_holdout / std::max(R.floor.error_holdout, 1e-300);
    // A low-passed force (real-data preprocessing) has no white noise left:
    // then the floor says nothing and only the signature is reported.
    if (ratio < 1000.0) std::snprintf(g, sizeof g, "; the remaining residual is %.1fx the noise floor: ", ratio);
    else std::snprintf(g, sizeof g, "; remaining residual (no white noise in the force to set a floor, e.g. low-passed data): ");
    v += g + R.signature.text;
  }
  return v;
}

}  // namespace diag

std::vector<RecordFigures> record_figures(const ExtModel &m, const std::vector<Record> &fit,
                                          const std::vector<Record> &holdout,
                                          const MisfitOptions &opt) {
  std::vector<RecordFigures> out;
  ExtFitSpec none;
  none.free.clear();
  MisfitOptions all = opt;
  all.fit_from = 0.0;
  for (const std::vector<Record> *set : {&fit, &holdout})
    for (const Record &rec : *set) {
      RecordFigures f;
      f.file = rec.path;
      f.holdout = set == &holdout;
      f.error = extended_error(m, {rec}, f.holdout ? all : opt);
      Eigen::VectorXd F;
      predict_extended(m, rec, opt.sim, none, F, nullptr);
      double ss = 0.0, lo = INFINITY, hi = -INFINITY;
      for (size_t i = 0; i < rec.F.size(); ++i) {
        const double r = F[(Eigen::Index)i] - rec.F[i];
        ss += r * r;
        lo = std::min(lo, rec.F[i]);
        hi = std::max(hi, rec.F[i]);
      }
      f.nrmse = hi > lo ? std::sqrt(ss / (double)rec.F.size()) / (hi - lo) : INFINITY;
      out.push_back(f);
    }
  return out;
}

}  // namespace rtb
