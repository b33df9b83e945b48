// artefact_correction_test.cpp -- artefact_corrected (extended_fit.h): the
// records as the element sees them, used by the diagnosis's refit from the
// STS start after a cause is accepted (diagnose.cpp, stage 5c). It must undo
// exactly the force-channel artefacts that predict_extended puts in.
#ifdef RTB_HAVE_OFFLINE
#include <gtest/gtest.h>

#include <cmath>

#include "offline/diagnose/extended_fit.h"
#include "offline/identify/sts_init.h"

namespace rtb {
namespace {

Record offset_sine_record(double dt, double seconds) {
  Record r;
  r.path = "sine";
  for (double t = 0.0; t <= seconds + 1e-12; t += dt) {
    r.t.push_back(t);
    r.x.push_back(std::sin(2.0 * M_PI * 2.0 * t));
    r.F.push_back(0.0);
  }
  return r;
}

TEST(ArtefactCorrection, UndoesTheDelayAndOffsetOfTheExtendedModel) {
  ExtModel m;
  rtb_params_default(&m.p, RTB_MODEL_RT);
  const double dt = 1e-3, delay = 7.5e-3, offset = -3.25;
  Record rec = offset_sine_record(dt, 1.0);
  Eigen::VectorXd element, measured;
  const ExtFitSpec spec;
  predict_extended(m, rec, SimOptions(), spec, element, nullptr);
  m.delay = delay;
  m.offset = offset;
  predict_extended(m, rec, SimOptions(), spec, measured, nullptr);
  for (size_t j = 0; j < rec.F.size(); ++j) rec.F[j] = measured[(Eigen::Index)j];

  const std::vector<Record> corrected = artefact_corrected({rec}, m);
  ASSERT_EQ(corrected.size(), 1u);
  double scale = 0.0, worst = 0.0;
  for (Eigen::Index j = 0; j < element.size(); ++j) scale = std::fmax(scale, std::fabs(element[j]));
  // Two linear interpolations (the model's and the correction's) of a 2 Hz
  // force at 1 kHz, |F''| dt^2 / 8 each: about 1e-4 of the amplitude with
  // the element's harmonics (a wrong sign of the delay would leave ~0.2 of
  // it, of the offset ~5e-3). The
  // first sample is left out: its correction interpolates towards a model
  // force that predict_extended holds at F(t0) before the record starts.
  for (size_t j = 1; rec.t[j] + delay < rec.t.back() - dt; ++j)
    worst = std::fmax(worst, std::fabs(corrected[0].F[j] - element[(Eigen::Index)j]));
  EXPECT_LT(worst, 3e-4 * scale);
  EXPECT_EQ(corrected[0].x, rec.x);  // the displacement is the element's input as recorded
  EXPECT_EQ(corrected[0].t, rec.t);
}

TEST(ArtefactCorrection, WithoutArtefactsTheRecordIsUnchanged) {
  Record rec = offset_sine_record(1e-3, 0.5);
  for (size_t j = 0; j < rec.F.size(); ++j) rec.F[j] = 10.0 * rec.x[j] + 1.0;
  ExtModel m;
  const std::vector<Record> same = artefact_corrected({rec}, m);
  EXPECT_EQ(same[0].F, rec.F);
}

// chain_records: the force of an element with elastic extensions, less
// their static force beyond the tangent at rest, is the force of the same
// element without them and with that tangent added to K0 (the chain's
// state depends on x only), so its STS start is that element's. A softening
// spring with the chain of blindgen softening_s33 (stroke 1, width 0.72):
// from the raw records the STS inversion reads the spring's curvature as
// the chain's and starts Kr several times too stiff.
TEST(ChainRecords, TakeOffTheElasticExtensionsBeyondTheirTangentAtRest) {
  ExtModel with;
  rtb_params_default(&with.p, RTB_MODEL_RT);
  with.p.K0 = -490.0;
  with.p.Kpa = 1320.0;
  with.p.Kr = 21100.0;
  with.p.C0 = 56.9;
  with.p.alpha = 0.277;
  with.p.sat_force = 527.0;
  with.p.sat_disp = 0.72;
  with.p.k3 = -40.0;
  with.p.k2 = 30.0;
  with.p.k_asym = -150.0;  // |k_asym| <= K0 + chain + sat_force/sat_disp = 923 with K0 < 0
  ExtModel without = with;
  without.p.sat_force = without.p.sat_disp = without.p.k3 = without.p.k2 = without.p.k_asym = 0.0;
  without.p.K0 = with.p.K0 + with.p.sat_force / with.p.sat_disp;
  EXPECT_DOUBLE_EQ(elastic_tangent_at_rest(with.p), 527.0 / 0.72);
  EXPECT_EQ(elastic_tangent_at_rest(without.p), 0.0);

  Record rec = offset_sine_record(1e-3, 2.0);
  Eigen::VectorXd Fw, Fo;
  const ExtFitSpec spec;
  predict_extended(with, rec, SimOptions(), spec, Fw, nullptr);
  predict_extended(without, rec, SimOptions(), spec, Fo, nullptr);
  for (size_t j = 0; j < rec.F.size(); ++j) rec.F[j] = Fw[(Eigen::Index)j];
  const std::vector<Record> chain = chain_records({rec}, with);
  double worst = 0.0, scale = 0.0;
  for (Eigen::Index j = 0; j < Fo.size(); ++j) {
    worst = std::fmax(worst, std::fabs(chain[0].F[(size_t)j] - Fo[j]));
    scale = std::fmax(scale, std::fabs(Fo[j]));
  }
  EXPECT_LT(worst, 1e-9 * scale);
  EXPECT_EQ(chain[0].x, rec.x);

  // The STS starts: from these records the plain element's; from the raw
  // ones a chain far from it.
  Record plain = rec;
  for (size_t j = 0; j < plain.F.size(); ++j) plain.F[j] = Fo[(Eigen::Index)j];
  const rtb_params s_chain = sts_initial_guess(chain, 15, 0.2, 0.5);
  const rtb_params s_plain = sts_initial_guess({plain}, 15, 0.2, 0.5);
  const rtb_params s_raw = sts_initial_guess({rec}, 15, 0.2, 0.5);
  EXPECT_NEAR(s_chain.Kr, s_plain.Kr, 1e-6 * s_plain.Kr);
  EXPECT_NEAR(s_chain.Kpa, s_plain.Kpa, 1e-6 * s_plain.Kpa);
  EXPECT_NEAR(s_chain.K0, s_plain.K0, 1e-6 * std::fabs(s_plain.Kpa));
  EXPECT_GT(std::fabs(std::log(s_raw.Kr / s_plain.Kr)), std::log(1.5));
}

TEST(ChainRecords, WithoutElasticExtensionsAreTheArtefactCorrectedRecords) {
  Record rec = offset_sine_record(1e-3, 0.5);
  for (size_t j = 0; j < rec.F.size(); ++j) rec.F[j] = 10.0 * rec.x[j] + 1.0;
  ExtModel m;
  m.offset = 1.0;
  EXPECT_EQ(chain_records({rec}, m)[0].F, artefact_corrected({rec}, m)[0].F);
  // An asymmetry's |x| term has no tangent at rest: all of it goes.
  m.p.k_asym = 4.0;
  for (size_t j = 0; j < rec.F.size(); ++j) rec.F[j] += 4.0 * std::fabs(rec.x[j]);
  const std::vector<Record> c = chain_records({rec}, m);
  for (size_t j = 0; j < rec.F.size(); ++j) EXPECT_NEAR(c[0].F[j], 10.0 * rec.x[j], 1e-12);
}

}  // namespace
}  // namespace rtb
#endif
