// cause_revision_test.cpp -- stage 5d of the diagnosis (cause_revision.cpp):
// an earlier cause that a later one made redundant is dropped, one that
// still pays is kept. Records of the own generator (synthetic_records.h), 4 s,
// 0.5% noise; the model with both causes is fitted jointly first, as the
// pipeline does, so the test sees the decision and not a start that fits
// badly.
#include <gtest/gtest.h>

#include "offline/diagnose/diagnose_stages.h"
#include "offline/synth/synthetic_records.h"

using namespace rtb;

namespace {

const Candidate &word(const std::string &name) {
  for (const Candidate &c : candidate_vocabulary())
    if (c.name == name) return c;
  throw std::invalid_argument("no word " + name);
}

// Stage 5d on the scenario's records with `causes` in the order accepted,
// fitted jointly from `start`. Returns drop_redundant's index; `R` and `cur`
// as the pipeline leaves them.
struct Revision {
  int dropped = -1;
  diag::Current before, after;
  DiagnoseResult R;
};

Revision revise(const Scenario &sc, const ExtModel &start, const std::vector<Candidate> &causes) {
  DiagnoseOptions opt;
  opt.quiet = true;
  MisfitOptions hold_opt = opt.misfit;
  hold_opt.fit_from = 0.0;
  diag::Context cx{sc.fit, sc.holdout, diag::concat(sc.fit, sc.holdout), sc.holdout, hold_opt, opt,
                   data_scales(sc.fit), {}};
  ExtModel truth;
  truth.p = sc.truth.p;
  truth.delay = sc.truth.delay;
  truth.offset = sc.truth.offset;
  cx.floor_sel = extended_error(truth, sc.holdout, hold_opt);  // the noise floor
  const ExtFitSpec spec = combined_spec(causes, cx.sc);
  const ExtFitResult f = fit_extended(sc.fit, start, spec, opt.misfit);
  Revision r;
  r.before = diag::make_current(f.model, spec, causes, cx);
  r.after = r.before;
  r.dropped = diag::drop_redundant(r.after, cx, r.R);
  return r;
}

}  // namespace

// A Maxwell branch accepted first on spectrum data, the spectrum after it:
// the branch adds nothing the spectrum does not hold, so it goes, and the
// model left is the spectrum alone, refitted.
TEST(DropRedundant, AnEarlierMaxwellBranchTheSpectrumCoversIsDropped) {
  const Scenario sc = hidden_effect_scenario("relaxation_spectrum", 5, 0.005, 4.0);
  ExtModel start;
  start.p = sc.truth.p;
  start.p.maxwell_k = 0.1 * sc.truth.p.spec_k;
  start.p.maxwell_tau = 0.3;
  const Revision r = revise(sc, start, {word("maxwell"), word("relaxation_spectrum")});
  ASSERT_EQ(r.dropped, 0);
  ASSERT_EQ(r.R.dropped.size(), 1u);
  EXPECT_EQ(r.R.dropped[0].name, "maxwell");
  ASSERT_EQ(r.after.causes.size(), 1u);
  EXPECT_EQ(r.after.causes[0].name, "relaxation_spectrum");
  EXPECT_EQ(r.after.model.p.maxwell_k, 0.0);  // switched off, not refitted back in
  // The figures reported are the model's without the branch, and it is no
  // worse than the noise allows: within 10% of the model with it.
  EXPECT_DOUBLE_EQ(r.R.dropped[0].error_without, r.after.error_holdout);
  EXPECT_DOUBLE_EQ(r.R.dropped[0].error_with, r.before.error_holdout);
  EXPECT_LT(r.after.error_holdout, 1.1 * r.before.error_holdout);
  EXPECT_EQ(r.R.extended_fit.model.p.maxwell_k, 0.0);
}

// A real Maxwell branch followed by a small offset: without the branch the
// held-out error grows several-fold, so the branch stays and nothing changes.
TEST(DropRedundant, AnEarlierCauseThatStillPaysIsKept) {
  const Scenario sc = hidden_effect_scenario("maxwell", 5, 0.005, 4.0);
  ExtModel start;
  start.p = sc.truth.p;
  const Revision r = revise(sc, start, {word("maxwell"), word("offset")});
  EXPECT_EQ(r.dropped, -1);
  EXPECT_TRUE(r.R.dropped.empty());
  ASSERT_EQ(r.after.causes.size(), 2u);
  EXPECT_EQ(r.after.causes[0].name, "maxwell");
  EXPECT_EQ(r.after.error_holdout, r.before.error_holdout);
  EXPECT_GT(r.after.model.p.maxwell_k, 0.5 * sc.truth.p.maxwell_k);
}
