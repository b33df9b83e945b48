// preprocess_test.cpp -- the preprocessing of real records (issue #5):
// zero-phase low-pass, reversal masks, weights, and the robustness pieces
// real data needed (stiffness ceiling, undetermined parameters, starts for
// records without a complete cycle).
#include <gtest/gtest.h>

#include <cmath>

#include "adjoint/misfit_gradient.h"
#include "identify/identify.h"
#include "identify/param_transform.h"
#include "identify/sts_init.h"
#include "model/misfit_norms.h"
#include "preprocess/preprocess.h"

namespace rtb {
namespace {

Record filter_sine_record(double f_hz, double dt, double T) {
  Record r;
  r.path = "sine";
  for (double t = 0.0; t <= T + 1e-12; t += dt) {
    r.t.push_back(t);
    r.x.push_back(std::sin(2 * M_PI * f_hz * t));
    r.F.push_back(std::sin(2 * M_PI * f_hz * t));
  }
  return r;
}

// A passive specimen's force rises with its displacement; a record whose
// force falls with it was signed the other way round.
TEST(ForceSign, FlipsOnlyAClearlyOppositeConvention) {
  Record r = filter_sine_record(1.0, 1e-3, 2.0);
  double c = 0.0;
  EXPECT_EQ(force_sign_of({r}, &c), 1);
  EXPECT_NEAR(c, 1.0, 1e-12);
  for (double &f : r.F) f = -900.0 * f + 50.0;  // compression-positive, with a preload
  EXPECT_EQ(force_sign_of({r}, &c), -1);
  EXPECT_NEAR(c, -1.0, 1e-12);
  Record lag = filter_sine_record(1.0, 1e-3, 2.0);  // a lossy loop: the force leads by 60 degrees
  for (size_t i = 0; i < lag.t.size(); ++i) lag.F[i] = std::sin(2 * M_PI * lag.t[i] + M_PI / 3);
  EXPECT_EQ(force_sign_of({lag}), 1);
  Record noise = filter_sine_record(1.0, 1e-3, 2.0);  // no relation: keep the sign as recorded
  for (size_t i = 0; i < noise.t.size(); ++i) noise.F[i] = std::cos(2 * M_PI * 37.0 * noise.t[i]);
  EXPECT_EQ(force_sign_of({noise}), 1);
  Preprocess pp;
  pp.force_sign = -1;
  std::vector<Record> recs = {filter_sine_record(1.0, 1e-3, 0.1)};
  apply_preprocess(pp, recs, true);
  EXPECT_EQ(recs[0].F[10], -filter_sine_record(1.0, 1e-3, 0.1).F[10]);
  EXPECT_EQ(preprocess_json(pp)["force_sign"], -1);
}

TEST(Lowpass, PassesSlowSineWithoutLagAndStopsChatter) {
  const double dt = 1.0 / 1024.0;
  const Record slow = filter_sine_record(0.5, dt, 8.0), fast = filter_sine_record(50.0, dt, 8.0);
  const std::vector<double> ys = lowpass_zero_phase(slow.F, dt, 20.0);
  const std::vector<double> yf = lowpass_zero_phase(fast.F, dt, 20.0);
  double es = 0, af = 0;
  for (size_t i = 0; i < ys.size(); ++i) {
    es = std::fmax(es, std::fabs(ys[i] - slow.F[i]));  // no lag: pointwise equal
    if (i > ys.size() / 4 && i < 3 * ys.size() / 4) af = std::fmax(af, std::fabs(yf[i]));
  }
  EXPECT_LT(es, 1e-3);
  // Butterworth 2nd order twice: |H|^2 at f/fc = 2.5 is 1/(1 + 2.5^4) = 0.0250.
  EXPECT_NEAR(af, 1.0 / (1.0 + std::pow(2.5, 4)), 2e-3);
}

TEST(Lowpass, KeepsAConstantAndRefusesANonUniformGrid) {
  const std::vector<double> c(100, 3.5);
  for (double v : lowpass_zero_phase(c, 0.01, 5.0)) EXPECT_NEAR(v, 3.5, 1e-12);
  std::vector<Record> recs = {filter_sine_record(1.0, 0.01, 2.0)};
  recs[0].t[50] += 0.004;  // 40% jitter at one sample
  Preprocess pp;
  pp.lowpass_hz = 5.0;
  EXPECT_THROW(apply_preprocess(pp, recs, true), InputError);
}

// Decimation keeps every k-th low-passed sample (the rate the element will
// run at) and refuses to alias: the low-pass must be below the new Nyquist.
TEST(Decimate, KeepsEveryKthFilteredSampleAndRefusesToAlias) {
  const double dt = 1.0 / 1024.0;
  Preprocess pp;
  pp.lowpass_hz = 20.0;
  pp.decimate = 5;
  std::vector<Record> recs = {filter_sine_record(0.5, dt, 4.0)};
  const Record orig = recs[0];
  apply_preprocess(pp, recs, false);
  const Record &d = recs[0];
  ASSERT_EQ(d.t.size(), (orig.t.size() + 4) / 5);
  const std::vector<double> filtered = lowpass_zero_phase(orig.F, dt, 20.0);
  for (size_t i = 0; i < d.t.size(); ++i) {
    ASSERT_EQ(d.t[i], orig.t[5 * i]);
    ASSERT_EQ(d.x[i], orig.x[5 * i]);
    ASSERT_EQ(d.F[i], filtered[5 * i]);
  }
  // 1024 / 50 Hz: Nyquist 10.24 Hz, below the 20 Hz low-pass -> error.
  pp.decimate = 50;
  std::vector<Record> aliased = {orig};
  try {
    apply_preprocess(pp, aliased, false);
    FAIL() << "decimation above the low-pass was accepted";
  } catch (const InputError &e) {
    EXPECT_NE(std::string(e.what()).find("Nyquist"), std::string::npos) << e.what();
    EXPECT_EQ(aliased[0].t.size(), orig.t.size()) << "the record changed on error";
  }
  pp.lowpass_hz = 0.0;  // no low-pass at all: also refused
  pp.decimate = 2;
  EXPECT_THROW(apply_preprocess(pp, aliased, false), InputError);
}

TEST(Reversals, FoundThroughNoiseBelowTheBand) {
  std::vector<double> x;
  for (int i = 0; i < 4000; ++i) {  // triangle, period 1000 samples
    const double ph = std::fmod(i / 1000.0 + 0.25, 1.0);
    x.push_back((ph < 0.5 ? 4 * ph - 1 : 3 - 4 * ph) + 1e-3 * std::sin(1.7 * i));
  }
  const std::vector<size_t> r = displacement_reversals(x, 0.02);
  ASSERT_EQ(r.size(), 8u);  // peaks at 250, 1250, ...; troughs at 750, 1750, ...
  for (size_t k = 0; k < r.size(); ++k) EXPECT_NEAR((double)r[k], 250.0 + 500.0 * k, 3.0);
}

TEST(Masks, LeaveSamplesOutOfEveryMisfit) {
  std::vector<Record> recs = {filter_sine_record(1.0, 0.01, 2.0)};
  Preprocess pp;
  pp.masks = {parse_time_window("0.5:1.0", "--mask")};
  pp.weights = {2.0};
  apply_preprocess(pp, recs, true);
  const std::vector<double> w = quadrature_weights(recs[0], 0.0);
  for (size_t i = 0; i < w.size(); ++i) {
    const bool in = recs[0].t[i] >= 0.5 && recs[0].t[i] <= 1.0;
    if (in) EXPECT_EQ(w[i], 0.0) << i;
    else if (i > 0 && i + 1 < w.size()) EXPECT_NEAR(w[i], 2.0 * 0.01, 1e-12) << i;
  }
  // A model wrong only inside the mask has zero error.
  std::vector<double> Fm = recs[0].F;
  for (size_t i = 0; i < Fm.size(); ++i)
    if (recs[0].masked[i]) Fm[i] += 10.0;
  EXPECT_EQ(misfit_norms(recs[0].t, Fm, recs[0].F, recs[0].masked).J, 0.0);
  EXPECT_GT(misfit_norms(recs[0].t, Fm, recs[0].F).J, 0.0);
}

TEST(Masks, BadOptionsAreReportedByName) {
  EXPECT_THROW(parse_time_window("2:1", "--mask"), InputError);
  EXPECT_THROW(parse_time_window("1", "--mask"), InputError);
  EXPECT_THROW(parse_time_window("a:2", "--mask"), InputError);
  std::vector<Record> recs = {filter_sine_record(1.0, 0.01, 1.0), filter_sine_record(1.0, 0.01, 1.0)};
  Preprocess pp;
  pp.weights = {1.0};
  try {
    apply_preprocess(pp, recs, true);
    FAIL() << "one weight for two files must be refused";
  } catch (const InputError &e) {
    EXPECT_NE(std::string(e.what()).find("--weight"), std::string::npos);
  }
  pp.weights.clear();
  pp.masks = {TimeWindow{0.0, 10.0}};
  EXPECT_THROW(apply_preprocess(pp, recs, true), InputError);  // nothing left to fit
}

TEST(StiffnessCeiling, MapsOntoTheOpenIntervalAndRoundTrips) {
  rtb_params p;
  rtb_params_default(&p, RTB_MODEL_RT);
  p.K0 = 3.0;
  p.Kpa = 700.0;
  p.Kr = 20.0;
  const ParamTransform tf({P_K0, P_Kpa, P_Kr}, p, 1000.0);
  const Eigen::VectorXd th = tf.to_theta(p);
  const rtb_params q = tf.to_params(th, p);
  EXPECT_NEAR(q.K0, 3.0, 1e-12);
  EXPECT_NEAR(q.Kpa, 700.0, 1e-9);
  Eigen::VectorXd far = th;
  far[1] = 1e3;  // an optimizer running off
  EXPECT_LE(tf.to_params(far, p).Kpa, 1000.0);
  // dp/dtheta against a central difference.
  const Eigen::VectorXd d = tf.dp_dtheta(th);
  for (int i = 0; i < 3; ++i) {
    Eigen::VectorXd a = th, b = th;
    a[i] += 1e-6;
    b[i] -= 1e-6;
    const ParamId id = tf.free[(size_t)i];
    const double fd = (param_get(tf.to_params(a, p), id) - param_get(tf.to_params(b, p), id)) / 2e-6;
    EXPECT_NEAR(d[i], fd, 1e-6 * std::fabs(fd)) << param_name(id);
  }
}

TEST(Uncertainty, AnUndeterminedParameterGetsInfinityTheOthersStayFinite) {
  // Two informative columns and one exactly zero (a parameter the data do
  // not see): the sandwich covariance must not give up on all three.
  const int m = 200;
  Eigen::MatrixXd J(m, 3);
  Eigen::VectorXd r(m), w = Eigen::VectorXd::Ones(m);
  for (int j = 0; j < m; ++j) {
    J(j, 0) = std::sin(0.1 * j);
    J(j, 1) = std::cos(0.07 * j);
    J(j, 2) = 0.0;
    r[j] = 0.01 * std::sin(3.3 * j);
  }
  std::vector<int> group(m, 0);
  Eigen::VectorXd sd;
  Eigen::MatrixXd corr;
  ASSERT_TRUE(sandwich_covariance(r, J, w, group, sd, &corr));
  EXPECT_TRUE(std::isinf(sd[2]));
  // Unit weights and one record: the sandwich is the textbook
  // sigma^2 (J^T J)^-1 of the two informative columns, with sigma^2 =
  // |r|^2 / (m - 3) (three fitted parameters). The 2x2 inverse written out:
  double a = 0, b = 0, c = 0, rr = 0;
  for (int j = 0; j < m; ++j) {
    a += J(j, 0) * J(j, 0);
    b += J(j, 0) * J(j, 1);
    c += J(j, 1) * J(j, 1);
    rr += r[j] * r[j];
  }
  const double sigma2 = rr / (m - 3), det = a * c - b * b;
  const double c00 = sigma2 * c / det, c11 = sigma2 * a / det, c01 = -sigma2 * b / det;
  EXPECT_NEAR(sd[0], std::sqrt(c00), 1e-10 * std::sqrt(c00));
  EXPECT_NEAR(sd[1], std::sqrt(c11), 1e-10 * std::sqrt(c11));
  EXPECT_NEAR(corr(0, 1), c01 / std::sqrt(c00 * c11), 1e-10);
}

TEST(StartPoint, RecordsWithoutACompleteCycleGetAGenericStart) {
  Record r;  // a single load-unload ramp, as the VHB tests
  r.path = "ramp";
  for (int i = 0; i <= 200; ++i) {
    const double t = 0.1 * i, x = t <= 10 ? t : 20 - t;
    r.t.push_back(t);
    r.x.push_back(x);
    r.F.push_back(2.0 * x + (t <= 10 ? 1.0 : -1.0) * std::min(1.0, x));
  }
  std::string note;
  const rtb_params p = sts_initial_guess({r}, 15, 0.2, 0.0, nullptr, nullptr, &note);
  EXPECT_EQ(rtb_params_validate(&p), RTB_OK);
  EXPECT_NE(note.find("no complete cycle"), std::string::npos);
}

}  // namespace
}  // namespace rtb
