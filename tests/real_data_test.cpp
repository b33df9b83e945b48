// real_data_test.cpp -- the measured data of ../shared/data (issue #5), when
// present: identification converges, and the fitted model explains the data
// better than the simplest physical baseline -- a linear spring F = k x
// fitted to the same records (weighted least squares, same error norm,
// eq. (27)), which the RT model contains as its K0 branch -- on the fitted
// and on the held-out records; and the friction damper's diagnosis names its
// clearance of the
// size the data README states. (Bounds are not taken from the code's own
// output.) Skips with a message when the folder is absent (a user's clone)
// and in the sanitizer tree (minutes of fitting under ASan).
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "identify/identify.h"
#include "identify/sts_init.h"
#include "model/misfit_norms.h"
#include "report/study.h"

namespace rtb {
namespace {

std::string data_dir() {
  const char *env = std::getenv("RTB_DATA_DIR");
  return env ? env : RTB_SHARED_DATA_DIR;
}

// Error sqrt(J/J0) on `eval` of the linear spring through the origin,
// F = k x, fitted to `fit` (weighted least squares with the misfit's
// quadrature weights) -- the protocol the model follows -- in the misfit's own
// norm: evaluated by the same misfit() (a stepper whose chain is negligible,
// Kpa = 1e-12 k).
double linear_spring_error(const std::vector<Record> &fit, const std::vector<Record> &eval,
                           const MisfitOptions &o) {
  double fx = 0, xx = 0;
  for (const Record &r : fit) {
    const std::vector<double> w = quadrature_weights(r, o.fit_from);
    for (size_t j = 0; j < r.x.size(); ++j) {
      fx += w[j] * r.F[j] * r.x[j];
      xx += w[j] * r.x[j] * r.x[j];
    }
  }
  rtb_params p;
  rtb_params_default(&p, RTB_MODEL_RT);
  p.K0 = std::fabs(fx / xx);
  p.Kpa = 1e-12 * p.K0;
  p.Kr = p.K0;
  return misfit(p, eval, o, false).error();
}

bool skip_reason(std::string *why) {
#ifdef RTB_TEST_SANITIZE_FLAGS
  *why = "real-data studies take minutes; they run in the Release tree only";
  return true;
#endif
  struct stat st{};
  if (stat(data_dir().c_str(), &st) != 0 || !S_ISDIR(st.st_mode)) {
    *why = "measured data folder " + data_dir() + " absent (set RTB_DATA_DIR); skipping";
    return true;
  }
  return false;
}

TEST(RealData, FrictionDamperDiagnosisFindsTheClearance) {
  std::string why;
  if (skip_reason(&why)) GTEST_SKIP() << why;
  StudySpec spec = friction_damper_study();
  // The test's budget (minutes, not the report's ten): the candidates a
  // friction device with play could show, and no stacked second stage.
  // `make report` runs the whole vocabulary (docs/results/friction_damper.md).
  // maxwell stays: its joint fit is the one whose RT part finds the better
  // baseline basin (22% against 47% from the STS start), see diagnose.h.
  spec.diag.only = {"backlash", "friction_asymmetry", "offset", "viscous", "maxwell"};
  spec.diag.max_causes = 2;
  spec.second_stage.clear();
  // The study decimates 1024 Hz -> 205 Hz after its 20 Hz low-pass: at
  // 1024 Hz the same diagnosis gives the same causes and errors to 0.1%
  // (measured: held-out 60.98% against 61.02%) in 190 s instead of 23 s.
  ASSERT_EQ(spec.pre.decimate, 5);
  const StudyResult r = run_study(spec, data_dir(), true);
  // Issue #10's target: backlash among the causes (its order against
  // friction asymmetry depends on which the baseline basin favours).
  const Cause *backlash = nullptr;
  for (const Cause &c : r.diag.causes)
    if (c.cand.name == "backlash") backlash = &c;
  ASSERT_NE(backlash, nullptr) << r.diag.verdict;
  // The data README: a clearance of roughly 0.1-0.2 in at every reversal.
  EXPECT_GT(r.diag.extended.p.backlash, 0.1);
  EXPECT_LT(r.diag.extended.p.backlash, 0.25);
  // The extension must help on the held-out earthquake records, and both
  // models must beat an elastic spring there (a friction damper dissipates:
  // a spring cannot draw its loop).
  EXPECT_LT(r.err_val_ext, 0.8 * r.err_val_base);
  EXPECT_LT(r.err_fit_ext, r.err_fit_base);
  const double spring_fit = linear_spring_error(r.fit, r.fit, spec.diag.misfit);
  const double spring_val = linear_spring_error(r.fit, r.validation, spec.diag.misfit);
  std::printf("[real] friction damper (%zu samples in the first fit record): error fit %.3f "
              "(spring %.3f), validation %.3f (spring %.3f); %s\n",
              r.fit[0].t.size(), r.err_fit_ext, spring_fit, r.err_val_ext, spring_val,
              r.diag.verdict.c_str());
  EXPECT_LT(r.err_fit_ext, spring_fit);
  EXPECT_LT(r.err_val_ext, spring_val);
}

TEST(RealData, Vhb4910IdentificationConvergesAndValidatesOnRelaxation) {
  std::string why;
  if (skip_reason(&why)) GTEST_SKIP() << why;
  // The report's baseline: all 16 load-unload tests, validated on the four
  // relaxation tests inside the identified stretch range.
  const StudySpec spec = vhb4910_study();
  std::vector<Record> fit, val;
  for (const std::string &f : spec.fit_files) fit.push_back(read_record_csv(data_dir() + "/" + f));
  for (const std::string &f : spec.validation_files) val.push_back(read_record_csv(data_dir() + "/" + f));
  apply_preprocess(spec.pre, fit, true);
  apply_preprocess(spec.pre, val, false);
  const rtb_params start = sts_initial_guess(fit, RTB_DEFAULT_CELLS, 0.2, 0.0);
  IdentifyOptions o;
  o.restarts = 0;
  const IdentifyResult res = identify(fit, start, o);
  EXPECT_TRUE(res.converged) << res.message;
  EXPECT_LT(res.error, 0.6 * res.error_start);
  // VHB 4910 is viscoelastic: a spring cannot follow its relaxation or the
  // loading/unloading difference, the RT model must do better on both sets.
  const MisfitValue v = misfit(res.params, val, o.misfit, false);
  const double spring_fit = linear_spring_error(fit, fit, o.misfit);
  const double spring_val = linear_spring_error(fit, val, o.misfit);
  std::printf("[real] VHB 4910: error fit %.3f (spring %.3f), validation %.3f (spring %.3f)\n",
              res.error, spring_fit, v.error(), spring_val);
  EXPECT_LT(res.error, spring_fit);
  EXPECT_LT(v.error(), spring_val);
}

}  // namespace
}  // namespace rtb
