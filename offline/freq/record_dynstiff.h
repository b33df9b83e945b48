// record_dynstiff.h -- dynamic stiffness and loss angle of a measured sine
// record (a test-rig characterization test), and of a model driven by the
// same record.
//
// The record's whole periods are delimited by upward zero crossings of x
// (interpolated; a crossing counts only after x has reached +-10% of its
// peak, so noise cannot fake one). The periods at full amplitude (peak within
// 5% of the record's largest) form the window: the longest run of them, e.g.
// the three constant-amplitude cycles of a ramped-envelope test. The
// fundamental w = 2 pi periods / window length, and X1, F1 are the least-
// squares fundamentals over the window (harmonic.h).
#ifndef RTB_OFFLINE_FREQ_RECORD_DYNSTIFF_H
#define RTB_OFFLINE_FREQ_RECORD_DYNSTIFF_H

#include <string>

#include "freq/harmonic.h"
#include "rtb_offline.h"

namespace rtb {

struct RecordDynStiff {
  std::string path;
  double freq = 0, amp = 0;      // fundamental [1/time], |X1| [length]
  int periods = 0;               // whole periods in the window
  double t_begin = 0, t_end = 0; // the window
  ComplexStiffness measured;
  bool has_model = false;
  ComplexStiffness model;        // the model's force over the same window
};

// Throws InputError naming the file when it holds no whole period.
// p may be nullptr (no model).
RecordDynStiff record_dynamic_stiffness(const Record &rec, const rtb_params *p,
                                        const SimOptions &sim = SimOptions());

}  // namespace rtb

#endif
