// diagnose.cpp -- see diagnose.h.
#include "diagnose/diagnose.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <thread>

#include "identify/sts_init.h"
#include "model/parallel_for.h"

namespace rtb {

namespace {

// Index of the parameter that measures the size of the effect.
double amplitude_z(const Candidate &c, const ExtFitResult &f) {
  std::string amp;
  if (!c.extra.empty()) amp = param_name(c.extra[0]);
  else if (c.delay) amp = "delay";
  else if (c.offset) amp = "offset";
  for (size_t i = 0; i < f.names.size(); ++i)
    if (f.names[i] == amp) {
      if (!f.stddev_valid) return 0.0;
      const double sd = f.stddev[(Eigen::Index)i];
      return sd > 0.0 ? std::fabs(f.value[(Eigen::Index)i]) / sd : INFINITY;
    }
  return 0.0;
}

// Weighted baseline residuals and the weighted sensitivity columns of the
// candidate's first (amplitude) parameter, stacked over the fit records.
struct Columns {
  Eigen::VectorXd r;
  Eigen::MatrixXd g;
};
Columns screen_columns(const ExtModel &m, const std::vector<Record> &recs, const MisfitOptions &opt,
                       const ExtFitSpec &spec) {
  std::vector<double> rv;
  std::vector<Eigen::RowVectorXd> rows;
  for (const Record &rec : recs) {
    Eigen::VectorXd F;
    Eigen::MatrixXd J;
    predict_extended(m, rec, opt.sim, spec, F, &J);
    const std::vector<double> w = quadrature_weights(rec, opt.fit_from);
    for (size_t j = 0; j < rec.F.size(); ++j) {
      if (!(w[j] > 0.0)) continue;
      const double q = std::sqrt(w[j]);
      rv.push_back(q * (F[(Eigen::Index)j] - rec.F[j]));
      rows.push_back(q * J.row((Eigen::Index)j));
    }
  }
  Columns c;
  c.r = Eigen::Map<Eigen::VectorXd>(rv.data(), (Eigen::Index)rv.size());
  c.g.resize(c.r.size(), rows.empty() ? 0 : rows[0].size());
  for (size_t k = 0; k < rows.size(); ++k) c.g.row((Eigen::Index)k) = rows[k];
  return c;
}

// Score test at the baseline: the linearized least squares with the RT
// sensitivities and the candidate's columns together, so that the part of
// the effect the baseline fit has already absorbed (e.g. relaxation taken by
// the RT cells) is re-optimized rather than counted against the candidate.
// The candidate's amplitude is the last unknown.
void joint_linear(const Columns &rt, const Eigen::MatrixXd &g, CandidateScreen &s,
                  Eigen::VectorXd *rt_step = nullptr) {
  const Eigen::Index m = rt.r.size(), P = rt.g.cols(), q = g.cols();
  Eigen::MatrixXd A(m, P + q);
  A << rt.g, g;
  const Eigen::VectorXd cs = A.colwise().norm().transpose().cwiseMax(1e-300);
  const Eigen::MatrixXd As = A * cs.cwiseInverse().asDiagonal();
  const Eigen::MatrixXd N = As.transpose() * As;
  const Eigen::LDLT<Eigen::MatrixXd> ldlt(N);
  const Eigen::VectorXd th = -ldlt.solve(As.transpose() * rt.r);
  const Eigen::VectorXd res = rt.r + As * th;
  const double r2 = rt.r.squaredNorm();
  s.dJ = r2 > 0 ? 1.0 - res.squaredNorm() / r2 : 0.0;
  s.value = th[P] / cs[P];
  const double s2 = res.squaredNorm() / std::max(1.0, double(m - P - q));
  const Eigen::VectorXd e = Eigen::VectorXd::Unit(P + q, P);
  const double var = s2 * e.dot(ldlt.solve(e)) / (cs[P] * cs[P]);
  s.z = var > 0 ? std::fabs(s.value) / std::sqrt(var) : 0.0;
  if (rt_step) *rt_step = th.head(P).cwiseQuotient(cs.head(P));
}

// Move the RT parameters by the linearized step that accompanies the
// candidate's term (the baseline had bent them to absorb the effect), in
// log coordinates and by at most +-50%.
void apply_rt_step(const Eigen::VectorXd &d, rtb_params &p) {
  const std::vector<ParamId> ids = core_params();
  for (size_t i = 0; i < ids.size() && (Eigen::Index)i < d.size(); ++i) {
    double &v = param_ref(p, ids[i]);
    if (v <= 0.0) continue;
    const double rel = std::max(-0.5, std::min(0.5, d[(Eigen::Index)i] / v));
    v *= std::exp(rel);
  }
  // alpha stays inside the admissible range (a baseline at the floor
  // RTB_ALPHA_MIN, friction-like, must not be stepped below it).
  p.alpha = std::max(std::min(p.alpha, 0.95), 1.01 * RTB_ALPHA_MIN);
}

// Starting gaps of the backlash screen, as fractions of the stroke: a
// clearance much wider than the first is a different basin (a friction
// device with a 10%-of-stroke play, e.g.). Each start is its own screening
// job, so the two short fits run in parallel.
constexpr double kBacklashStarts[] = {0.02, 0.1};

CandidateScreen screen_candidate(const Candidate &c, const ExtModel &base,
                                 const std::vector<Record> &fit, const MisfitOptions &opt,
                                 const DataScales &sc, const Columns &rt, int variant) {
  CandidateScreen s;
  s.start = base;
  ExtFitSpec spec;
  spec.free = c.extra;
  spec.fit_delay = c.delay;
  spec.fit_offset = c.offset;
  if (c.name == "maxwell") {
    // Linear in the branch stiffness at fixed tau: scan tau over the records'
    // time scales, keep the best.
    spec.free = {P_maxwell_k};
    for (double tau : {0.003, 0.01, 0.03, 0.1, 0.3, 1.0}) {
      ExtModel m = base;
      m.p.maxwell_tau = std::max(tau * sc.duration, 5.0 * sc.dt);
      CandidateScreen t;
      joint_linear(rt, screen_columns(m, fit, opt, spec).g, t);
      if (t.value > 0.0 && t.dJ > s.dJ) {
        s = t;
        s.start = m;
      }
    }
    if (s.dJ == 0.0) {  // no positive stiffness helps at any tau: report the best anyway
      ExtModel m = base;
      m.p.maxwell_tau = extra_start_value(P_maxwell_tau, sc);
      joint_linear(rt, screen_columns(m, fit, opt, spec).g, s);
      s.start = m;
    }
    s.plausible = s.value > 0.0;
    s.start.p.maxwell_k = s.plausible ? s.value : extra_start_value(P_maxwell_k, sc);
    return s;
  }
  if (c.name == "softening") {
    // Linear in the saturation force at fixed width: scan the width over
    // the stroke, keep the best positive force.
    spec.free = {P_sat_force};
    for (double xs : {0.03, 0.1, 0.3, 1.0}) {
      ExtModel m = base;
      m.p.sat_disp = xs * sc.Xmax;
      CandidateScreen t;
      Eigen::VectorXd step;
      joint_linear(rt, screen_columns(m, fit, opt, spec).g, t, &step);
      if (t.value > 0.0 && t.dJ > s.dJ) {
        s = t;
        s.start = m;
        apply_rt_step(step, s.start.p);
      }
    }
    s.plausible = s.value > 0.0;
    if (s.start.p.sat_disp == 0.0) s.start.p.sat_disp = extra_start_value(P_sat_disp, sc);
    s.start.p.sat_force = s.plausible ? s.value : extra_start_value(P_sat_force, sc);
    return s;
  }
  if (c.name == "backlash") {
    // Not differentiable at g = 0: a short joint fit (RT + g) from a gap;
    // with RT held the baseline's compensation would hide the gap.
    ExtFitSpec one = candidate_spec(c, sc);
    one.max_iter = 6;
    ExtModel m = base;
    m.p.backlash = kBacklashStarts[variant] * sc.Xmax;
    const ExtFitResult f = fit_extended(fit, m, one, opt);
    const double r2 = rt.r.squaredNorm();
    s.value = f.model.p.backlash;
    s.dJ = r2 > 0 ? std::max(0.0, 1.0 - f.J / (0.5 * r2)) : 0.0;
    const Eigen::Index gi = (Eigen::Index)one.free.size() - 1;
    s.z = f.stddev_valid && f.stddev[gi] > 0 ? s.value / f.stddev[gi] : 0.0;
    s.start = f.model;
    return s;
  }
  Eigen::VectorXd rt_step;
  joint_linear(rt, screen_columns(base, fit, opt, spec).g, s, &rt_step);
  apply_rt_step(rt_step, s.start.p);
  if (!c.extra.empty()) {
    const ParamId id = c.extra[0];
    const bool positive = id == P_viscous_c || id == P_mass || id == P_mullins;
    s.plausible = !positive || s.value > 0.0;
    double v = s.value;
    // A wrong-signed screen (the baseline absorbed part of the effect) still
    // gets a joint fit if it ranks high, from a default positive size.
    if (id == P_mullins && v > 0.0) v = std::min(v, 0.9);
    if (id == P_k_asym) v = std::max(-0.9 * s.start.p.K0, std::min(0.9 * s.start.p.K0, v));
    if (positive && !(v > 0.0)) v = extra_start_value(id, sc);
    param_ref(s.start.p, id) = v;
  }
  if (c.delay) {
    s.plausible = s.value > 0.0;  // the force channel lags, by definition
    s.start.delay = s.value > 0.0 ? s.value : 2.0 * sc.dt;
  }
  if (c.offset) s.start.offset = s.value;
  return s;
}

char pct_buf[64];
const char *pct(double e) {
  std::snprintf(pct_buf, sizeof pct_buf, "%.2f%%", 100.0 * e);
  return pct_buf;
}

}  // namespace

DiagnoseResult diagnose(const std::vector<Record> &fit, const std::vector<Record> &holdout,
                        const DiagnoseOptions &opt) {
  const auto t0 = std::chrono::steady_clock::now();
  DiagnoseResult R;
  R.has_holdout = !holdout.empty();
  MisfitOptions hold_opt = opt.misfit;
  hold_opt.fit_from = 0.0;

  // 1. Baseline: plain RT from the STS start.
  const rtb_params start = sts_initial_guess(fit, opt.cells, opt.alpha0, opt.misfit.fit_from);
  IdentifyOptions io;
  io.misfit = opt.misfit;
  io.quiet = opt.quiet;
  io.max_iter = opt.baseline_max_iter;
  auto since = [](std::chrono::steady_clock::time_point a) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count();
  };
  R.baseline_fit = identify(fit, start, io);
  R.seconds_baseline = since(t0);
  // A second round starts here when a candidate's joint fit shows that the
  // baseline sat in a poor basin (see the end of step 4).
  for (int round = 0;; ++round) {
    R.candidates.clear();
    R.chosen = -1;
    R.baseline.p = R.baseline_fit.params;
    double Jb = 0, J0b = 0, Jb_trim = 0;
    R.baseline_error_fit = extended_error(R.baseline, fit, opt.misfit, &Jb, &J0b);
    extended_error(R.baseline, fit, opt.misfit, &Jb_trim, nullptr, opt.trim);
    const std::vector<Record> &sel = R.has_holdout ? holdout : fit;
    const MisfitOptions &sel_opt = R.has_holdout ? hold_opt : opt.misfit;
    R.baseline_error_holdout = extended_error(R.baseline, sel, sel_opt);
    R.baseline_error_holdout_trimmed = extended_error(R.baseline, sel, sel_opt, nullptr, nullptr, opt.trim);
    if (!opt.quiet)
      std::fprintf(stderr, "diagnose: baseline RT error fit %.3f%%, holdout %.3f%%\n",
                   100 * R.baseline_error_fit, 100 * R.baseline_error_holdout);

    // 2. Residuals of the baseline.
    R.residuals = analyze_residuals(R.baseline, fit, holdout, opt.misfit);

    // 3a. Screening at the baseline.
    const DataScales sc = data_scales(fit);
    std::vector<Candidate> cands;
    for (const Candidate &c : candidate_vocabulary())
      if (opt.only.empty() || std::find(opt.only.begin(), opt.only.end(), c.name) != opt.only.end())
        cands.push_back(c);
    std::vector<CandidateOutcome> out(cands.size());
    // Screening jobs (candidate, variant), the long backlash fits first.
    std::vector<std::pair<size_t, int>> jobs;
    for (size_t i = 0; i < cands.size(); ++i) {
      out[i].cand = cands[i];
      if (cands[i].name == "backlash")
        for (int v = 0; v < (int)std::size(kBacklashStarts); ++v) jobs.insert(jobs.begin(), {i, v});
      else
        jobs.push_back({i, 0});
    }
    const auto t_screen = std::chrono::steady_clock::now();
    ExtFitSpec core;
    const Columns rt = screen_columns(R.baseline, fit, opt.misfit, core);
    std::vector<CandidateScreen> screens(jobs.size());
    parallel_for(jobs.size(), opt.threads, [&](size_t k) {
      const auto t1 = std::chrono::steady_clock::now();
      screens[k] = screen_candidate(cands[jobs[k].first], R.baseline, fit, opt.misfit, sc, rt,
                                    jobs[k].second);
      screens[k].seconds = since(t1);
    });
    // A candidate's screen is its best variant (largest misfit reduction).
    std::vector<bool> have(cands.size(), false);
    for (size_t k = 0; k < jobs.size(); ++k) {
      CandidateScreen &s = out[jobs[k].first].screen;
      const double spent = s.seconds + screens[k].seconds;
      if (!have[jobs[k].first] || screens[k].dJ > s.dJ) s = screens[k];
      s.seconds = spent;
      have[jobs[k].first] = true;
    }
    R.seconds_screen += since(t_screen);
    // 3b. Joint fits of the most promising candidates.
    std::vector<size_t> order;
    for (size_t i = 0; i < out.size(); ++i)
      if (out[i].screen.z >= opt.min_z) order.push_back(i);
    std::sort(order.begin(), order.end(),
              [&](size_t p, size_t q) { return out[p].screen.dJ > out[q].screen.dJ; });
    if ((int)order.size() > opt.joint_fits) order.resize((size_t)opt.joint_fits);
    const auto t_joint = std::chrono::steady_clock::now();
    parallel_for(order.size(), opt.threads, [&](size_t k) {
      CandidateOutcome &co = out[order[k]];
      const auto t1 = std::chrono::steady_clock::now();
      try {
        co.fit = fit_extended(fit, co.screen.start, candidate_spec(co.cand, sc), opt.misfit);
        co.joint = std::isfinite(co.fit.J);
        if (!co.joint) co.why = "joint fit failed: non-finite misfit";
      } catch (const std::exception &e) {
        co.joint = false;
        co.why = std::string("joint fit failed: ") + e.what();
      }
      co.fit_seconds = since(t1);
    });
    R.seconds_joint += since(t_joint);

    // 4. Criteria and choice.
    for (CandidateOutcome &co : out) {
      if (!co.joint) {
        co.error_holdout = NAN;
        co.fit.error = NAN;
        if (co.why.empty())
          co.why = co.screen.z < opt.min_z ? "screened out: effect not significant"
                                            : "screened out: smaller misfit reduction than others";
        R.candidates.push_back(co);
        continue;
      }
      const double k = (double)(co.cand.extra.size() + co.cand.delay + co.cand.offset);
      const double ms = (double)co.fit.samples;
      // On trimmed misfits, like the selection figure: isolated spikes (e.g. at
      // ideal input corners) must not decide in either direction.
      double Jc_trim = 0;
      extended_error(co.fit.model, fit, opt.misfit, &Jc_trim, nullptr, opt.trim);
      co.dbic = ms * std::log(Jb_trim / Jc_trim) - k * std::log(ms);
      co.error_holdout = extended_error(co.fit.model, sel, sel_opt);
      co.error_holdout_trimmed = extended_error(co.fit.model, sel, sel_opt, nullptr, nullptr, opt.trim);
      co.gain = 1.0 - co.error_holdout_trimmed / R.baseline_error_holdout_trimmed;
      co.amplitude_z = amplitude_z(co.cand, co.fit);
      // A Maxwell branch whose relaxation time is below the sample interval
    // acts as a linear dashpot c = k tau: the data cannot tell it from
    // `viscous`, so it may not claim a relaxation time.
    const bool unresolved_tau = co.cand.name == "maxwell" && co.fit.model.p.maxwell_tau < 2.0 * sc.dt;
    if (co.amplitude_z < opt.min_z) co.why = "effect not significant (z < min_z)";
    else if (unresolved_tau) co.why = "relaxation time below 2 sample intervals: a viscous dashpot";
      else if (co.dbic < opt.min_dbic) co.why = "fit gain explained by the extra parameters (delta BIC)";
      else if (co.gain < opt.min_gain) co.why = R.has_holdout ? "held-out gain below min_gain" : "fit gain below min_gain";
      else co.eligible = true;
      R.candidates.push_back(co);
    }

    // Basin check: the plain RT model is nested in every candidate. If a
    // candidate fits much better while its own term is insignificant, its RT
    // part found a better minimum than the baseline (seen on friction-damper
    // data): refit the baseline from there and screen again, once.
    const CandidateOutcome *better = nullptr;
    for (const CandidateOutcome &co : R.candidates)
      if (co.joint && co.amplitude_z < opt.min_z && co.fit.error < 0.9 * R.baseline_error_fit &&
          (!better || co.fit.error < better->fit.error))
        better = &co;
    if (round > 0 || !better) break;
    rtb_params restart = R.baseline_fit.params;
    for (ParamId id : core_params()) param_ref(restart, id) = param_get(better->fit.model.p, id);
    if (!opt.quiet)
      std::fprintf(stderr, "diagnose: the %s fit found a better RT basin (%.3f%% < %.3f%%): refitting "
                   "the baseline from it\n", better->cand.name.c_str(), 100 * better->fit.error,
                   100 * R.baseline_error_fit);
    const auto t_again = std::chrono::steady_clock::now();
    IdentifyResult again = identify(fit, restart, io);
    R.seconds_baseline += since(t_again);
    if (!(again.J < R.baseline_fit.J)) break;
    R.baseline_fit = again;
  }  // rounds
  for (size_t i = 0; i < R.candidates.size(); ++i)
    if (R.candidates[i].eligible &&
        (R.chosen < 0 || R.candidates[i].error_holdout_trimmed <
                             R.candidates[(size_t)R.chosen].error_holdout_trimmed))
      R.chosen = (int)i;

  // 5. Extended model and gain.
  if (R.chosen >= 0) {
    const CandidateOutcome &c = R.candidates[(size_t)R.chosen];
    R.cause = c.cand.name;
    R.extended = c.fit.model;
    R.extended_error_fit = c.fit.error;
    R.extended_error_holdout = c.error_holdout;
  } else {
    R.extended = R.baseline;
    R.extended_error_fit = R.baseline_error_fit;
    R.extended_error_holdout = R.baseline_error_holdout;
  }
  R.gain = 1.0 - R.extended_error_holdout / R.baseline_error_holdout;
  std::string v = "cause: ";
  v += R.chosen >= 0 ? describe_effect(R.candidates[(size_t)R.chosen].cand, R.extended)
                     : std::string("none (no candidate explains the residual significantly)");
  v += std::string("; ") + (R.has_holdout ? "holdout" : "fit") + " error " +
       pct(R.baseline_error_holdout);
  v += std::string(" -> ") + pct(R.extended_error_holdout);
  char g[160];
  std::snprintf(g, sizeof g, " (gain %.0f%%)", 100.0 * R.gain);
  v += g;
  if (R.chosen >= 0) {
    // The selection figure: with isolated spikes trimmed it can differ a lot
    // (e.g. an inertia term at ideal input corners); say so.
    const CandidateOutcome &c = R.candidates[(size_t)R.chosen];
    if (std::fabs(c.gain - R.gain) > 0.05) {
      std::snprintf(g, sizeof g, "; with the largest %.1f%% of residuals trimmed %s -> ",
                    100.0 * opt.trim, pct(R.baseline_error_holdout_trimmed));
      v += g;
      v += pct(c.error_holdout_trimmed);
      std::snprintf(g, sizeof g, " (gain %.0f%%)", 100.0 * c.gain);
      v += g;
    }
  }
  R.verdict = v;
  R.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return R;
}

}  // namespace rtb
