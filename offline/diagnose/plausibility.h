// plausibility.h -- a cause the records themselves contradict is not named.
//
// A fitted measurement artefact or switch can lower the misfit for the wrong
// reason (an offset that trades against a relaxation the model lacks, a
// "delay" that mimics damping). Each is checked against a feature of the
// data that does not depend on the model's fit:
// * offset: where a record is at rest at x ~ 0 before it moves, the measured
//   force is the sensor's zero; the fitted offset must agree with it.
// * delay: the measured force must lag the current model's prediction by
//   about the fitted delay (the least-squares shift over all records, each
//   counting by its information on a shift), and the residual must be shaped
//   like a shift (the cross-correlation's peak near that shift). Not a lead
//   (the displacement channel lagging): RT's dashpots imitate one.
// * slack: where the fitted model floats free (zero force), the measured
//   force must be near zero too, on a visible share of the samples.
// * softening: the fitted static elastic law must soften (its tangent drop by
//   5% or more) somewhere over the measured displacements.
#ifndef RTB_OFFLINE_PLAUSIBILITY_H
#define RTB_OFFLINE_PLAUSIBILITY_H

#include <string>
#include <vector>

#include "diagnose/candidates.h"

namespace rtb {

// "" unless the records exclude candidate c before any fit, e.g. slack on a
// specimen whose measured force is clearly negative somewhere (it pushes:
// below 5% of the peak and 6 noise sigmas).
std::string excluded_by_data(const Candidate &c, const std::vector<Record> &recs);

// "" when the data do not contradict candidate c as fitted (model `fitted`,
// fitted on top of `current`); else why. sigma: the records' noise levels
// (noise_floor.h), in the order fit then holdout.
std::string contradiction(const Candidate &c, const ExtModel &fitted, const ExtModel &current,
                          const std::vector<Record> &recs, const std::vector<double> &sigma,
                          const MisfitOptions &opt);

// Lag [time] at which the measured force best matches the prediction F
// (positive: the measurement lags), by the cross-correlation peak with
// parabolic refinement, searched within +-max_lag samples.
double xcorr_lag(const Record &rec, const Eigen::VectorXd &F, int max_lag);

}  // namespace rtb

#endif
