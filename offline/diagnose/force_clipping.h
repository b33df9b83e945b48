// force_clipping.h -- stage 0 of the diagnosis, second half: a force channel
// that saturated. An ADC at full scale, or an amplifier at its rail, records
// one and the same value wherever the true force is beyond it: the record's
// extreme value is then held by many samples. No physical word may be fitted
// to such flat tops (refgen `clipping`: a degressive cubic spring imitated
// them), so the clipped samples leave the misfit and the verdict names the
// saturation instead.
//
// A record is clipped at its maximum (minimum) when at least
// max(5, 0.2% of its samples) hold exactly that value, and more than 4 times
// as many as hold the nearest value inside it (a coarsely quantized smooth
// peak holds its top code about as long as the next one). Unclipped records
// hold their extreme once or a few times: at most 3 times in every record
// of ../shared/data (VHB 4910 is written with 4 decimals, the damper with 7
// significant digits).
#ifndef RTB_OFFLINE_FORCE_CLIPPING_H
#define RTB_OFFLINE_FORCE_CLIPPING_H

#include <string>
#include <vector>

#include "rtb_offline.h"

namespace rtb {

struct ClippedRecord {
  std::string file;
  bool top = false, bottom = false;  // clipped at the maximum / minimum
  double level_top = 0.0, level_bottom = 0.0;  // the held values [force]
  long samples = 0;                  // samples at a clipped level
};

// Detect clipping in every record and mask the clipped samples from the
// misfit (rec.masked). Returns the clipped records only.
std::vector<ClippedRecord> mask_force_clipping(std::vector<Record> &recs);

// One sentence for the verdict, e.g. "the force channel is clipped at
// +12.5 / -12.5 in 3 of 5 records (812 samples left out of the misfit)".
std::string clipping_text(const std::vector<ClippedRecord> &c, size_t n_records);

}  // namespace rtb

#endif
