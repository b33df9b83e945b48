// diagnose.h -- find what the RT model gets wrong in measured data, name the
// cause from a fixed vocabulary, fit the extended model and measure the gain.
//
// 1. Fit plain RT on the fit records (STS start, trust region).
// 2. Analyse the residuals on fit and holdout records.
// 3. Screen every candidate of candidate_vocabulary() at the baseline: the
//    best size of its effect with the RT parameters held, from the exact
//    sensitivities (a linear least-squares step for effects linear in their
//    parameter, a tau grid for Maxwell, a short fit for backlash); then fit
//    the `joint_fits` most promising ones jointly with the RT parameters,
//    warm-started from the screen.
// 4. A candidate is eligible when (a) its amplitude parameter is significant
//    (|value| >= min_z standard deviations), (b) the fit improves by more than
//    the parameter count can explain (delta BIC >= min_dbic) and (c) the
//    held-out error drops by at least min_gain (relative). (b) and (c) use
//    misfits with the largest `trim` fraction of squared residuals dropped,
//    so isolated spikes decide nothing. The cause is the
//    eligible candidate with the lowest held-out error, or "none". A Maxwell
//    branch with tau below two sample intervals is a dashpot: not eligible.
// Basin check: plain RT is nested in every candidate. If an insignificant
// candidate fits below 0.9x the baseline, the baseline is refitted from its
// RT part and steps 1-4 run once more (seen on friction-damper data).
#ifndef RTB_OFFLINE_DIAGNOSE_H
#define RTB_OFFLINE_DIAGNOSE_H

#include <string>
#include <vector>

#include "diagnose/candidates.h"
#include "diagnose/residual_analysis.h"
#include "identify/identify.h"

namespace rtb {

struct DiagnoseOptions {
  int cells = RTB_DEFAULT_CELLS;
  double alpha0 = 0.2;
  MisfitOptions misfit;
  double min_gain = 0.15;   // relative held-out error reduction
  double min_dbic = 10.0;
  double min_z = 3.0;
  double trim = 0.005;      // fraction of largest held-out residuals ignored when selecting
  int threads = 2;
  // Candidates fitted jointly after screening. The screen underrates an
  // effect the baseline has absorbed on the fit records (a small viscous
  // term taken up by the cells: 5th of 10 by its linearized gain, seed 6).
  int joint_fits = 5;
  // Iteration budget of the baseline fit. Data with an effect the RT model
  // lacks can send it down a long valley towards a limit model (rigid cells
  // mimicking an inertia force: 1000 iterations, 170 s); the joint fits start
  // from the baseline and continue with the effect's term, and the basin
  // check refits the baseline when a candidate's RT part does better.
  int baseline_max_iter = 100;
  bool quiet = true;
  std::vector<std::string> only;  // restrict the candidates (empty = all)
};

struct CandidateScreen {
  double value = 0.0;         // best effect size with RT held at the baseline
  double z = 0.0;             // its significance
  double dJ = 0.0;            // misfit reduction it brings (relative to baseline J)
  bool plausible = true;      // sign admissible (e.g. damping >= 0)
  ExtModel start;             // start point of the joint fit
  double seconds = 0.0;       // wall time of the screen
};

struct CandidateOutcome {
  Candidate cand;
  CandidateScreen screen;
  bool joint = false;         // fitted jointly (else screened out)
  ExtFitResult fit;
  double fit_seconds = 0.0;   // wall time of the joint fit
  double error_holdout = 0.0;
  double error_holdout_trimmed = 0.0;  // selection figure (see DiagnoseOptions::trim)
  double dbic = 0.0;          // BIC(baseline) - BIC(candidate), trimmed fit misfits
  double gain = 0.0;          // 1 - trimmed holdout error / baseline's (selection)
  double amplitude_z = 0.0;   // |amplitude parameter| / its standard deviation
  bool eligible = false;
  std::string why;            // reason when not eligible
};

struct DiagnoseResult {
  IdentifyResult baseline_fit;
  ExtModel baseline;
  double baseline_error_fit = 0.0, baseline_error_holdout = 0.0;
  double baseline_error_holdout_trimmed = 0.0;
  bool has_holdout = false;
  std::vector<RecordResiduals> residuals;
  std::vector<CandidateOutcome> candidates;
  int chosen = -1;            // index into candidates, -1 = none
  std::string cause = "none";
  ExtModel extended;          // = baseline when cause is none
  double extended_error_fit = 0.0, extended_error_holdout = 0.0;
  double gain = 0.0;
  std::string verdict;
  double wall_seconds = 0.0;
  // Where the wall time went: baseline identification (including a basin
  // refit), screening, joint fits (all rounds).
  double seconds_baseline = 0.0, seconds_screen = 0.0, seconds_joint = 0.0;
};

DiagnoseResult diagnose(const std::vector<Record> &fit, const std::vector<Record> &holdout,
                        const DiagnoseOptions &opt);

}  // namespace rtb

#endif
