// force_spikes.h -- stage 0 of the diagnosis, third part: isolated spikes in
// the force channel (acquisition glitches: a bit error, a dropped sample, an
// electrical transient). No specimen makes the force jump away and back in
// one sample, so no word may be fitted to them (refgen `spikes`: one sample
// in 200-500 off by 2.5-15% of the elastic force; the robust noise floor
// ignores them, the misfit does not). They leave the misfit, and the
// verdict names them when nothing else is found.
//
// A spike at sample k: the second difference e_k = F_k - (F_{k-1} +
// F_{k+1})/2 is beyond kSpikeSigmas robust standard deviations of e (1.4826
// MAD over the record), beyond 1% of the record's force range, and its two
// neighbours both have the opposite sign at 20-80% of |e_k| (the pattern
// -1/2, 1, -1/2 of a single-sample excursion; a genuine jump of the force
// gives +1/2, -1/2), and e is quiet (within 4 sigma) two and three samples
// either side: the friction damper's records ring at break-away (force
// zig-zags over several samples, 5 such points in one dataset-2 sine
// before this rule), a glitch does not. A record counts as glitched when it has at least
// max(3, 2e-4 n) of them: Gaussian noise gives none at 7 sigma (2.6e-12 per
// sample), Laplace-tailed noise about 5e-5 per sample.
#ifndef RTB_OFFLINE_FORCE_SPIKES_H
#define RTB_OFFLINE_FORCE_SPIKES_H

#include <string>
#include <vector>

#include "rtb_offline.h"

namespace rtb {

struct SpikedRecord {
  std::string file;
  long spikes = 0;          // samples masked
  double largest = 0.0;     // largest |e_k| [force]
  double largest_sigmas = 0.0;  // the same in robust standard deviations of e
};

// Detect isolated spikes in every record and mask them from the misfit
// (rec.masked). Returns the glitched records only.
std::vector<SpikedRecord> mask_force_spikes(std::vector<Record> &recs);

// One sentence for the verdict, e.g. "the force channel has 57 isolated
// one-sample spikes in 5 of 7 records (largest 9.1 N, 14 sigma; left out of
// the misfit)".
std::string spikes_text(const std::vector<SpikedRecord> &s, size_t n_records);

}  // namespace rtb

#endif
