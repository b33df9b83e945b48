// ext_model_helpers.h -- shared by the diagnosis' unit tests: the paper's RT
// parameters as an extended model, its predicted force through the force
// channel (predict_extended), records "measured" through a known truth, and
// a vocabulary word by name, and a word's joint fit.
#ifndef RTB_TESTS_EXT_MODEL_HELPERS_H
#define RTB_TESTS_EXT_MODEL_HELPERS_H

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "offline/diagnose/candidates.h"
#include "offline/diagnose/extended_fit.h"

namespace rtb_test {

inline rtb::ExtModel paper_model() {
  rtb::ExtModel m;
  rtb_params_default(&m.p, RTB_MODEL_RT);
  return m;
}

// No parameter free: the prediction alone (and a delay/offset column if the
// caller sets fit_delay / fit_offset).
inline rtb::ExtFitSpec nothing_free() {
  rtb::ExtFitSpec s;
  s.free.clear();
  return s;
}

inline Eigen::VectorXd predicted(const rtb::ExtModel &m, const rtb::Record &r,
                                 const rtb::ExtFitSpec &spec = nothing_free(),
                                 Eigen::MatrixXd *jac = nullptr) {
  Eigen::VectorXd F;
  rtb::predict_extended(m, r, rtb::SimOptions(), spec, F, jac);
  return F;
}

// Replaces each record's force by `truth`'s prediction (noise-free).
inline void measure_through(const rtb::ExtModel &truth, std::vector<rtb::Record> &recs) {
  for (rtb::Record &r : recs) {
    const Eigen::VectorXd F = predicted(truth, r);
    for (size_t j = 0; j < r.F.size(); ++j) r.F[j] = F[(Eigen::Index)j];
  }
}

inline const rtb::Candidate &vocabulary_word(const std::string &name) {
  for (const rtb::Candidate &c : rtb::candidate_vocabulary())
    if (c.name == name) return c;
  ADD_FAILURE() << "no candidate " << name;
  return rtb::candidate_vocabulary().front();
}

// A word's joint fit from `start`, as the diagnosis runs it (stage 4): the
// core and the word's parameters free.
inline rtb::ExtFitResult fit_word(const rtb::Candidate &c, const rtb::ExtModel &start,
                                  const std::vector<rtb::Record> &recs) {
  return rtb::fit_extended(recs, start, rtb::combined_spec({c}, rtb::data_scales(recs)),
                           rtb::MisfitOptions());
}

}  // namespace rtb_test

#endif
