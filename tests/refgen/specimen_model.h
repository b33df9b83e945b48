// specimen_model.h -- internal to refgen: the specimen's constitutive laws
// (specimen_model.cpp) and its fine-step integrator (radau_stepper.cpp).
#ifndef RTB_TESTS_REFGEN_SPECIMEN_MODEL_H
#define RTB_TESTS_REFGEN_SPECIMEN_MODEL_H

#include <vector>

#include "refgen.h"

namespace refgen {

// The actuator at one instant (servo output).
struct Drive {
  double t = 0.0, x = 0.0, v = 0.0, a = 0.0;  // [s], [mm], [mm/s], [mm/s^2]
};

// Where the specimen end is, given the actuator and cell 1.
struct EndPosition {
  double xb = 0.0;       // [mm]
  double dxb_dy1 = 0.0;  // nonzero only while the end floats (floating gap, slack)
  bool contact = true;   // the end moves with the actuator
};

// Everything the specimen remembers between fine steps.
struct SpecimenState {
  std::vector<double> y;       // cell DOFs of eq. (2) [mm]
  std::vector<double> v;       // their velocities at the end of the last step (predictor)
  std::vector<double> q;       // Maxwell branch dashpot positions [mm]
  double xb = 0.0;             // specimen end position [mm]
  double xb_max = 0.0;         // prior maximum |xb| (Mullins memory)
  bool contact = true;
};

SpecimenState rest_state(const Specimen &s);

// The specimen held at actuator position x for ever (a preload): every
// dashpot and Maxwell branch relaxed, the end in contact on the side it was
// pushed from (x minus the half gap towards 0).
SpecimenState relaxed_state(const Specimen &s, double x);

// Stiffness multiplier at time t (thermal drift): 1 + drift_rate t.
double stiffness_scale(const Specimen &s, double t);

// Inverse dashpot law of eq. (1): the cell velocity that carries dashpot
// force f, phi(f) = sign(f) (|f| / C)^(1/alpha), C = C0 for f >= 0 and
// C0 c0_neg_ratio for f < 0. Writes dphi/df (0 at f = 0 since alpha < 1).
double dashpot_velocity(const Specimen &s, double f, double *dphi_df);

// Rate-independent force of the specimen at end position xb: K0 and Kpa of
// eq. (11) plus the elastic effects. Writes dF/dxb.
double elastic_force(const Specimen &s, double scale, double xb, double y1, double xb_max,
                     double *dF_dxb);

// End position for actuator x. xb_prev is the end position at the start of
// the step (held clearance); xb_max the Mullins memory.
EndPosition end_position(const Specimen &s, double scale, double x, double y1, double xb_prev,
                         double xb_max);

// Cell velocities y' = phi(b - K y) of eq. (2), b = Kpa xb e1, and their
// tridiagonal Jacobian d y'/d y (sub[k] = d/dy_{k-1}, sup[k] = d/dy_{k+1}).
struct CellRates {
  std::vector<double> v, sub, diag, sup;
  EndPosition end;
};
void cell_rates(const Specimen &s, double t, double x, double xb_prev, double xb_max,
                const double *y, CellRates &out);

// Force the load cell sees after a committed step (inertia of the fixture on
// the actuator side included).
double specimen_force(const Specimen &s, const SpecimenState &st, const Drive &d);

// One fine step t -> t + h of 2-stage Radau IIA (c = 1/3, 1) with full Newton
// on the stage increments; d[0], d[1] are the drive at t + h/3 and t + h.
// Returns false (state untouched) when Newton does not converge.
bool radau_step(const Specimen &s, SpecimenState &st, double t, double h, const Drive d[2]);

}  // namespace refgen

#endif
