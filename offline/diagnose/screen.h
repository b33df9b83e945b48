// screen.h -- stage 3 of the diagnosis: a cheap first look at every
// candidate at the current model (the plain RT baseline, or the model with
// the causes found so far), before the expensive joint fits.
//
// For an effect linear in its amplitude the screen is a score test: the
// linearized least squares in the current model's free parameters and the
// candidate's amplitude together, from the exact sensitivities (so the part
// of the effect the current fit has already absorbed is re-optimized, not
// counted against the candidate). Effects with a shape parameter (Maxwell
// tau, softening width, spectrum exponent) scan it on a grid; a clearance
// (not differentiable at g = 0) gets a short joint fit from two gaps; slack
// (a switch) gets a short fit with the switch on, and Mullins softening a
// short fit from a finite size (its linearization at 0 misleads). Each word
// of the vocabulary carries its method, grids and starts (candidates.cpp),
// so a new word is one row there, not a branch here.
#ifndef RTB_OFFLINE_SCREEN_H
#define RTB_OFFLINE_SCREEN_H

#include <vector>

#include "diagnose/candidates.h"

namespace rtb {

struct CandidateScreen {
  double value = 0.0;         // best effect size with the model held
  double z = 0.0;             // its significance
  double dJ = 0.0;            // misfit reduction it brings (relative to the model's J)
  double dJ_model = 0.0;      // ... that the model's own parameters bring alone (the same
                              // for every candidate of a screen): dJ's common part
  bool plausible = true;      // sign admissible (e.g. damping >= 0)
  ExtModel start;             // start point of the joint fit
  double seconds = 0.0;       // wall time of the screen
};

// Screen every candidate at model m (free parameters: spec.free, spec's delay
// and offset) on the records `recs`, `threads` jobs at a time.
std::vector<CandidateScreen> screen_candidates(const std::vector<Candidate> &cands,
                                               const ExtModel &m, const ExtFitSpec &spec,
                                               const std::vector<Record> &recs,
                                               const MisfitOptions &opt, const DataScales &sc,
                                               int threads);

}  // namespace rtb

#endif
