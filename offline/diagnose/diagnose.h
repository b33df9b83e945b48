// diagnose.h -- find what the RT model gets wrong in measured data, name the
// cause(s) from a vocabulary, fit the extended model and measure the gain.
//
// The pipeline (diagnose.cpp), one stage per function or file:
// 0. input        a noisy displacement is low-passed for the model input
//                 (displacement_noise.h: robust velocity and acceleration);
//                 samples where the force channel saturated leave the misfit
//                 (force_clipping.h), and the verdict names the saturation
//                 instead of a cause fitted to the partial loops; so do
//                 isolated one-sample spikes (force_spikes.h).
// 1. baseline     plain RT on the fit records (STS start, trust region).
// 2. noise floor  the white-noise level of the residual, estimated from the
//                 data (noise_floor.h): how small the residual can get.
// 3. screen       every candidate at the current model, on ALL records (an
//                 effect may show mainly in the held-out kind: inertia at high
//                 frequency), from the exact sensitivities (screen.h).
// 4. joint fits   the most promising candidates fitted jointly with the
//                 current model's parameters on the fit records; when the
//                 first round names none and the baseline is far above a
//                 floor, the next few by significance too (fit_past_the_cut).
// 5. selection    a candidate is eligible when its amplitude is significant
//                 (z >= min_z), the fit improves by more than its parameter
//                 count explains (delta BIC >= min_dbic), the held-out error
//                 drops by min_gain (relative, trimmed of isolated spikes) or,
//                 near the floor, by half its excess over the floor,
//                 and the data do not contradict it (plausibility.h: an offset
//                 must agree with at-rest segments, a delay with the
//                 cross-correlation, slack with zero-force segments). The
//                 lowest held-out error among the eligible wins, unless a
//                 candidate with fewer parameters comes within `parsimony`
//                 of it (a two-parameter relaxation spectrum imitates a
//                 viscous dashpot: the simpler word is then the cause); a
//                 word that takes an earlier cause to nothing counts its
//                 parameters net of that cause's.
//                 The accepted cause's model is refitted once from the STS
//                 start of the records its artefacts removed (the joint fit
//                 began in the basin that compensated for the missing cause);
//                 the refit stands if it fits better; if it does, the cause
//                 must still pay against the model without it refitted from
//                 the new basin (and a Maxwell branch after the spectrum
//                 against the spectrum widened to it), or it is no cause.
//                 A later cause must also pay against the earlier causes
//                 refitted at another cell count N (10, 12, 20): the chain's
//                 N is a modelling choice, and a specimen that is another
//                 chain's leaves a residual a further word would take.
//                 An earlier cause that no longer pays once the new one is
//                 in is dropped. Stages
//                 3-5 repeat at the extended model while a further cause
//                 still pays on held-out data and the residual is above the
//                 noise floor (several causes).
// 6. report       causes, or `none` when the baseline is at the noise floor,
//                 or `unexplained` with the residual's signature (band, trend,
//                 where in the cycle) when it is above the floor and no
//                 candidate removes it: a wrong physical name is worse.
//                 Causes whose own remaining residual is mostly a slow trend
//                 over time are withdrawn: the vocabulary is time-invariant,
//                 so they only compensate a drift (`withdrawn` in the JSON).
// Basin check: plain RT is nested in every candidate. If an insignificant
// candidate fits below 0.9x the baseline, the baseline is refitted from its
// RT part and the first round runs once more. Likewise in a later round
// (stage 5f, repair_basin): the current causes are refitted from such a
// candidate's fit without its word; the round is judged against the refit,
// or run once more if the refit is still above the noise floor.
#ifndef RTB_OFFLINE_DIAGNOSE_H
#define RTB_OFFLINE_DIAGNOSE_H

#include <string>
#include <vector>

#include "diagnose/candidates.h"
#include "diagnose/displacement_noise.h"
#include "diagnose/force_clipping.h"
#include "diagnose/force_spikes.h"
#include "diagnose/noise_floor.h"
#include "diagnose/residual_analysis.h"
#include "diagnose/screen.h"
#include "identify/identify.h"

namespace rtb {

struct DiagnoseOptions {
  int cells = RTB_DEFAULT_CELLS;
  double alpha0 = 0.2;
  MisfitOptions misfit;
  double min_gain = 0.15;   // relative held-out error reduction of the first cause
  double min_gain_next = 0.10;  // ... of each further cause
  // Near the noise floor a relative gain of min_gain is out of reach even for
  // the right word (refgen relaxation_spectrum_s3: the baseline is 1.27x the
  // floor, so at most 21%). A candidate also passes the gain test when it
  // removes this share of the current error's excess over the floor with at
  // least min_gain_near_floor of relative gain (plain data: every candidate
  // of refgen's none_s1-s3 removes at most 3%).
  double min_excess_removed = 0.5;
  double min_gain_near_floor = 0.05;
  // Held-out records within this factor of their floor show no effect to
  // gain on (an effect seen in the fit records only: blindgen slack_s13, a
  // random held-out record that never goes slack, 1.872% at a floor of
  // 1.874%); the fit records then decide (fit_records_decide), when their
  // excess over their own floor is at least min_fit_excess of it (slack_s13:
  // 1.932% at 1.674%, 0.15; plain data of refgen and blindgen 0.01-0.04).
  // With one or two parameters against thousands of samples, an in-sample
  // gain of half such an excess is not over-fitting; a misjudged floor would
  // be, hence the margin.
  double holdout_at_floor = 1.05;
  double min_fit_excess = 0.1;
  double min_dbic = 10.0;
  double min_z = 3.0;
  double trim = 0.005;      // fraction of largest held-out residuals ignored when selecting
  // An eligible candidate with fewer parameters whose held-out error is
  // within this fraction of the best one's is preferred (parsimony).
  double parsimony = 0.10;
  // The residual is "at the noise floor" below this multiple of the floor's
  // eq. (27) error (noise_floor.h); above it, no candidate means `unexplained`.
  double floor_ratio = 1.3;
  int max_causes = 3;
  // Stage 6: causes whose remaining residual (above the floor) is more than
  // this share a + b t trend, or withdraw_drift_share a t F_model stiffness
  // drift, are withdrawn: a time-invariant word only compensates a drift.
  // Both are measured where the displacement moves: during a hold a slow
  // residual is a relaxation shape (VHB 4910's 1800 s holds).
  // Of 180 kept reports with a right word the largest trend share is 0.033
  // and the largest drift share 0.037; refgen zero_drift leaves 0.23-0.76.
  double withdraw_trend_share = 0.1;
  double withdraw_drift_share = 0.3;
  // ... or more than this share a scale and a drift of the model force per
  // record: the records disagree on the stiffness (a specimen warmer or
  // older in one test than another), which no word of one specimen follows.
  // Blindgen thermal_drift_s10 leaves 0.95 after `maxwell` (named for it),
  // s11 0.91; the words named on 8 cases whose residual stays above the
  // floor (mullins, inertia, viscous, viscous+cubic_stiffness,
  // backlash+cubic, maxwell+offset) leave 0.05-0.39.
  double withdraw_record_scale_share = 0.6;
  // Stage 5e (cause_pair.cpp): when no single word pays in the first round
  // and the baseline is above pair_above_floor times the floor (of the
  // held-out records or of the fit records), the
  // pair_leads first-round words with the largest held-out gains (at least
  // pair_lead_gain) are each tried with a second word. Three leads from 3%:
  // with the displacement filtered (stage 0), blindgen mullins+delay_s5's
  // baseline is 2 points better held out and its delay, the pair's first
  // member, gains 4% there (15% unfiltered), behind a cubic spring (6%)
  // and a Mullins loss (5%) that pair with nothing.
  double pair_above_floor = 3.0;
  int pair_leads = 3;
  double pair_lead_gain = 0.03;
  // Stage 1: the friction start is tried when the STS start's baseline fit
  // error is above friction_start_above (damper: 47-48%), and its baseline
  // replaces the STS start's when its fit error is below
  // friction_start_margin times it.
  double friction_start_above = 0.15;
  double friction_start_margin = 0.8;
  // The friction start's fit is probed for this many iterations (no
  // restarts) and run to the end only when the probe already fits better
  // than the STS start's end: the margin above leaves 20% to the rest.
  int friction_probe_iter = 20;
  // After a cause is accepted, a refit from the STS start replaces the
  // accepted fit when its fit error is lower by more than this fraction.
  double refit_margin = 0.01;
  int threads = 2;
  // Candidates fitted jointly after screening: the first round, later rounds.
  // The screen underrates an effect the baseline has absorbed on the fit
  // records (a small viscous term taken up by the cells: 5th of 10 by its
  // linearized gain, seed 6).
  int joint_fits = 5;
  int joint_fits_next = 3;
  // ... and those screened within this factor of the last one kept, in
  // what each adds to the model's own step (screen.h dJ_model): the
  // screen is a linearization or a 6-iteration fit, so a near tie at the cut
  // is no ranking (blindgen mullins+delay_s13: the erf Mullins loss screened
  // 0.0690 against an offset's 0.0698, sixth, unfitted; fitted, it takes the
  // held-out error from 21.2% to 9.6%). Not chained, and no tie at a cut
  // of zero reduction.
  double joint_fit_tie = 0.9;
  // Stage 4: a word fitted jointly that adds less than 1/dominance of what
  // the round's leading word adds beyond the model's own step (screen.h:
  // dJ - dJ_model) gets a brief fit, at most dominated_max_iter iterations
  // and no restarts; its whole fit follows when the judged round leaves it
  // in the running: no word fitted in full is eligible, or it is within
  // dominated_reach times the best eligible word's trimmed held-out error
  // (dominated_fits.cpp; blindgen inertia_s59 at 1 kHz: 155 -> 87 s, the
  // same verdict). dominance 0: every word gets its whole fit.
  double dominance = 8.0;
  int dominated_max_iter = 10;
  double dominated_reach = 2.0;
  // Iteration budget of the baseline fit. Data with an effect the RT model
  // lacks can send it down a long valley towards a limit model (rigid cells
  // mimicking an inertia force: 1000 iterations, 170 s); the joint fits start
  // from the baseline and continue with the effect's term, and the basin
  // check refits the baseline when a candidate's RT part does better.
  int baseline_max_iter = 100;
  bool quiet = true;
  std::vector<std::string> only;  // restrict the candidates (empty = all)
  // What-if mode (`rtb diagnose --causes`): these words are fitted in this
  // order, one per round, and accepted whatever stage 5 says; its criteria
  // are still computed and reported. The first round screens every word as
  // the diagnosis does, so its basin check gives the same baseline; later
  // rounds look at the imposed word only. To measure what a word the data
  // do not select would give (VHB 4910: slack, docs/diagnosis_what_if.md).
  // Empty: the diagnosis chooses.
  std::vector<std::string> imposed;
};

// A model's eq. (27) errors: on the fit records, on the selection records
// (held out), and the latter trimmed (DiagnoseOptions::trim).
struct ModelErrors {
  double fit = 0.0, holdout = 0.0, holdout_trimmed = 0.0;
};

struct CandidateOutcome {
  Candidate cand;
  int round = 0;              // 0: screened at the baseline; k: with k causes found
  CandidateScreen screen;
  bool joint = false;         // fitted jointly (else screened out)
  ExtFitResult fit;
  double fit_seconds = 0.0;   // wall time of the joint fit
  double error_holdout = 0.0;
  double error_holdout_trimmed = 0.0;  // selection figure (see DiagnoseOptions::trim)
  double dbic = 0.0;          // BIC(current) - BIC(candidate), trimmed fit misfits
  double gain = 0.0;          // 1 - trimmed holdout error / current model's (selection)
  double amplitude_z = 0.0;   // |amplitude parameter| / its standard deviation
  // Parameters of current causes whose sizes vanish (z < min_z) in this
  // candidate's joint fit: the word replaces them, and select_cause counts
  // its parameters net of theirs.
  size_t displaces = 0;
  bool eligible = false;
  std::string why;            // reason when not eligible
  // Significant, worth its parameters, and refused only for its held-out
  // gain or a plausibility check against the current model: it may pay
  // together with a second cause (stage 5e, cause_pair.cpp).
  bool lead = false;
  // Where its joint fit started when not at the screen's start: "" or, from
  // stage 5e, "refitted alone from the <a> + <b> pair".
  std::string origin;
  // Fitted briefly, its screen dominated by the round's leader
  // (DiagnoseOptions::dominance); its figures are those of that brief fit.
  bool brief = false;
  ModelErrors errors() const { return {fit.error, error_holdout, error_holdout_trimmed}; }
};

// Stage 5's choice among a round's outcomes: the eligible candidate with the
// lowest trimmed held-out error or, within `parsimony` (a fraction) of it,
// the one with the fewest fitted parameters, net of the current causes its
// fit displaces (CandidateOutcome::displaces; ties: the lower error);
// nullptr when none is eligible. A degressive cubic spring is the small-x
// form of the softening spring (F tanh(x/d) = F x/d - F x^3/(3 d^3) + ...):
// when the softening spring takes at least half of the cubic's excess over
// the noise floor `scales.sel` (eq. (27), held out) and that excess is
// above a tenth of the floor, the specimen saturates and parsimony does not
// hand the word to the cubic (blindgen softening_s2: tanh law, cubic 3.88% and
// softening 3.59% against a floor of 3.49%; refgen's degressive cubics tie
// within 0.01 point). So too when the fitted spring saturates within the
// stroke (its width d at most the records' largest |x|, where the cubic
// form is off by 40%), is at least as good on the fit records, which hold
// the largest strokes, and within `parsimony` of the cubic held out
// (blindgen inertia+softening_s13: d = 1.97 mm within 2.73 mm, 4.28% /
// 8.48% against the cubic's 4.38% / 9.01%; inertia+softening_s54: d = 1.03
// mm within 1.15 mm, 4.584% / 4.922% against 4.601% / 4.875%; a softening spring
// fitted to refgen's degressive cubics, seeds 3-5, has d = 2.1-2.5 mm at
// strokes of 1.1-1.3 mm: the records show no saturation). Likewise a
// relaxation spectrum's fastest branches are a dashpot: when the spectrum
// is at least as good held out and takes half the dashpot's excess over the
// floor on the fit records (above a tenth of it), the records show the long
// memory and parsimony does not hand the word to the dashpot (blindgen relaxation_spectrum_s10: fit 2.31% against 2.77%,
// floor 2.23%; held out 2.95% against 3.12%; refgen viscous_s2's dashpot
// leaves 0.07 point on the fit records, under the tenth). Between one
// Maxwell branch and a spectrum within `parsimony` (two parameters each),
// the branch is named unless the spectrum is no worse on both the fit and
// the held-out records (blindgen maxwell+offset_s43, a 34 ms branch: 2.13%
// fit and 2.84% held out against the spectrum's 2.22% and 2.80%; on
// blindgen relaxation_spectrum seeds 8, 10, 41 and 43 the spectrum is lower
// on both).
struct SelectionScales {
  double sel = 0.0;     // the noise floor's eq. (27) error on the selection records
  double fit = 0.0;     // and on the fit records
  double stroke = 0.0;  // the records' largest |x| (DataScales::Xmax)
};
const CandidateOutcome *select_cause(const std::vector<CandidateOutcome> &round,
                                     double parsimony, const SelectionScales &scales);

// True when `name` is a word of the vocabulary (candidates.h).
bool is_candidate_name(const std::string &name);

// Stage 5's gain test. `gain`: the candidate's relative held-out gain
// (trimmed); current / candidate / floor: eq. (27) errors on the selection
// records of the current model, the candidate and the noise floor. Passes at
// min_gain, or near the floor when the candidate removes
// opt.min_excess_removed of the current error's excess over the floor with
// at least opt.min_gain_near_floor of gain.
double excess_removed(double current, double candidate, double floor);
bool gain_suffices(double gain, double current, double candidate, double floor, double min_gain,
                   const DiagnoseOptions &opt);

// Whether a cause pays: `with` against `without`, the model refitted
// without it. Held out by gain_suffices (held_out_pays); or, when the held-out records sit
// at their noise floor (within opt.holdout_at_floor) and so cannot judge,
// on the fit records (fit_records_decide): their excess over the fit floor
// is at least opt.min_fit_excess of that floor, the cause removes
// opt.min_excess_removed of it, and the held-out error does not grow.
bool fit_records_decide(const ModelErrors &without, const ModelErrors &with,
                        const SelectionScales &sc, const DiagnoseOptions &opt);
bool held_out_pays(const ModelErrors &without, const ModelErrors &with, const SelectionScales &sc,
                   double min_gain, const DiagnoseOptions &opt);
bool cause_pays(const ModelErrors &without, const ModelErrors &with, const SelectionScales &sc,
                double min_gain, const DiagnoseOptions &opt);

// One accepted cause, in the order found.
struct Cause {
  Candidate cand;
  std::string description;    // e.g. "backlash of 0.0312 (floating end)"
  std::vector<std::string> names;  // its fitted size(s) ...
  std::vector<double> value, stddev;  // ... with uncertainty (stddev NaN if unknown)
  double error_holdout = 0.0; // held-out eq. (27) error with this and the earlier causes
  double gain = 0.0;          // 1 - error_holdout / the previous model's
  double error_holdout_before = 0.0;  // the previous model's held-out error
  bool paired = false;        // one of the first two causes, accepted as a pair (stage 5e)
  // Accepted on the fit records: the held-out ones were at their noise
  // floor and could not judge (fit_records_decide).
  bool on_fit_records = false;
  double error_fit = 0.0, error_fit_before = 0.0;  // fit records' eq. (27), with and without it
};

// Per-record figures of a model.
struct RecordFigures {
  std::string file;
  bool holdout = false;
  double error = 0.0;         // eq. (27), a fraction
  double nrmse = 0.0;         // rms(F_model - F_measured) / (max F - min F), a fraction
};

// What the residual looks like when no candidate explains it.
struct ResidualSignature {
  double dominant_hz = 0.0;      // frequency of the residual's largest spectral line
  double dominant_share = 0.0;   // share of the residual's energy within +-10% of it
  double input_share = 0.0;      // share of the displacement's energy there, in the records
                                 // carrying the line (weighted by their part of it)
  double trend_share = 0.0;      // share explained by a + b t (slow drift of the force)
  double drift_share = 0.0;      // share explained by t F_model (a stiffness drift)
  double record_scale_share = 0.0;   // share explained by a scale and a t F_model drift
                                     // per record (records that disagree on the stiffness)
  double record_scale_spread = 0.0;  // largest minus smallest per-record scale (a fraction)
  std::string where;             // the loop quadrant or phase where it is largest
  std::string text;              // one sentence
};

struct DiagnoseResult {
  IdentifyResult baseline_fit;
  ExtModel baseline;
  double baseline_error_fit = 0.0, baseline_error_holdout = 0.0;
  double baseline_error_holdout_trimmed = 0.0;
  bool has_holdout = false;
  DisplacementDenoise denoise; // stage 0's decision
  std::vector<ClippedRecord> clipping;  // records whose force channel saturated
  std::vector<SpikedRecord> spikes;     // records with one-sample glitches
  NoiseFloor floor;            // of the baseline residual
  std::vector<RecordResiduals> residuals;
  std::vector<CandidateOutcome> candidates;  // every round's
  std::vector<Cause> causes;
  // Earlier causes a later one made redundant (stage 5d), with the held-out
  // error (eq. (27)) without and with them.
  struct Dropped {
    std::string name;
    double error_without = 0.0, error_with = 0.0;
  };
  std::vector<Dropped> dropped;
  // Causes withdrawn in stage 6: what they leave is a slow trend over time
  // (ResidualSignature trend or drift share above 0.3), which no
  // time-invariant word explains; they would only compensate it.
  std::vector<Cause> withdrawn;
  bool imposed = false;        // the causes were imposed (DiagnoseOptions::imposed)
  std::string cause = "none";  // causes[0]'s name, or "none" / "unexplained"
  bool residual_above_floor = false;  // after the causes found
  ResidualSignature signature;        // of the final residual (set when above the floor)
  ExtModel extended;           // = baseline when there is no cause
  ExtFitSpec extended_spec;    // its free parameters
  ExtFitResult extended_fit;   // its fit (sizes and uncertainty)
  double extended_error_fit = 0.0, extended_error_holdout = 0.0;
  // Held-out error trimmed of isolated spikes (DiagnoseOptions::trim), the
  // figure the selection uses; reported beside the plain one when they
  // disagree on the sign of the gain.
  double extended_error_holdout_trimmed = 0.0;
  std::vector<RecordFigures> extended_records;
  double gain = 0.0;
  std::string verdict;
  double wall_seconds = 0.0;
  // Where the wall time went: baseline identification (including a basin
  // refit), screening, joint fits (all rounds).
  double seconds_baseline = 0.0, seconds_screen = 0.0, seconds_joint = 0.0;
};

DiagnoseResult diagnose(const std::vector<Record> &fit, const std::vector<Record> &holdout,
                        const DiagnoseOptions &opt);

// eq. (27) error and NRMSE of model m on each record.
std::vector<RecordFigures> record_figures(const ExtModel &m, const std::vector<Record> &fit,
                                          const std::vector<Record> &holdout,
                                          const MisfitOptions &opt);

}  // namespace rtb

#endif
