// offline_test_records.h -- small generated records shared by the offline
// tests (kept short so the sanitizer build stays fast).
#ifndef RTB_TESTS_OFFLINE_TEST_RECORDS_H
#define RTB_TESTS_OFFLINE_TEST_RECORDS_H

#include <cmath>
#include <random>
#include <vector>

#include "offline/synth/synthetic_records.h"

namespace rtb_test {

// Paper-like identification data: a triangular periodic record and sines at
// two frequencies (section 5.3), from `truth`, optional relative force noise.
inline std::vector<rtb::Record> paper_records(const rtb_params &truth, double duration,
                                              double noise = 0.0, double dt = 1e-3) {
  using namespace rtb;
  TruthSpec ts;
  ts.p = truth;
  ts.noise = noise;
  ts.oversample = 1;  // identification targets: data from the same discrete model
  std::vector<Record> out;
  const InputSpec specs[] = {{InputKind::Triangle, 1.0, 0.5, duration, dt},
                             {InputKind::Sine, 0.5, 1.0, duration, dt},
                             {InputKind::Sine, 0.2, 10.0, duration, dt}};
  unsigned seed = 11;
  for (const InputSpec &s : specs) {
    ts.seed = seed++;
    out.push_back(synthesize(s, ts, "rec"));
  }
  return out;
}

}  // namespace rtb_test

#endif
