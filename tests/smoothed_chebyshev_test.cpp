// smoothed_chebyshev_test.cpp -- the eq. (14) smoothing in the stage solve
// (issue #11, session 47): its Taylor series below s|v| = RTB_SLAW_SERIES
// (dashpot_law.h), the curvature psi_s''/psi_s' that each evaluation now
// returns, and the Chebyshev step it gives the smoothed stage (newton_step.h
// rtb_newton_second_order_curv). What must hold: the series is the closed
// form to rounding, the second-order term is the residual's own curvature,
// and every returned smoothed stage still solves eq. (2) with the exact
// eq. (14) to the tolerance, with less work than before.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "dashpot_law.h"
#include "newton_step.h"
#include "rt_bushing/rt_bushing.h"
#include "rtb_internal.h"
#include "tests/physics_helpers.h"
#include "tests/stage_residual.h"

namespace {

constexpr double kC0 = 40.0;

}  // namespace

// The series (P0 > 0) against the closed form (P0 = 0: expm1, log1p, log,
// exp) from s|v| = 1e-12 to just below the threshold, over five decades of
// s and the whole alpha range. Both carry the rounding of their own exp of
// alpha ln|v|_s (up to ~alpha |ln|v|_s| eps), hence 1e-14 and not an ulp;
// measured 5.4e-15 (force), 5.3e-15 (slope), 7.1e-15 (curvature).
TEST(SmoothedSeries, IsTheClosedFormBelowItsThreshold) {
  for (const double alpha : {RTB_ALPHA_MIN, 0.05, 0.2, 0.5, 0.9, 1.0}) {
    for (const double s : {1e-3, 1.0, 100.0, 1e4, 1e8}) {
      const double P0 = rtb_slaw_series_scale(alpha, s);
      ASSERT_GT(P0, 0.0);
      for (int i = 0; i <= 200; ++i) {
        const double x = 0.999 * RTB_SLAW_SERIES * std::pow(10.0, -12.0 * (200 - i) / 200.0);
        for (const double v : {x / s, -x / s}) {
          double Ds, Dc, cs, cc;
          const double fs = rtb_slaw_eval(v, kC0, alpha, s, P0, &Ds, &cs);
          const double fc = rtb_slaw_eval(v, kC0, alpha, s, 0.0, &Dc, &cc);
          EXPECT_NEAR(fs, fc, 1e-14 * std::fabs(fc)) << "alpha " << alpha << " s " << s << " x " << x;
          EXPECT_NEAR(Ds, Dc, 1e-14 * Dc) << "alpha " << alpha << " s " << s << " x " << x;
          EXPECT_NEAR(cs, cc, 1e-13 * std::fabs(cc)) << "alpha " << alpha << " s " << s << " x " << x;
        }
      }
      // At rest: no force, no curvature, and the documented finite slope
      // C0 (s/2)^(1-alpha) (ln 2)^alpha.
      double D0, c0;
      EXPECT_EQ(rtb_slaw_eval(0.0, kC0, alpha, s, P0, &D0, &c0), 0.0);
      EXPECT_EQ(c0, 0.0);
      const double slope = kC0 * std::pow(s / 2.0, 1.0 - alpha) * std::pow(std::log(2.0), alpha);
      EXPECT_NEAR(1.0 / D0, slope, 1e-14 * slope) << "alpha " << alpha << " s " << s;
    }
  }
}

// The curvature each evaluation returns is psi_s''/psi_s', in every regime
// (series, transition, sharp), against a central difference of the slope.
TEST(SmoothedSeries, CurvatureIsTheSlopesLogDerivative) {
  const double s = 100.0;
  for (const double alpha : {RTB_ALPHA_MIN, 0.2, 0.9}) {
    const double P0 = rtb_slaw_series_scale(alpha, s);
    for (const double x : {3e-3, 0.3, 3.0, 30.0, 300.0}) {
      for (const double v : {x / s, -x / s}) {
        double D, c, Dp, Dm, cu;
        rtb_slaw_eval(v, kC0, alpha, s, P0, &D, &c);
        const double h = 1e-5 * std::fabs(v);
        rtb_slaw_eval(v + h, kC0, alpha, s, P0, &Dp, &cu);
        rtb_slaw_eval(v - h, kC0, alpha, s, P0, &Dm, &cu);
        const double fd = (std::log(1.0 / Dp) - std::log(1.0 / Dm)) / (2.0 * h);  // (ln psi')'
        EXPECT_NEAR(c, fd, 1e-6 * std::fabs(c) + 1e-9 * std::fabs(1.0 / v))
            << "alpha " << alpha << " x " << x << " v " << v;
      }
    }
  }
}

// Q = 1/2 H''[dl, dl] along the update, as the stage solver moves each DOF
// (steep: v by D dl with f = psi_s(v); else f by dl with v = phi_s(f)),
// against the residual's second difference along that path. A wrong sign,
// factor or DOF rule leaves an error of the size of Q.
TEST(SmoothedChebyshev, SecondOrderTermIsTheResidualsCurvature) {
  const int n = 6;
  const double s = 100.0, hK0 = 3.0, hKr = 1.7;
  for (const double alpha : {0.05, 0.3, 0.9}) {
    rtb_law L;
    rtb_law_init(&L, kC0, alpha, s, 0.0);
    const double xs[n] = {2e-3, 0.4, 4.0, 60.0, -0.7, -900.0};  // s v of each cell
    const bool steep[n] = {true, false, true, false, true, false};
    double f[n], v[n], D[n], C[n], dl[n];
    for (int k = 0; k < n; ++k) {
      v[k] = xs[k] / s;
      f[k] = rtb_law_eval_v_c(&L, v[k], &D[k], &C[k]);
      dl[k] = 0.01 * std::fabs(f[k]) * (k % 2 ? -1.0 : 1.0);  // a 1% move of each force
    }
    auto residual = [&](double t, double *H) {
      double ft[n], vt[n], hKv[n];
      for (int k = 0; k < n; ++k) {
        int evals;
        double Dk;
        if (steep[k]) {
          vt[k] = v[k] + t * D[k] * dl[k];
          ft[k] = rtb_law_eval_v(&L, vt[k], &Dk);
        } else {
          ft[k] = f[k] + t * dl[k];
          vt[k] = rtb_slaw_velocity_p(ft[k], kC0, alpha, s, L.P0, v[k], RTB_SLAW_INV_ITERS, 0.0,
                                      &evals, nullptr, nullptr);
        }
      }
      rtb_newton_hK_apply(n, hK0, hKr, vt, hKv);
      for (int k = 0; k < n; ++k) H[k] = ft[k] + hKv[k];
    };
    double Q[n], Hp[n], Hm[n], H0[n], sc;
    const double qmax = rtb_newton_second_order_curv(n, hK0, hKr, steep, D, C, dl, Q, &sc);
    ASSERT_GT(qmax, 0.0);
    const double t = 0.1;
    residual(t, Hp);
    residual(-t, Hm);
    residual(0.0, H0);
    for (int k = 0; k < n; ++k) {
      const double fd = (Hp[k] + Hm[k] - 2.0 * H0[k]) / (2.0 * t * t);
      EXPECT_NEAR(Q[k], fd, 0.02 * qmax) << "alpha " << alpha << " cell " << k;
    }
    EXPECT_GT(sc, 0.0);
  }
}

// For eq. (1) the curvature (alpha - 1)/v gives rtb_newton_second_order's
// term: one formula for both laws.
TEST(SmoothedChebyshev, CurvatureFormReducesToThePowerLaws) {
  const int n = 4;
  const double alpha = 0.2, hK0 = 2.0, hKr = 0.9;
  const bool steep[n] = {true, false, false, true};
  const double v[n] = {0.3, -0.02, 1e-4, -2.0}, dl[n] = {0.5, -0.1, 0.02, 0.3};
  double f[n], D[n], C[n], Q1[n], Q2[n], move, sc;
  for (int k = 0; k < n; ++k) {
    f[k] = rtb_law_force(v[k], kC0, alpha);
    D[k] = rtb_law_dvdf(f[k], v[k], alpha);
    C[k] = (alpha - 1.0) / v[k];
  }
  rtb_newton_second_order(n, hK0, hKr, alpha, steep, f, v, D, dl, Q1, &move);
  rtb_newton_second_order_curv(n, hK0, hKr, steep, D, C, dl, Q2, &sc);
  for (int k = 0; k < n; ++k) EXPECT_NEAR(Q2[k], Q1[k], 1e-13 * std::fabs(Q1[k])) << "cell " << k;
}

namespace {

struct SmoothedRun {
  double worst = 0.0;  // max relative residual with the exact eq. (14), all stages
  std::vector<int> work;
  int not_converged = 0;
};

// 3000 steps of BM_Extension's input (10 Hz, 1 mm sine + 10 um noise at
// 1 kHz) on the paper's element, N = 15, smoothed by s.
SmoothedRun run_smoothed(double s, double tol, int integrator) {
  rtb_params p = rtbtest::paper_params(RTB_MODEL_RT, 15, integrator);
  p.smoothing = s;
  SmoothedRun o;
  rtbtest::drive_noisy_sine(p, tol, 3000, 11, [&](int i, rtb_status q, const rtb_step_info &info,
                                                  const rtb_stage *stg) {
    EXPECT_GE(q, 0) << "step " << i;
    o.not_converged += q == RTB_NOT_CONVERGED;
    if (i > 500) o.work.push_back(info.work);
    for (int j = 0; q >= 0 && j < rtb_integrator_stages(&p); ++j) {
      int locked, loaded;
      o.worst = std::fmax(o.worst, rtbtest::full_residual(p, stg[j], &locked, &loaded));
    }
  });
  std::sort(o.work.begin(), o.work.end());
  return o;
}

}  // namespace

// Every stage the Chebyshev step ended still solves eq. (2) with the exact
// eq. (14) to the tolerance (the inverse's own force tolerance, a hundredth
// of it, included), from a nearly linear dashpot (s = 1) to one that is
// eq. (1) but near rest (s = 1e4); and the median work per step is below
// what the Newton step alone spent on this input (s = 100, SDIRK2, default
// tolerance: 307 units per step before session 47, 223 with this step).
TEST(SmoothedChebyshev, StagesMeetTheToleranceWithLessWork) {
  for (const int integrator : {RTB_INTEGRATOR_SDIRK2, RTB_INTEGRATOR_BE}) {
    for (const double s : {1.0, 100.0, 1e4}) {
      for (const double tol : {1e-8, 1e-12}) {
        const SmoothedRun o = run_smoothed(s, tol, integrator);
        EXPECT_EQ(o.not_converged, 0) << "s " << s << " tol " << tol;
        EXPECT_LE(o.worst, 2.0 * tol) << "s " << s << " tol " << tol << " integrator " << integrator;
      }
    }
  }
  rtb_settings set;
  rtb_settings_default(&set);
  const SmoothedRun o = run_smoothed(100.0, set.tol, RTB_INTEGRATOR_SDIRK2);
  ASSERT_FALSE(o.work.empty());
  EXPECT_LE(o.work[o.work.size() / 2], 260);
}
