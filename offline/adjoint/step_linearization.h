// step_linearization.h -- tangent (JVP) and adjoint (VJP) of ONE discrete
// step of the real-time stepper, from the implicit-function theorem at each
// converged stage (discretize-then-differentiate).
//
// A stage solves  G(Y) = Y - c - h phi(b1 e1 - K Y) = 0  (rtb_internal.h), so
//   A dY = dc + h D e1 db1 - h D (dK Y) + h phi_p dp,   A = I + h D K,
// with D = diag(phi'(f)). phi' is finite everywhere (0 at f = 0): no
// smoothing is needed, unlike the continuous adjoint of eq. (12).
//
// A step = chain advance (the stages) followed by the force map (eq. (11)
// plus extensions). They are linearized separately so that the trajectory
// code can inject state sources between them (dot-product test, eq. (15)).
#ifndef RTB_OFFLINE_STEP_LINEARIZATION_H
#define RTB_OFFLINE_STEP_LINEARIZATION_H

#include "model/forward.h"
#include "rtb_offline.h"

namespace rtb {

// Tangent or cotangent of the memory the element carries between steps.
struct StateDual {
  double y[RTB_MAX_CELLS];  // cell DOFs
  double z;                 // Maxwell branch displacement
  void clear();
};

// Chain + Maxwell state: d_new = M d_old + (d/dp) dp.
void chain_jvp(const StepView &v, const StateDual &d_old, const double *dp, StateDual &d_new);
// Transpose: accumulates into bar_old (which is NOT cleared) and pbar.
void chain_vjp(const StepView &v, const StateDual &bar_new, StateDual &bar_old, double *pbar);

// Force of the step from the new state: dF = dF/dstate d_new + dF/dp dp.
double force_jvp(const StepView &v, const StateDual &d_new, const double *dp);
// Transpose: bar_new += Fbar dF/dstate, pbar += Fbar dF/dp.
void force_vjp(const StepView &v, double Fbar, StateDual &bar_new, double *pbar);

}  // namespace rtb

#endif
