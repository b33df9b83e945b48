// diagnose.cpp -- the diagnosis pipeline (see diagnose.h for the stages).
#include "diagnose/diagnose.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "diagnose/plausibility.h"
#include "identify/sts_init.h"
#include "model/parallel_for.h"

namespace rtb {

ResidualSignature residual_signature(const ExtModel &m, const std::vector<Record> &recs,
                                     const std::vector<RecordResiduals> &where,
                                     const MisfitOptions &opt);

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point a) {
  return std::chrono::duration<double>(Clock::now() - a).count();
}

std::vector<Record> concat(const std::vector<Record> &a, const std::vector<Record> &b) {
  std::vector<Record> all = a;
  all.insert(all.end(), b.begin(), b.end());
  return all;
}

// The model the next round starts from: its parameters, free set, causes and
// figures (trimmed held-out error for selection, misfit for the BIC).
struct Current {
  ExtModel model;
  ExtFitSpec spec;
  std::vector<Candidate> causes;
  double error_fit = 0, error_holdout = 0, error_holdout_trimmed = 0;
  double J_trim = 0;  // trimmed fit misfit
};

struct Context {
  const std::vector<Record> &fit, &holdout, all;
  const std::vector<Record> &sel;  // records of the selection figure
  MisfitOptions sel_opt;
  const DiagnoseOptions &opt;
  DataScales sc;
  std::vector<double> sigma;  // noise level per record of `all`
  double floor_sel = 0.0;     // the noise floor's eq. (27) error on `sel`
  bool clipped = false;       // stage 0 found a saturated force channel
};

Current make_current(const ExtModel &m, const ExtFitSpec &spec, const std::vector<Candidate> &causes,
                     const Context &cx) {
  Current c;
  c.model = m;
  c.spec = spec;
  c.causes = causes;
  c.error_fit = extended_error(m, cx.fit, cx.opt.misfit);
  extended_error(m, cx.fit, cx.opt.misfit, &c.J_trim, nullptr, cx.opt.trim);
  c.error_holdout = extended_error(m, cx.sel, cx.sel_opt);
  c.error_holdout_trimmed = extended_error(m, cx.sel, cx.sel_opt, nullptr, nullptr, cx.opt.trim);
  return c;
}

// Size of the effect (its first parameter, or the delay / offset) over its
// standard deviation: the Wald z. NaN when the fit has no finite standard
// deviation for it (a size at a clamp, a singular covariance).
double amplitude_z(const Candidate &c, const ExtFitResult &f) {
  std::string amp;
  if (!c.extra.empty()) amp = param_name(c.extra[0]);
  else if (c.delay) amp = "delay";
  else if (c.offset) amp = "offset";
  else return INFINITY;  // a switch (slack): judged by BIC and gain alone
  for (size_t i = 0; i < f.names.size(); ++i)
    if (f.names[i] == amp) {
      const double sd = f.stddev_valid ? f.stddev[(Eigen::Index)i] : NAN;
      if (!std::isfinite(sd)) return NAN;  // no Wald figure: see evaluate()
      return sd > 0.0 ? std::fabs(f.value[(Eigen::Index)i]) / sd : INFINITY;
    }
  return 0.0;
}


// Stage 4: joint fits of the best-screened candidates (in parallel).
void joint_fits(std::vector<CandidateOutcome> &out, const Current &cur, const Context &cx,
                int how_many, const std::string &imposed) {
  std::vector<size_t> order;
  for (size_t i = 0; i < out.size(); ++i)
    if (out[i].screen.z >= cx.opt.min_z) order.push_back(i);
  std::sort(order.begin(), order.end(),
            [&](size_t p, size_t q) { return out[p].screen.dJ > out[q].screen.dJ; });
  if ((int)order.size() > how_many) order.resize((size_t)how_many);
  // What-if: the imposed word is fitted whatever its screen says.
  for (size_t i = 0; i < out.size(); ++i)
    if (out[i].cand.name == imposed && std::find(order.begin(), order.end(), i) == order.end())
      order.push_back(i);
  parallel_for(order.size(), cx.opt.threads, [&](size_t k) {
    CandidateOutcome &co = out[order[k]];
    const auto t1 = Clock::now();
    std::vector<Candidate> with = cur.causes;
    with.push_back(co.cand);
    try {
      co.fit = fit_extended(cx.fit, co.screen.start, combined_spec(with, cx.sc), cx.opt.misfit);
      co.joint = std::isfinite(co.fit.J);
      if (!co.joint) co.why = "joint fit failed: non-finite misfit";
    } catch (const std::exception &e) {
      co.joint = false;
      co.why = std::string("joint fit failed: ") + e.what();
    }
    co.fit_seconds = since(t1);
  });
}

// Stage 5a: the criteria of one candidate against the current model.
void judge(CandidateOutcome &co, const Current &cur, const Context &cx, double min_gain) {
  const DiagnoseOptions &opt = cx.opt;
  if (!co.joint) {
    co.error_holdout = NAN;
    co.fit.error = NAN;
    if (co.why.empty())
      co.why = co.screen.z < opt.min_z ? "screened out: effect not significant"
                                        : "screened out: smaller misfit reduction than others";
    return;
  }
  const double k = (double)(co.cand.extra.size() + co.cand.delay + co.cand.offset +
                            (co.cand.extra.empty() && !co.cand.delay && !co.cand.offset));
  const double ms = (double)co.fit.samples;
  // On trimmed misfits, like the selection figure: isolated spikes (e.g. at
  // ideal input corners) must not decide in either direction.
  double Jc_trim = 0;
  extended_error(co.fit.model, cx.fit, opt.misfit, &Jc_trim, nullptr, opt.trim);
  co.dbic = ms * std::log(cur.J_trim / Jc_trim) - k * std::log(ms);
  co.error_holdout = extended_error(co.fit.model, cx.sel, cx.sel_opt);
  co.error_holdout_trimmed = extended_error(co.fit.model, cx.sel, cx.sel_opt, nullptr, nullptr, opt.trim);
  co.gain = 1.0 - co.error_holdout_trimmed / cur.error_holdout_trimmed;
  co.amplitude_z = amplitude_z(co.cand, co.fit);
  // At a clamp the Wald z does not exist; the likelihood ratio of the fit
  // against the current model (one added parameter) still measures it.
  if (std::isnan(co.amplitude_z))
    co.amplitude_z = std::sqrt(std::max(0.0, ms * std::log(cur.J_trim / Jc_trim)));
  // A Maxwell branch whose relaxation time is below the sample interval acts
  // as a linear dashpot c = k tau: the data cannot tell it from `viscous`.
  const bool unresolved_tau =
      co.cand.name == "maxwell" && co.fit.model.p.maxwell_tau < 2.0 * cx.sc.dt;
  // A size pinned at the edge of its admissible range (a dashpot level
  // asymmetry of 95%, a Mullins loss of 95%) is the fit compensating for
  // something else with the nearest freedom it has, not a measurement of it.
  const bool at_bound = (co.cand.name == "friction_asymmetry" &&
                         std::fabs(co.fit.model.p.fric_asym) >= 0.94) ||
                        (co.cand.name == "mullins" && co.fit.model.p.mullins >= 0.94);
  if (co.amplitude_z < opt.min_z) co.why = "effect not significant (z < min_z)";
  else if (at_bound) co.why = "size at the bound of its admissible range: a compensation, not a measurement";
  else if (unresolved_tau) co.why = "relaxation time below 2 sample intervals: a viscous dashpot";
  else if (co.dbic < opt.min_dbic) co.why = "fit gain explained by the extra parameters (delta BIC)";
  else if (!gain_suffices(co.gain, cur.error_holdout, co.error_holdout, cx.floor_sel, min_gain, opt))
    co.why = cx.holdout.empty() ? "fit gain below min_gain" : "held-out gain below min_gain";
  else {
    co.why = contradiction(co.cand, co.fit.model, cur.model, cx.all, cx.sigma, opt.misfit);
    // A saturated force channel hides the loops' extremes: a word fitted to
    // what is left is not a measurement (refgen clipping_s4: with 45% of the
    // fit samples held, a Maxwell branch and a clearance were fitted to the
    // partial loops). The candidate stays in the report, unnamed.
    if (co.why.empty() && cx.clipped)
      co.why = "not named: the force channel is clipped (stage 0), the loops are partial";
    co.eligible = co.why.empty();
  }
}

// Stages 3-5 at the current model: the outcomes of every remaining candidate.
std::vector<CandidateOutcome> one_round(const Current &cur, const Context &cx, int round,
                                        DiagnoseResult &R) {
  std::vector<Candidate> cands;
  std::vector<CandidateOutcome> excluded;
  const std::vector<std::string> &imposed = cx.opt.imposed;
  for (const Candidate &c : candidate_vocabulary()) {
    if (!cx.opt.only.empty() &&
        std::find(cx.opt.only.begin(), cx.opt.only.end(), c.name) == cx.opt.only.end())
      continue;
    // A what-if's first round is the diagnosis's (its basin check sets the
    // same baseline); later rounds look at the imposed word only.
    if (round > 0 && !imposed.empty() && c.name != imposed[(size_t)round]) continue;
    bool clash = false;
    for (const Candidate &k : cur.causes) clash = clash || candidates_conflict(c, k);
    if (clash) continue;
    const std::string why = excluded_by_data(c, cx.all);
    if (why.empty()) {
      cands.push_back(c);
      continue;
    }
    CandidateOutcome co;  // reported, never screened
    co.cand = c;
    co.round = round;
    co.why = why;
    co.screen.start = cur.model;
    excluded.push_back(co);
  }
  std::vector<CandidateOutcome> out(cands.size());
  const auto t_screen = Clock::now();
  const std::vector<CandidateScreen> screens =
      screen_candidates(cands, cur.model, cur.spec, cx.all, cx.opt.misfit, cx.sc, cx.opt.threads);
  for (size_t i = 0; i < cands.size(); ++i) {
    out[i].cand = cands[i];
    out[i].round = round;
    out[i].screen = screens[i];
  }
  R.seconds_screen += since(t_screen);
  const auto t_joint = Clock::now();
  joint_fits(out, cur, cx, round == 0 ? cx.opt.joint_fits : cx.opt.joint_fits_next,
             imposed.empty() ? std::string() : imposed[(size_t)round]);
  R.seconds_joint += since(t_joint);
  for (CandidateOutcome &co : out)
    judge(co, cur, cx, round == 0 ? cx.opt.min_gain : cx.opt.min_gain_next);
  for (CandidateOutcome &co : excluded) {
    judge(co, cur, cx, 0.0);
    out.push_back(co);
  }
  return out;
}

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

// What-if mode: the imposed word's joint fit with the lowest held-out error
// (of its variants), eligible or not; nullptr if no fit succeeded.
const CandidateOutcome *imposed_cause(const std::vector<CandidateOutcome> &round,
                                      const std::string &name) {
  const CandidateOutcome *pick = nullptr;
  for (const CandidateOutcome &co : round)
    if (co.cand.name == name && co.joint &&
        (!pick || co.error_holdout_trimmed < pick->error_holdout_trimmed))
      pick = &co;
  return pick;
}

// Basin check of the first round: a candidate whose own term is
// insignificant but whose fit is much better found a better RT minimum.
const CandidateOutcome *better_basin(const std::vector<CandidateOutcome> &out, double base_error,
                                     double min_z) {
  const CandidateOutcome *better = nullptr;
  for (const CandidateOutcome &co : out)
    if (co.joint && co.amplitude_z < min_z && co.fit.error < 0.9 * base_error &&
        (!better || co.fit.error < better->fit.error))
      better = &co;
  return better;
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

char pct_buf[64];
const char *pct(double e) {
  std::snprintf(pct_buf, sizeof pct_buf, "%.2f%%", 100.0 * e);
  return pct_buf;
}

std::string verdict_text(const DiagnoseResult &R, const DiagnoseOptions &opt) {
  std::string v = R.imposed ? "imposed causes (what-if, not selected): " : "cause: ";
  const std::string clipped = clipping_text(R.clipping, R.extended_records.size());
  if (R.causes.empty() && !clipped.empty()) {
    v += "unexplained (" + clipped + ")";
  } else if (R.causes.empty() && R.cause == "unexplained") {
    char b[200];
    std::snprintf(b, sizeof b, "unexplained (residual %.1fx the noise floor of %s; no candidate removes it): ",
                  R.baseline_error_holdout / std::max(R.floor.error_holdout, 1e-300),
                  pct(R.floor.error_holdout));
    v += b + R.signature.text;
  } else if (R.causes.empty()) {
    v += "none (the residual is at the noise floor of " + std::string(pct(R.floor.error_holdout)) + ")";
  } else {
    for (size_t i = 0; i < R.causes.size(); ++i) v += (i ? " + " : "") + R.causes[i].description;
  }
  v += std::string("; ") + (R.has_holdout ? "holdout" : "fit") + " error " +
       pct(R.baseline_error_holdout);
  v += std::string(" -> ") + pct(R.extended_error_holdout);
  char g[200];
  std::snprintf(g, sizeof g, " (gain %.0f%%)", 100.0 * R.gain);
  v += g;
  if (!R.causes.empty() && !clipped.empty()) v += "; and " + clipped;
  if (!R.causes.empty() && R.residual_above_floor) {
    const double ratio = R.extended_error_holdout / std::max(R.floor.error_holdout, 1e-300);
    // A low-passed force (real-data preprocessing) has no white noise left:
    // then the floor says nothing and only the signature is reported.
    if (ratio < 1000.0) std::snprintf(g, sizeof g, "; the remaining residual is %.1fx the noise floor: ", ratio);
    else std::snprintf(g, sizeof g, "; remaining residual (no white noise in the force to set a floor, e.g. low-passed data): ");
    v += g + R.signature.text;
  }
  (void)opt;
  return v;
}

}  // namespace

// Fitted parameters a candidate adds (its extension's, or the artefact's).
double excess_removed(double current, double candidate, double floor) {
  const double excess = current - floor;
  return excess > 0.0 ? (current - candidate) / excess : 0.0;
}

bool gain_suffices(double gain, double current, double candidate, double floor, double min_gain,
                   const DiagnoseOptions &opt) {
  return gain >= min_gain || (gain >= opt.min_gain_near_floor &&
                              excess_removed(current, candidate, floor) >= opt.min_excess_removed);
}

bool is_candidate_name(const std::string &name) {
  for (const Candidate &c : candidate_vocabulary())
    if (c.name == name) return true;
  return false;
}

static size_t parameter_count(const Candidate &c) {
  return c.extra.size() + (c.delay ? 1 : 0) + (c.offset ? 1 : 0);
}

// Stage 5's choice among the eligible: the lowest trimmed held-out error,
// or, within `parsimony` of it, the candidate with the fewest parameters
// (then the lower error). nullptr when none is eligible.
const CandidateOutcome *select_cause(const std::vector<CandidateOutcome> &round,
                                     double parsimony) {
  const CandidateOutcome *best = nullptr;
  for (const CandidateOutcome &co : round)
    if (co.eligible && (!best || co.error_holdout_trimmed < best->error_holdout_trimmed)) best = &co;
  if (!best) return nullptr;
  const double within = (1.0 + parsimony) * best->error_holdout_trimmed;
  const CandidateOutcome *pick = best;
  for (const CandidateOutcome &co : round) {
    if (!co.eligible || co.error_holdout_trimmed > within) continue;
    const size_t n = parameter_count(co.cand), m = parameter_count(pick->cand);
    if (n < m || (n == m && co.error_holdout_trimmed < pick->error_holdout_trimmed)) pick = &co;
  }
  return pick;
}

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

// Stage 1: plain RT from the STS start (section 5.4). A device that slides
// can send that fit to a viscous basin (the friction damper's dataset-3 sines:
// 48% with alpha 0.61). When that fit leaves more than friction_start_above
// of the force unexplained and the friction start (sts_init.h) fits better
// before any iteration, it is identified too, and its end kept when it fits
// clearly better (friction_start_margin). On refgen's 92 cases the STS end
// is at most 17.9% (asymmetry_s2); the friction start is tried on the two
// above 15% and its end, 0.1-0.4% higher, not kept.
IdentifyResult baseline_fit(const std::vector<Record> &fit, const DiagnoseOptions &opt,
                            const IdentifyOptions &io) {
  const rtb_params sts = sts_initial_guess(fit, opt.cells, opt.alpha0, opt.misfit.fit_from);
  IdentifyResult best = identify(fit, sts, io);
  if (!(best.error > opt.friction_start_above)) return best;
  rtb_params friction;
  try {
    friction = friction_initial_guess(fit, opt.cells, opt.misfit.fit_from);
  } catch (const std::exception &) {
    return best;
  }
  ExtModel at;
  at.p = friction;
  if (!(extended_error(at, fit, opt.misfit) < best.error_start)) return best;
  IdentifyResult alt = identify(fit, friction, io);
  if (!opt.quiet)
    std::fprintf(stderr, "diagnose: the friction start fits better (%.3f%% < %.3f%% at the start): "
                 "baseline %.3f%% from it, %.3f%% from the STS start\n",
                 100 * alt.error_start, 100 * best.error_start, 100 * alt.error, 100 * best.error);
  // Only a gross difference switches the basin: on a sliding device the
  // two ends differ by 2x (21.5% / 48%), while on rubber-like data the
  // friction end can be a few percent lower in a basin that has absorbed
  // another effect (refgen delay_s3: 2.53% against 2.66%, and the delay's
  // cross-correlation check then contradicted the right word).
  return alt.error < opt.friction_start_margin * best.error ? alt : best;
}

DiagnoseResult diagnose(const std::vector<Record> &fit_in, const std::vector<Record> &holdout_in,
                        const DiagnoseOptions &opt) {
  const auto t0 = Clock::now();
  DiagnoseResult R;
  // 0. The model input: one decision for all records.
  std::vector<Record> both = concat(fit_in, holdout_in);
  R.denoise = denoise_displacement(both);
  R.clipping = mask_force_clipping(both);
  const std::vector<Record> fit(both.begin(), both.begin() + (long)fit_in.size());
  const std::vector<Record> holdout(both.begin() + (long)fit_in.size(), both.end());
  R.has_holdout = !holdout.empty();
  MisfitOptions hold_opt = opt.misfit;
  hold_opt.fit_from = 0.0;
  Context cx{fit, holdout, concat(fit, holdout), R.has_holdout ? holdout : fit,
             R.has_holdout ? hold_opt : opt.misfit, opt, data_scales(fit), {}};
  cx.clipped = !R.clipping.empty();

  // 1. Baseline: plain RT from the STS start, or from the friction start
  // when that one fits better.
  IdentifyOptions io;
  io.misfit = opt.misfit;
  io.quiet = opt.quiet;
  io.max_iter = opt.baseline_max_iter;
  R.baseline_fit = baseline_fit(fit, opt, io);
  R.seconds_baseline = since(t0);
  const ExtFitSpec core;  // free = the five RT parameters
  Current cur;
  std::vector<CandidateOutcome> first;
  for (int attempt = 0;; ++attempt) {
    R.baseline = ExtModel();
    R.baseline.p = R.baseline_fit.params;
    cur = make_current(R.baseline, core, {}, cx);
    // 2. Noise floor of the baseline residual.
    R.floor = estimate_noise_floor(R.baseline, fit, holdout, opt.misfit);
    cx.sigma = R.floor.sigma_fit;
    cx.sigma.insert(cx.sigma.end(), R.floor.sigma_holdout.begin(), R.floor.sigma_holdout.end());
    cx.floor_sel = R.has_holdout ? R.floor.error_holdout : R.floor.error_fit;
    // 3-5. First round.
    first = one_round(cur, cx, 0, R);
    const CandidateOutcome *better = better_basin(first, cur.error_fit, opt.min_z);
    if (attempt > 0 || !better) break;
    rtb_params restart = R.baseline_fit.params;
    for (ParamId id : core_params()) param_ref(restart, id) = param_get(better->fit.model.p, id);
    if (!opt.quiet)
      std::fprintf(stderr, "diagnose: the %s fit found a better RT basin (%.3f%% < %.3f%%): refitting "
                   "the baseline from it\n", better->cand.name.c_str(), 100 * better->fit.error,
                   100 * cur.error_fit);
    const auto t_again = Clock::now();
    IdentifyResult again = identify(fit, restart, io);
    R.seconds_baseline += since(t_again);
    if (!(again.J < R.baseline_fit.J)) break;
    R.baseline_fit = again;
  }
  R.baseline_error_fit = cur.error_fit;
  R.baseline_error_holdout = cur.error_holdout;
  R.baseline_error_holdout_trimmed = cur.error_holdout_trimmed;
  R.residuals = analyze_residuals(R.baseline, fit, holdout, opt.misfit);
  if (!opt.quiet)
    std::fprintf(stderr, "diagnose: baseline RT error fit %.3f%%, holdout %.3f%%, noise floor %.3f%%\n",
                 100 * R.baseline_error_fit, 100 * R.baseline_error_holdout,
                 100 * R.floor.error_holdout);

  // 5b-6. Accept the best eligible candidate, then look for the next cause at
  // the extended model while the residual is above the floor.
  R.extended_spec = core;
  std::vector<CandidateOutcome> round_out = first;
  const auto above_floor = [&](const Current &c) {
    return c.error_holdout > opt.floor_ratio * R.floor.error_holdout ||
           c.error_fit > opt.floor_ratio * R.floor.error_fit;
  };
  const size_t n_imposed = opt.imposed.size();
  R.imposed = n_imposed > 0;
  for (int round = 0;; ++round) {
    const CandidateOutcome *best =
        R.imposed ? imposed_cause(round_out, opt.imposed[(size_t)round])
                  : select_cause(round_out, opt.parsimony);
    R.candidates.insert(R.candidates.end(), round_out.begin(), round_out.end());
    if (!best) break;
    std::vector<Candidate> causes = cur.causes;
    causes.push_back(best->cand);
    const Current before = cur;
    CandidateOutcome accepted = *best;
    cur = make_current(best->fit.model, combined_spec(causes, cx.sc), causes, cx);
    if (refit_from_sts(cur, cx, accepted.fit)) {
      cur = make_current(accepted.fit.model, cur.spec, causes, cx);
      accepted.error_holdout = cur.error_holdout;
    }
    R.causes.push_back(make_cause(accepted, before));
    R.extended_fit = accepted.fit;
    if (!R.imposed) {
      const int gone = drop_redundant(cur, cx, R);
      if (gone >= 0) R.causes.erase(R.causes.begin() + gone);
    }
    if (R.imposed ? (size_t)round + 1 >= n_imposed
                  : (round + 1 >= opt.max_causes || !above_floor(cur)))
      break;
    round_out = one_round(cur, cx, round + 1, R);
  }
  R.extended = cur.model;
  R.extended_spec = cur.spec;
  R.extended_error_fit = cur.error_fit;
  R.extended_error_holdout = cur.error_holdout;
  R.extended_records = record_figures(R.extended, fit, holdout, opt.misfit);
  R.residual_above_floor = above_floor(cur);
  if (R.residual_above_floor)
    R.signature = residual_signature(R.extended, cx.all, R.residuals, opt.misfit);
  // Clipped records: what the model misses there is the rig, not a word.
  R.cause = !R.causes.empty() ? R.causes.front().cand.name
                              : (R.residual_above_floor || !R.clipping.empty() ? "unexplained" : "none");
  R.gain = 1.0 - R.extended_error_holdout / R.baseline_error_holdout;
  R.verdict = verdict_text(R, opt);
  R.wall_seconds = since(t0);
  return R;
}

}  // namespace rtb
