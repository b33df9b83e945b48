// dominated_fits.cpp -- stage 4's brief fits (diagnose_stages.h): a word
// whose screen one word of the round dominates is fitted with a short
// budget, and in full only when the judged round leaves it in the running.
//
// Why: a round fits its five best-screened words jointly, each to 60
// iterations with its restarts, whatever the leader does. Beside a dominant
// effect those fits cannot win and cost most of the diagnosis. Blindgen
// inertia_s59 (five 10 s records decimated to 1 kHz, two threads): the
// mass's screen took 0.884 of the misfit beyond the core's own step, the
// next word (a force lead) 0.091, a cubic spring 0.045; the cubic went to
// its 60-iteration cap (30 s), the spectrum through four restarts (32 s),
// for held-out errors of 62-81% against the mass's 8.5%: 86 s of the
// diagnosis's 155 s were such fits.
//
// Safe by construction where it matters: a brief fit is judged like any
// other, and when no fully fitted word is eligible (the pair stage, the
// words past the cut and the basin repairs then need real fits), or when a
// brief word is within dominated_reach of the best eligible word's held-out
// error, it gets its whole fit, as it had before, and is judged anew. A
// brief word beyond that reach is out of the running even when it is
// eligible: the round selects the best word, and the next round screens
// every word again (inertia_s59's force lead, eligible at 62% held out
// beside the mass's 8.5%, took 10 s of the round's 22 s to its 60-iteration
// cap and was then demoted as the mass's twin). A word screened by a short
// fit (clearance, slack, Mullins) is never brief: its 6-iteration screen can
// underrate it (blindgen mullins_s56: z = 190 with its reduction clamped at
// 0; fitted, 10.4% -> 2.5% held out).
#include <algorithm>
#include <cstdio>

#include "diagnose/diagnose_stages.h"
#include "model/parallel_for.h"

namespace rtb {
namespace diag {

// What the word adds beyond the model's own step (screen.h).
static double added_by(const CandidateOutcome &co) { return co.screen.dJ - co.screen.dJ_model; }

void mark_dominated(std::vector<CandidateOutcome> &out, const std::vector<size_t> &fitted,
                    double dominance, int max_iter) {
  if (!(dominance > 0.0)) return;
  double lead = 0.0;
  for (size_t i : fitted) lead = std::max(lead, added_by(out[i]));
  if (!(lead > 0.0)) return;
  char origin[96];
  std::snprintf(origin, sizeof origin, "a brief fit (%d iterations): its screen under 1/%g of the leader's",
                max_iter, dominance);
  for (size_t i : fitted) {
    CandidateOutcome &co = out[i];
    co.brief = co.cand.screen != ScreenMethod::short_fit && dominance * added_by(co) < lead;
    if (co.brief) co.origin = origin;
  }
}

// The best eligible word fitted in full; nullptr if none.
static const CandidateOutcome *best_complete(const std::vector<CandidateOutcome> &out) {
  const CandidateOutcome *best = nullptr;
  for (const CandidateOutcome &co : out)
    if (!co.brief && co.eligible && (!best || co.error_holdout_trimmed < best->error_holdout_trimmed))
      best = &co;
  return best;
}

std::vector<size_t> brief_fits_to_complete(const std::vector<CandidateOutcome> &out, double reach) {
  const CandidateOutcome *best = best_complete(out);
  std::vector<size_t> again;
  for (size_t i = 0; i < out.size(); ++i) {
    const CandidateOutcome &co = out[i];
    if (!co.brief) continue;
    if (!best || (co.joint && co.error_holdout_trimmed < reach * best->error_holdout_trimmed))
      again.push_back(i);
  }
  return again;
}

void complete_dominated_fits(std::vector<CandidateOutcome> &out, const Current &cur,
                             const Context &cx, double min_gain) {
  const std::vector<size_t> again = brief_fits_to_complete(out, cx.opt.dominated_reach);
  const CandidateOutcome *best = best_complete(out);
  const std::string lead = best ? best->cand.name : std::string("no eligible word");
  parallel_for(again.size(), cx.opt.threads, [&](size_t k) {
    CandidateOutcome &co = out[again[k]];
    const double brief_seconds = co.fit_seconds;
    co.brief = false;
    co.origin.clear();
    fit_word(co, cur, cx);
    co.fit_seconds += brief_seconds;
  });
  for (size_t i : again) {
    judge_anew(out[i], cur, cx, min_gain);
    if (!cx.opt.quiet)
      std::fprintf(stderr, "diagnose: %s, fitted briefly beside %s, fitted in full: held-out %.3f%%\n",
                   out[i].cand.name.c_str(), lead.c_str(), 100 * out[i].error_holdout);
  }
}

}  // namespace diag
}  // namespace rtb
