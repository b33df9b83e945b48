// diagnose_stages.h -- private to the diagnosis pipeline: the state its
// stages share and the stage functions diagnose() (diagnose.cpp) calls in
// order. Not part of the offline tool's interface (rtb_offline.h,
// diagnose.h).
//   cause_round.cpp     stages 3-5a: screen, joint fits, judge one round
//   cause_revision.cpp  stages 5c-5d: refit an accepted cause, reject it if its
//                       gain was not its own, drop a stale one
//   cause_pair.cpp      stage 5e: two causes that pay only together
//   verdict_text.cpp    stage 6: the one-sentence verdict, per-record figures
#ifndef RTB_OFFLINE_DIAGNOSE_STAGES_H
#define RTB_OFFLINE_DIAGNOSE_STAGES_H

#include <chrono>
#include <string>
#include <vector>

#include "diagnose/diagnose.h"

namespace rtb {
namespace diag {

using Clock = std::chrono::steady_clock;
inline double since(Clock::time_point a) {
  return std::chrono::duration<double>(Clock::now() - a).count();
}

// The model the next round starts from: its parameters, free set, causes and
// figures (trimmed held-out error for selection, misfit for the BIC).
struct Current {
  ExtModel model;
  ExtFitSpec spec;
  std::vector<Candidate> causes;
  double error_fit = 0, error_holdout = 0, error_holdout_trimmed = 0;
  double J_trim = 0;  // trimmed fit misfit
  ModelErrors errors() const { return {error_fit, error_holdout, error_holdout_trimmed}; }
};

// The records of `a` followed by those of `b` (fit then held-out: the
// screening and selection records, issue #10 item 3).
inline std::vector<Record> concat(const std::vector<Record> &a, const std::vector<Record> &b) {
  std::vector<Record> all = a;
  all.insert(all.end(), b.begin(), b.end());
  return all;
}

// The held-out gain a word must bring in a round: min_gain in the first,
// min_gain_next in later ones.
inline double round_min_gain(const DiagnoseOptions &opt, int round) {
  return round == 0 ? opt.min_gain : opt.min_gain_next;
}

// What every stage reads: the records, the selection figure's set-up, the
// options, the data's scales and the noise floor once stage 2 has run.
struct Context {
  const std::vector<Record> &fit, &holdout, all;
  const std::vector<Record> &sel;  // records of the selection figure
  MisfitOptions sel_opt;
  const DiagnoseOptions &opt;
  DataScales sc;
  std::vector<double> sigma;  // noise level per record of `all`
  double floor_sel = 0.0;     // the noise floor's eq. (27) error on `sel`
  double floor_fit = 0.0;     // and on `fit`
  SelectionScales selection_scales() const { return {floor_sel, floor_fit, sc.Xmax}; }
  bool clipped = false;       // stage 0 found a saturated force channel
  std::vector<std::vector<double>> recorded_x = {};  // `all`'s displacement before stage 0's filter
};

// The figures of model m with `causes` (free set `spec`) on the context.
Current make_current(const ExtModel &m, const ExtFitSpec &spec, const std::vector<Candidate> &causes,
                     const Context &cx);

// Stage 4's choice: the indices of the outcomes to fit jointly, the
// `how_many` with the largest screened misfit reduction among those with
// screen z >= min_z, and any screened within a factor `tie` of the last of
// them (a near tie); `viscous` too when one of them is a lead of the force
// (its first-order twin, against which the lead is judged: blindgen
// viscous+cubic_stiffness_s9, where the lead's screen ranked the dashpot out
// and a 3.2 ms lead was named for it), and the what-if's `imposed` word.
std::vector<size_t> joint_fit_order(const std::vector<CandidateOutcome> &out, double min_z,
                                    int how_many, double tie, const std::string &imposed);

// The words fitted past the screen's cut (fit_past_the_cut): the significant
// ones screened out, at most how_many, by the significance of their size (z),
// not by misfit reduction. That order has already put them below the cut, and
// a short fit's reduction clamps at 0 when its 6 iterations from a baseline in
// another basin do not descend (blindgen mullins_s56, the baseline a friction
// chain at alpha 0.001: the erf Mullins loss screened at z = 190 and no
// reduction, fourth past the cut behind three linearized words at 0.06-0.18;
// fitted, it takes the held-out error from 10.4% to 2.5% at a 2.3% floor).
std::vector<size_t> past_the_cut_order(const std::vector<CandidateOutcome> &out, double min_z,
                                       int how_many);

// Stage 5a again, on a fit that replaced the one judged: the verdict and its
// reason are recomputed from nothing.
void judge_anew(CandidateOutcome &co, const Current &cur, const Context &cx, double min_gain);

// Stage 4 for one word: its joint fit with the current causes from the
// screen's start, its other definition and the restarts of its basin; only
// the first fit, with DiagnoseOptions::dominated_max_iter, when co.brief.
void fit_word(CandidateOutcome &co, const Current &cur, const Context &cx);

// Stage 4's brief fits (dominated_fits.cpp): marks co.brief on the words
// `fitted` (indices into `out`) that add less than 1/dominance of what the
// leader among them adds beyond the model's own step (screen.h: dJ -
// dJ_model), with the report's note for a fit of max_iter iterations; never
// a word screened by a short fit, whose screen can underrate it. Not called
// in a what-if round or past the screen's cut. dominance <= 0: none.
void mark_dominated(std::vector<CandidateOutcome> &out, const std::vector<size_t> &fitted,
                    double dominance, int max_iter);
// After stage 5a, the brief words the judged round leaves in the running:
// all of them when no word fitted in full is eligible; else those fitted
// that are eligible or within `reach` times the best eligible word's trimmed
// held-out error.
std::vector<size_t> brief_fits_to_complete(const std::vector<CandidateOutcome> &out, double reach);
// Their whole fits (fit_word), each judged anew.
void complete_dominated_fits(std::vector<CandidateOutcome> &out, const Current &cur,
                             const Context &cx, double min_gain);

// Stages 3-5a at the current model: the outcomes of every remaining
// candidate of the vocabulary (screened, the best fitted jointly, judged).
// Adds the screening and joint-fit wall time to R.
std::vector<CandidateOutcome> one_round(const Current &cur, const Context &cx, int round,
                                        DiagnoseResult &R);

// Basin check of the first round: a candidate whose own term is
// insignificant but whose fit is below 0.9x base_error; nullptr if none.
const CandidateOutcome *better_basin(const std::vector<CandidateOutcome> &out, double base_error,
                                     double min_z);

// The round's joint fits judged again against a changed current model.
void rejudge(std::vector<CandidateOutcome> &out, const Current &cur, const Context &cx, int round);

// What-if mode: the imposed word's best joint fit, eligible or not.
const CandidateOutcome *imposed_cause(const std::vector<CandidateOutcome> &round,
                                      const std::string &name);

// `m` with its five RT parameters from the STS start of the records its
// chain sees (artefacts and the elastic extensions' static force removed,
// chain_records; K0 less their tangent at rest); extension sizes and
// settings kept.
ExtModel sts_core_start(const ExtModel &m, const Context &cx);

// Stage 5c: refit the accepted cause's model from the STS start; true when
// the refit replaced `fit`.
bool refit_from_sts(const Current &cur, const Context &cx, ExtFitResult &fit);

// Stage 5c: whether the accepted cause `c` needs the check below: a Maxwell
// branch after the relaxation spectrum (it may be the spectrum's missing end).
bool extends_spectrum(const Candidate &c, const Current &before);
// Stage 5c: after a refit that replaced the fit, or when extends_spectrum,
// is `c` still worth its threshold against the model without it (`before`'s
// causes, the spectrum widened to the branch) refitted from the current one?
// If not, cur becomes that model; true.
bool not_a_cause(Current &cur, const Current &before, const Candidate &c, const Context &cx,
                 DiagnoseResult &R);
// Stage 5c: does a later cause `c` also pay against `before`'s causes
// refitted at another cell count? If not, cur becomes the best such model;
// true.
bool other_cells_explain(Current &cur, const Current &before, const Candidate &c,
                         const Context &cx, DiagnoseResult &R);
// Stage 5d: drop an earlier cause that no longer pays; its index, or -1.
int drop_redundant(Current &cur, const Context &cx, DiagnoseResult &R);
// Stage 5d: drop a cause whose size the revisions after its acceptance took
// to nothing (z < min_z in the current fit) and that no longer pays; its
// index, or -1.
int drop_vanished(Current &cur, const Context &cx, DiagnoseResult &R);
// Stage 5f: a better basin of the current model, from a later round's
// insignificant candidate that fits below 0.9x the current model (refitted
// from there, adopted when lower) or else from two restarts along the
// current model's least determined direction (adopted when 1% lower;
// cause_revision.cpp). True when cur changed.
bool repair_basin(Current &cur, const std::vector<CandidateOutcome> &round, const Context &cx,
                  DiagnoseResult &R);
// Stage 5d: a refinement whose relaxation is no longer a cause is dropped
// (cause_revision.cpp). Returns the index dropped, or -1.
int drop_orphaned(Current &cur, const Context &cx, DiagnoseResult &R);
// Size of cause c's effect (its first parameter, or the delay / offset) in
// fit f over its standard deviation: the Wald z. NaN when the fit has no
// finite standard deviation for it (a size at a clamp, a singular
// covariance); infinite for a switch (slack).
double amplitude_z(const Candidate &c, const ExtFitResult &f);
// The parameters of `causes` whose sizes fit f takes to nothing (z <
// min_z; a NaN z does not count, nor a configured word): a later word whose
// joint fit does this replaces them (CandidateOutcome::displaces).
size_t displaced_parameters(const std::vector<Candidate> &causes, const ExtFitResult &f,
                            double min_z);
// Stage 5d: a relaxation spectrum refitted onto its fastest branch becomes
// that branch's word (`viscous` or `maxwell`); the index replaced, or -1.
int spectrum_to_one_branch(Current &cur, const Context &cx, DiagnoseResult &R);
// Stage 5d: a degressive cubic accepted before a later cause, refitted as a
// softening spring with the later causes, is replaced by it when the spring
// saturates within the stroke and is no worse; the index replaced, or -1.
int cubic_to_softening(Current &cur, const Context &cx, DiagnoseResult &R);
// The share of a relaxation spectrum's stiffness on its fastest branch.
double fastest_branch_share(const rtb_params &p);
// Whether fit b of one definition of a word is preferred to fit a of the
// other: the held-out records decide when one gains min_gain on the other
// there, the fit misfit J otherwise.
bool definition_preferred(const ExtFitResult &b, const ExtFitResult &a, const Context &cx);
// Cause i of `causes`, fitted as `fit`, refitted in its other definition
// (other_definition, candidates.h) with the rest; true, and causes[i] and
// fit replaced, when the records prefer it (definition_preferred).
bool prefer_other_definition(std::vector<Candidate> &causes, size_t i, const Context &cx,
                             ExtFitResult &fit);
// Stage 5d: each earlier cause's other definition, refitted with the later
// ones; the records' choice replaces it in cur and R.
void revisit_definitions(Current &cur, const Context &cx, DiagnoseResult &R);
// A cause switched off in m: its sizes zeroed, its settings the plain element's.
void switch_off(const Candidate &c, ExtModel &m);
// Cause c's sizes and settings copied from `from` into `to`.
void copy_cause(const Candidate &c, const ExtModel &from, ExtModel &to);

// Stage 5e: no single word paid in the first round (`first`); try the
// leads with a second word. True when a pair paid: cur becomes the pair's
// model, both causes are in R.causes and the trial round in R.candidates.
// Else single->eligible tells whether a member of a refused pair, refitted
// alone from it, is a first cause (*single: its outcome, judged against the
// baseline), for the caller to accept.
bool pair_of_causes(Current &cur, const std::vector<CandidateOutcome> &first, const Context &cx,
                    DiagnoseResult &R, CandidateOutcome *single);

// The report entry of an accepted cause (sizes, gain over `before`).
Cause make_cause(const CandidateOutcome &co, const Current &before);
// Every cause's description and sizes taken from the final fit (R.extended_fit).
void final_sizes(DiagnoseResult &R);

// Stage 6: the verdict sentence of a finished result.
std::string verdict_text(const DiagnoseResult &R);

// Stage 6: the signature of a residual above the floor (residual_signature.cpp).
ResidualSignature residual_signature(const ExtModel &m, const std::vector<Record> &recs,
                                     const std::vector<RecordResiduals> &where,
                                     const MisfitOptions &opt);

}  // namespace diag
}  // namespace rtb

#endif
