// residual_analysis.h -- what the model gets wrong, where in the loop and
// when in time: the residual e = F_measured - F_model of each record against
// candidate signatures (x, v, a, |x|, x^3, sign(v), F_model, dF_model/dt,
// a constant), split by first loading / later cycles, near reversals /
// elsewhere, loop quadrant and time decile.
#ifndef RTB_OFFLINE_RESIDUAL_ANALYSIS_H
#define RTB_OFFLINE_RESIDUAL_ANALYSIS_H

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "diagnose/extended_fit.h"

namespace rtb {

struct Signature {
  std::string name;
  double correlation = 0;  // weighted correlation with the residual
  double explained = 0;    // fraction of residual energy a LS fit of it removes
  double coefficient = 0;  // that LS coefficient (e ~ coefficient * feature)
};

struct RecordResiduals {
  std::string path;
  bool holdout = false;
  double error = 0, rms = 0, mean = 0;
  std::vector<Signature> signatures;  // sorted by `explained`, largest first
  double delay_estimate = 0;          // LS time shift of the model output [time]
  double rms_first_loading = 0, rms_later = 0;
  double rms_near_reversal = 0, rms_elsewhere = 0;
  double rms_quadrant[4] = {0, 0, 0, 0};  // loading x>0, unloading x>0, loading x<0, unloading x<0
  std::vector<double> rms_time_decile;
};

std::vector<RecordResiduals> analyze_residuals(const ExtModel &m, const std::vector<Record> &fit,
                                               const std::vector<Record> &holdout,
                                               const MisfitOptions &opt);
nlohmann::ordered_json residuals_json(const std::vector<RecordResiduals> &r);

}  // namespace rtb

#endif
