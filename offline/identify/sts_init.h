// sts_init.h -- initial values from the STS model (section 5.4): measure
// the hysteresis-loop features Tg1, Tg2, Fmax, Xmax on the stabilized cycles
// of a record, invert eq. (21)-(24) for the STS parameters and map them to RT
// starting values with eq. (25)-(26).
#ifndef RTB_OFFLINE_STS_INIT_H
#define RTB_OFFLINE_STS_INIT_H

#include <string>
#include <vector>

#include "rtb_offline.h"

namespace rtb {

struct LoopFeatures {
  double Tg1 = 0, Tg2 = 0;   // tangent slopes just after / just before a cusp
  double Fmax = 0, Xmax = 0; // half peak-to-peak force and displacement
  double Ksec = 0;           // Fmax / Xmax, eq. (17)
  double V0 = 0;             // mean |velocity| over the cycles [length/time]
  int cycles = 0;            // complete cycles averaged
};

// Features averaged over every complete cycle after t0 + fit_from (both
// cusps of each). Slopes come from quadratic least-squares fits over a window
// of `window` (fraction of the peak-to-peak travel) next to each reversal, so
// force noise of a few percent averages out. Throws InputError when the
// record holds no complete cycle.
LoopFeatures detect_loop_features(const Record &rec, double fit_from = 0.0, double window = 0.08);

struct StsParams {
  double K0 = 0, Kpa = 0, Kr = 0, Ff = 0;
};
// eq. (21)-(24) for N cells, fed the peak-to-peak force and displacement
// (2 Fmax, 2 Xmax): eq. (20) as printed is the peak-to-peak force.
StsParams invert_sts(const LoopFeatures &f, int cells);

// eq. (25)-(26): K0, Kpa, Kr from STS, C0 = Ff / V0^alpha0. A non-physical
// inversion (any of K0 < 0, Kpa, Kr, Ff <= 0: inconsistent features) is
// replaced as a whole by the fallbacks (K0 = Ksec / 2, Kpa = max(Tg1 - K0,
// Ksec / 2), Kr = cells Kpa) with the loop's sliding level, Ff = (Fmax - K0
// Xmax) / cells, and reported in `note`. Without a loop (all NaN) Ff =
// Fmax / (10 cells).
rtb_params rt_start_from_sts(const StsParams &s, const LoopFeatures &f, int cells, double alpha0,
                             std::string *note = nullptr);

// Convenience: features averaged over records, inversion, mapping.
rtb_params sts_initial_guess(const std::vector<Record> &recs, int cells, double alpha0,
                             double fit_from, LoopFeatures *feat = nullptr,
                             StsParams *sts = nullptr, std::string *note = nullptr);

// A friction-device start: a Jenkins element, one slider carrying the load
// (the cells decoupled by Kr = 1e-3 Kpa) at a small alpha, with K0 = Tg2 the
// slope while sliding, Kpa = Tg1 - K0 and the slider level Fmax - K0 Xmax.
// On a device that slides, plain RT from the STS start can end in a viscous
// basin (the friction damper's dataset-3 sines: fit 48% with alpha 0.61,
// against 21.5% with alpha 0.05 from this start).
rtb_params friction_initial_guess(const std::vector<Record> &recs, int cells, double fit_from);
// The same from features already measured (`sts_start` from
// sts_initial_guess on the same records: its cell count and extensions).
rtb_params friction_initial_guess(const rtb_params &sts_start, const LoopFeatures &f);

}  // namespace rtb

#endif
