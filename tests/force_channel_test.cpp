// force_channel_test.cpp -- predict_extended's force channel (extended_fit.h):
// the delay's second definition, a first-order low-pass of time constant
// `delay` (a load-cell amplifier's bandwidth), against an independent
// integration of the continuous filter, and the sensitivities the joint fits
// use against central differences, for both definitions.
#ifdef RTB_HAVE_OFFLINE
#include <gtest/gtest.h>

#include <cmath>

#include "ext_model_helpers.h"

namespace rtb {
namespace {

Record channel_sine_record(double dt, double hz, double seconds) {
  Record r;
  r.path = "sine";
  for (double t = 0.0; t <= seconds + 1e-12; t += dt) {
    r.t.push_back(t);
    r.x.push_back(0.8 * std::sin(2.0 * M_PI * hz * t));
    r.F.push_back(0.0);
  }
  return r;
}

using rtb_test::paper_model;
using rtb_test::predicted;

TEST(ForceChannel, TheLowPassIsTheContinuousFirstOrderFilter) {
  const double dt = 1e-4, tau = 5e-3;
  const Record rec = channel_sine_record(dt, 5.0, 1.0);
  const Eigen::VectorXd F = predicted(paper_model(), rec);
  ExtModel m = paper_model();
  m.delay = tau;
  m.delay_lowpass = true;
  const Eigen::VectorXd y = predicted(m, rec);
  // Reference: tau y' = F - y with F linear between samples, RK4 at dt/50.
  const int sub = 50;
  const double hs = dt / sub;
  double yr = F[0], worst = 0.0, scale = 0.0;
  for (Eigen::Index j = 1; j < F.size(); ++j) {
    auto Fin = [&](double s) { return F[j - 1] + (F[j] - F[j - 1]) * s / dt; };
    auto rhs = [&](double s, double v) { return (Fin(s) - v) / tau; };
    for (int i = 0; i < sub; ++i) {
      const double s = i * hs;
      const double k1 = rhs(s, yr), k2 = rhs(s + hs / 2, yr + hs / 2 * k1);
      const double k3 = rhs(s + hs / 2, yr + hs / 2 * k2), k4 = rhs(s + hs, yr + hs * k3);
      yr += hs / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    }
    worst = std::fmax(worst, std::fabs(y[j] - yr));
    scale = std::fmax(scale, std::fabs(F[j]));
  }
  // The channel holds each sample over the interval before it, a lead of
  // dt/2 against the linear input: |y - y_ref| <~ dt/2 max|F'| = 1.6e-3 of
  // the amplitude at 5 Hz. A wrong decay (exp(-dt tau), or no filter) is
  // off by tens of percent: the filter alone lags by 9 degrees here.
  EXPECT_LT(worst, 2e-3 * scale);
  double lag = 0.0;
  for (Eigen::Index j = 0; j < F.size(); ++j) lag = std::fmax(lag, std::fabs(y[j] - F[j]));
  EXPECT_GT(lag, 0.1 * scale);
}

// Central differences of the predicted force in every fitted coordinate.
void expect_jacobian(const ExtModel &m, const Record &rec, const ExtFitSpec &spec) {
  Eigen::MatrixXd J;
  const Eigen::VectorXd F = predicted(m, rec, spec, &J);
  const double scale = F.cwiseAbs().maxCoeff();
  for (Eigen::Index c = 0; c < J.cols(); ++c) {
    const bool is_delay = c == (Eigen::Index)spec.free.size();
    ExtModel a = m, b = m;
    double step;
    if (is_delay) {
      step = 1e-6 * m.delay;
      a.delay += step;
      b.delay -= step;
    } else {
      const ParamId id = spec.free[(size_t)c];
      step = 1e-6 * param_ref(a.p, id);
      param_ref(a.p, id) += step;
      param_ref(b.p, id) -= step;
    }
    const Eigen::VectorXd fd = (predicted(a, rec, spec) - predicted(b, rec, spec)) / (2.0 * step);
    const double colscale = std::fmax(fd.cwiseAbs().maxCoeff(), 1e-12 * scale);
    EXPECT_LT((J.col(c) - fd).cwiseAbs().maxCoeff(), 1e-5 * colscale)
        << (is_delay ? "delay" : "parameter") << " column " << c;
  }
}

// A 3 Hz record, the delay 4.3 ms (between samples: the pure lag's
// interpolation is smooth in delay there), Kpa, C0, alpha and delay free.
void expect_channel_jacobian(bool lowpass, bool lead = false) {
  const Record rec = channel_sine_record(1e-3, 3.0, 1.0);
  ExtModel m = paper_model();
  m.delay = 4.3e-3;
  m.delay_lowpass = lowpass;
  m.delay_lead = lead;
  ExtFitSpec spec;
  spec.free = {P_Kpa, P_C0, P_alpha};
  spec.fit_delay = true;
  expect_jacobian(m, rec, spec);
}

TEST(ForceChannel, LowPassSensitivitiesMatchCentralDifferences) { expect_channel_jacobian(true); }

TEST(ForceChannel, PureDelaySensitivitiesMatchCentralDifferences) { expect_channel_jacobian(false); }

// The third definition, a lead of the force (the displacement channel lags).
TEST(ForceChannel, LeadSensitivitiesMatchCentralDifferences) { expect_channel_jacobian(false, true); }

// A lead is the lag mirrored: F_lead(t) = F(t + d), so shifting the
// prediction by the lag's 2 d lands on the lag's prediction.
TEST(ForceChannel, ALeadIsTheLagMirrored) {
  const Record rec = channel_sine_record(1e-3, 3.0, 1.0);
  ExtModel lag = paper_model(), lead = paper_model();
  lag.delay = lead.delay = 4e-3;
  lead.delay_lead = true;
  const Eigen::VectorXd a = predicted(lag, rec), b = predicted(lead, rec);
  const double scale = a.cwiseAbs().maxCoeff();
  for (Eigen::Index j = 20; j + 20 < a.size(); ++j) ASSERT_NEAR(b[j - 4], a[j + 4], 1e-12 * scale) << j;
  // And artefact correction undoes it.
  Record measured = rec;
  for (Eigen::Index j = 0; j < b.size(); ++j) measured.F[(size_t)j] = b[j];
  const Record corrected = artefact_corrected({measured}, lead)[0];
  const Eigen::VectorXd F = predicted(paper_model(), rec);
  for (Eigen::Index j = 20; j + 20 < F.size(); ++j) ASSERT_NEAR(corrected.F[(size_t)j], F[j], 1e-12 * scale) << j;
}

TEST(ForceChannel, AVanishingLowPassIsFiniteAndTransparent) {
  // A fit can drive the time constant towards 0 (log-parametrized): the
  // force and every sensitivity must stay finite (a NaN reached Eigen's
  // SVD in the covariance and crashed refgen delay+asymmetry seed 7).
  const Record rec = channel_sine_record(1e-3, 3.0, 0.5);
  ExtModel m = paper_model();
  m.delay = 1e-300;
  m.delay_lowpass = true;
  ExtFitSpec spec;
  spec.free = {P_Kpa, P_C0};
  spec.fit_delay = true;
  Eigen::MatrixXd J;
  const Eigen::VectorXd y = predicted(m, rec, spec, &J);
  const Eigen::VectorXd F = predicted(paper_model(), rec);
  EXPECT_TRUE(J.allFinite());
  EXPECT_LT((y - F).cwiseAbs().maxCoeff(), 1e-12 * F.cwiseAbs().maxCoeff());
}

}  // namespace
}  // namespace rtb
#endif
