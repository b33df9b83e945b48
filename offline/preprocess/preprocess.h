// preprocess.h -- what real rig records need before a fit, as explicit,
// recorded options: unit scaling, a zero-phase low-pass of the force,
// decimation to the rate the element will run at, time windows excluded from
// the misfit (machine transients), per-file weights.
//
// Nothing here changes the model; every option is written into the output
// JSON by preprocess_json() so that a fit can be reproduced from its report.
#ifndef RTB_OFFLINE_PREPROCESS_H
#define RTB_OFFLINE_PREPROCESS_H

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "rtb_offline.h"

namespace rtb {

struct TimeWindow {
  double t0 = 0.0, t1 = 0.0;  // s, from the record's first sample (t1 >= t0)
};

struct Preprocess {
  // Column scale factors, applied first (e.g. in -> mm is 25.4, kip -> kN 4.448).
  double time_scale = 1.0, disp_scale = 1.0, force_scale = 1.0;
  // Sign convention of the force against the displacement: +1 as recorded,
  // -1 flipped (a compression-positive load cell on an extension-positive
  // stroke), 0 not decided yet (resolve_force_sign; apply_preprocess then
  // keeps the sign).
  int force_sign = 0;
  // Zero-phase low-pass of the force: a 2nd-order Butterworth run forward and
  // backward (4th-order magnitude, no phase lag, so it cannot pose as a delay).
  // 0: off. Needs a (nearly) uniform time grid.
  double lowpass_hz = 0.0;
  // Keep every k-th sample after the low-pass (1: all). The model then steps
  // at k dt: identify at the rate the controller runs the element. Needs the
  // low-pass below the new Nyquist frequency (no aliasing).
  int decimate = 1;
  // Windows excluded from the misfit in every record.
  std::vector<TimeWindow> masks;
  // s excluded after every reversal of the displacement (and every stop
  // following an overshoot): machine transients at turning points.
  double mask_after_reversal = 0.0;
  // Per-file weights of the fit records (empty: all 1), in --data order.
  std::vector<double> weights;

  bool active() const;
};

// Parses "T0:T1" (seconds); throws InputError with the option name on error.
TimeWindow parse_time_window(const std::string &s, const std::string &option);

// A passive specimen's force rises with its displacement (a positive static
// stiffness, and a positive storage stiffness at every frequency): the
// records' summed covariance of x and F is positive. Returns -1 when the
// records say the opposite clearly (correlation below -0.2), else +1;
// *corr (may be null) receives the correlation.
int force_sign_of(const std::vector<Record> &recs, double *corr = nullptr);

// Applies `pp` to the records in place: scaling, filtering, masks; weights
// are applied only when `use_weights` (fit records, not held-out ones).
// Throws InputError naming the file for what cannot be applied (e.g. a
// low-pass on a non-uniform grid, a weight count that does not match).
void apply_preprocess(const Preprocess &pp, std::vector<Record> &recs, bool use_weights);

// Turning points of x (indices), with a dead band of `band` (same unit as x):
// a reversal is recorded once x has retreated by more than `band` from the
// running extreme. Robust to sensor noise below the band.
std::vector<size_t> displacement_reversals(const std::vector<double> &x, double band);

// Zero-phase low-pass (see Preprocess::lowpass_hz) of y sampled every dt s:
// a Butterworth of order 2 (default) or 4 run forward and backward
// (magnitude 1 / (1 + (f/fc)^(2 order)), no phase).
std::vector<double> lowpass_zero_phase(const std::vector<double> &y, double dt, double cutoff_hz,
                                       int order = 2);

nlohmann::ordered_json preprocess_json(const Preprocess &pp);

}  // namespace rtb

#endif
