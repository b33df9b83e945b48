// synthetic_records.h -- records generated from known parameters, for tests,
// benchmarks and the demo: the test-rig inputs of the paper (triangular
// cycles, sines, a step with a 0.1 s rise and hold, a multi-sine), the force
// integrated on a grid `oversample` times finer than the record's (so the
// data never share the fitted stepper's discretization), optional
// measurement-chain artefacts and Gaussian force noise.
#ifndef RTB_OFFLINE_SYNTHETIC_RECORDS_H
#define RTB_OFFLINE_SYNTHETIC_RECORDS_H

#include <string>
#include <vector>

#include "rtb_offline.h"

namespace rtb {

enum class InputKind { Triangle, Sine, Step, MultiSine };

struct InputSpec {
  InputKind kind = InputKind::Sine;
  double amplitude = 1.0;   // [length]
  double frequency = 1.0;   // [Hz] (Triangle, Sine; MultiSine base)
  double duration = 10.0;   // [s]
  double dt = 1e-3;         // record sampling [s]
  double rise = 0.1;        // Step: rise time [s]
  double step_at = 0.5;     // Step: start of the rise [s]
};

struct TruthSpec {
  rtb_params p{};           // RT parameters incl. any physical extension
  double delay = 0.0;       // force channel lag [s]
  double offset = 0.0;      // force sensor offset
  double noise = 0.0;       // std of force noise as a fraction of max |F|
  unsigned seed = 1;
  int oversample = 10;
};

std::vector<double> input_displacement(const InputSpec &in, std::vector<double> &t);
Record synthesize(const InputSpec &in, const TruthSpec &truth, const std::string &name);

// The hidden-effect scenario of issue #4: random RT parameters (seeded), one
// effect of the vocabulary at a size that clearly exceeds 0.5% noise, fit
// records (slow triangle, two sines) and holdout records (step and hold,
// multi-sine).
struct Scenario {
  std::string effect;
  TruthSpec truth;
  std::vector<Record> fit, holdout;
};
Scenario hidden_effect_scenario(const std::string &effect, unsigned seed, double noise = 0.005,
                                double duration = 10.0);

}  // namespace rtb

#endif
