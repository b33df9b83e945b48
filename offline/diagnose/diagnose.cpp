// diagnose.cpp -- see diagnose.h.
#include "diagnose/diagnose.h"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <thread>

#include "identify/sts_init.h"

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
  R.baseline_fit = identify(fit, start, io);
  R.baseline.p = R.baseline_fit.params;
  double Jb = 0, J0b = 0;
  R.baseline_error_fit = extended_error(R.baseline, fit, opt.misfit, &Jb, &J0b);
  R.baseline_error_holdout =
      R.has_holdout ? extended_error(R.baseline, holdout, hold_opt) : R.baseline_error_fit;
  if (!opt.quiet)
    std::fprintf(stderr, "diagnose: baseline RT error fit %.3f%%, holdout %.3f%%\n",
                 100 * R.baseline_error_fit, 100 * R.baseline_error_holdout);

  // 2. Residuals of the baseline.
  R.residuals = analyze_residuals(R.baseline, fit, holdout, opt.misfit);

  // 3. Candidates, every start point a task, run on opt.threads threads.
  const DataScales sc = data_scales(fit);
  struct Task {
    size_t cand;
    ExtModel start;
    ExtFitResult out;
    bool ok = false;
  };
  std::vector<Candidate> cands;
  for (const Candidate &c : candidate_vocabulary())
    if (opt.only.empty() || std::find(opt.only.begin(), opt.only.end(), c.name) != opt.only.end())
      cands.push_back(c);
  std::vector<Task> tasks;
  for (size_t i = 0; i < cands.size(); ++i)
    for (const ExtModel &s : candidate_starts(cands[i], R.baseline, sc)) tasks.push_back({i, s, {}});
  std::atomic<size_t> next{0};
  auto worker = [&]() {
    for (size_t k; (k = next.fetch_add(1)) < tasks.size();) {
      Task &t = tasks[k];
      try {
        t.out = fit_extended(fit, t.start, candidate_spec(cands[t.cand], sc), opt.misfit);
        t.ok = std::isfinite(t.out.J);
      } catch (const std::exception &) {
        t.ok = false;
      }
    }
  };
  std::vector<std::thread> pool;
  for (int i = 1; i < std::max(1, opt.threads); ++i) pool.emplace_back(worker);
  worker();
  for (std::thread &th : pool) th.join();

  // 4. Best start of each candidate, criteria, choice.
  for (size_t i = 0; i < cands.size(); ++i) {
    CandidateOutcome co;
    co.cand = cands[i];
    bool have = false;
    for (const Task &t : tasks)
      if (t.cand == i && t.ok && (!have || t.out.J < co.fit.J)) {
        co.fit = t.out;
        have = true;
      }
    if (!have) {
      co.why = "fit failed";
      co.error_holdout = INFINITY;
      R.candidates.push_back(co);
      continue;
    }
    const double k = (double)(cands[i].extra.size() + cands[i].delay + cands[i].offset);
    const double ms = (double)co.fit.samples;
    co.dbic = ms * std::log(Jb / co.fit.J) - k * std::log(ms);
    co.error_holdout = R.has_holdout ? extended_error(co.fit.model, holdout, hold_opt) : co.fit.error;
    co.gain = 1.0 - co.error_holdout / R.baseline_error_holdout;
    co.amplitude_z = amplitude_z(cands[i], co.fit);
    if (co.amplitude_z < opt.min_z) co.why = "effect not significant (z < min_z)";
    else if (co.dbic < opt.min_dbic) co.why = "fit gain explained by the extra parameters (delta BIC)";
    else if (co.gain < opt.min_gain) co.why = R.has_holdout ? "held-out gain below min_gain" : "fit gain below min_gain";
    else co.eligible = true;
    R.candidates.push_back(co);
  }
  for (size_t i = 0; i < R.candidates.size(); ++i)
    if (R.candidates[i].eligible &&
        (R.chosen < 0 || R.candidates[i].error_holdout < R.candidates[(size_t)R.chosen].error_holdout))
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
  char g[64];
  std::snprintf(g, sizeof g, " (gain %.0f%%)", 100.0 * R.gain);
  v += g;
  R.verdict = v;
  R.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return R;
}

}  // namespace rtb
