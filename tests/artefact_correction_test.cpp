// artefact_correction_test.cpp -- artefact_corrected (extended_fit.h): the
// records as the element sees them, used by the diagnosis's refit from the
// STS start after a cause is accepted (diagnose.cpp, stage 5c). It must undo
// exactly the force-channel artefacts that predict_extended puts in.
#ifdef RTB_HAVE_OFFLINE
#include <gtest/gtest.h>

#include <cmath>

#include "offline/diagnose/extended_fit.h"

namespace rtb {
namespace {

Record sine_record(double dt, double seconds) {
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
  Record rec = sine_record(dt, 1.0);
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
  Record rec = sine_record(1e-3, 0.5);
  for (size_t j = 0; j < rec.F.size(); ++j) rec.F[j] = 10.0 * rec.x[j] + 1.0;
  ExtModel m;
  const std::vector<Record> same = artefact_corrected({rec}, m);
  EXPECT_EQ(same[0].F, rec.F);
}

}  // namespace
}  // namespace rtb
#endif
