// candidates.h -- the vocabulary of causes `rtb diagnose` can name, each as
// the extra freedom it adds to the RT model and where its fit starts.
#ifndef RTB_OFFLINE_CANDIDATES_H
#define RTB_OFFLINE_CANDIDATES_H

#include <string>
#include <vector>

#include "diagnose/extended_fit.h"

namespace rtb {

// Typical magnitudes of the records, for starting values and scales.
struct DataScales {
  double Fmax = 1, Xmax = 1, Vmax = 1, Amax = 1, Ksec = 1;
  double dt = 1e-3, duration = 1;
  // The longest record the model is run on, fit or held out [time]: the
  // relaxation spectrum's slowest branch (set_spectrum_range). = duration
  // from data_scales; the diagnosis widens it to its held-out records.
  double memory = 1;
};
DataScales data_scales(const std::vector<Record> &recs);

// How stage 3 (screen.cpp) looks at a candidate before the joint fits.
enum class ScreenMethod {
  score,       // linear in its amplitude extra[0]: the score test
  shape_scan,  // amplitude linear, a shape scanned on grids (ShapePass)
  short_fit,   // a short joint fit: not differentiable at zero size (a
               // clearance), a switch (slack), or a linearization at zero
               // that misleads (Mullins)
};

// A model setting with a grid value g, on the data's scales.
using ShapeSetter = void (*)(rtb_params &p, const DataScales &s, double g);
// Model settings a word needs (flags, a branch time range).
using Configure = void (*)(rtb_params &p, const DataScales &s);

// One pass of a shape scan: the amplitude is linear at every grid value.
// A pass keeps the shape the passes before it chose, or `fallback` for a
// pass that found no admissible amplitude.
struct ShapePass {
  ShapeSetter set;
  std::vector<double> grid;
  double fallback;
};

struct Candidate {
  std::string name;           // vocabulary word
  bool physical = true;       // false: measurement-chain artefact (not in rt_bushing)
  std::vector<ParamId> extra; // extension parameters it frees
  bool delay = false, offset = false;
  std::string variant;        // a second definition of the same word ("held")
  Configure configure = nullptr;  // or nullptr
  ScreenMethod screen = ScreenMethod::score;
  std::vector<ShapePass> passes;  // shape_scan
  // short_fit: one screen job per start (start_at puts it into the model),
  // or a single job from the configured model when there is none.
  ShapeSetter start_at = nullptr;
  std::vector<double> starts;
};

// The relaxation spectrum's branch range: from tau_min [time] to the longest
// record (DataScales::memory), at most RTB_MAX_BRANCHES branches two per
// decade.
void set_spectrum_range(rtb_params &p, const DataScales &s, double tau_min);

// cubic_stiffness, asymmetry, maxwell, viscous, backlash (floating and held
// end), mullins, delay, inertia, offset, softening, slack,
// relaxation_spectrum, friction_asymmetry, stretch_relaxation ("none" is the
// absence of all of them, "unexplained" a residual above the noise floor none
// of them removes).
const std::vector<Candidate> &candidate_vocabulary();

// Why candidate c cannot come yet, given the causes so far ("" if it can):
// stretch_relaxation refines a maxwell branch or a relaxation_spectrum.
std::string needs_other_cause(const Candidate &c, const std::vector<Candidate> &causes);

// Two candidates that cannot be in one model (slack floats free; a held
// clearance holds), or are the same word.
bool candidates_conflict(const Candidate &a, const Candidate &b);

// Fit specification of the joint fit: free = core + the extras of every
// candidate in `cs` (a model with several causes).
ExtFitSpec candidate_spec(const Candidate &c, const DataScales &s);
ExtFitSpec combined_spec(const std::vector<Candidate> &cs, const DataScales &s);

// The word's other definition, when it has one the screen cannot tell apart
// (both look alike at zero size): the joint fit tries both and keeps the one
// the records prefer (cause_round.cpp).
// * delay: a pure lag of the force channel, or its first-order low-pass (an
//   amplifier's bandwidth); same parameter, ExtModel::delay_lowpass toggled.
//   A lead of the force (the displacement channel lags; the screen's sign
//   says which) has no other definition.
// * asymmetry: k_asym |xb| (tension and compression stiffness differ: a kink
//   at 0), or k2 xb^2 (a quadratic term: the tangent changes linearly with
//   xb); the alternative is started where it matches the first's force
//   k_asym |x| at the stroke's two thirds.
// * mullins: the softening of K0 alone, or of the whole RT force (every
//   stiffness and dashpot alike, rtb_params.mullins_whole: a damage that
//   scales the material's stress); the alternative starts with the same
//   loss of static force. Ogden-Roxburgh's erf shape (mullins_width) is its
//   own vocabulary entry (variant "erf", two sizes) without another one.
// Returns false when c has no other definition; else *alt (variant set) and
// *alt_start (from `start`, the screen's start for c).
bool other_definition(const Candidate &c, const ExtModel &start, const DataScales &s,
                      Candidate *alt, ExtModel *alt_start);

// The word with its definition, as tables show it: "mullins (erf)".
std::string display_name(const Candidate &c);

// One line describing the fitted effect, e.g. "backlash of 0.0312".
std::string describe_effect(const Candidate &c, const ExtModel &m);

// A default positive start for an extension parameter that must be positive
// (its optimizer coordinate is a log): a small effect on the data's scales.
// 0 for signed parameters, which start at 0.
double extra_start_value(ParamId id, const DataScales &s);

}  // namespace rtb

#endif
