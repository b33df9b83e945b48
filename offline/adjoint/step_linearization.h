// step_linearization.h -- tangent (JVP) and adjoint (VJP) of ONE discrete
// step of the real-time stepper, from the implicit-function theorem at each
// converged stage (discretize-then-differentiate).
//
// A stage solves  G(Y) = Y - c - h phi(b1 e1 - K Y) = 0  (rtb_internal.h), so
//   A dY = dc + h D e1 db1 - h D (dK Y) + h phi_p dp,   A = I + h D K,
// with D = diag(phi'(f)). phi' is finite everywhere (0 at f = 0): no
// smoothing is needed, unlike the continuous adjoint of eq. (12).
//
// A step is the composition
//   xb_new = B(state_old, p)            clearance/slack: x -+ g/2 in contact,
//                                       the root of F_bushing(xb) = 0 when
//                                       floating, xb_old when held
//   state_new = C(state_old, p, xb_new) stages, Maxwell branch, Mullins memory
//   F = Fo(state_old, state_new, p)     eq. (11) + extensions + inertia
// and both functions below linearize all of it. The force law, the branch
// updates and the dashpot law are the stepper's own inline functions
// (rt_bushing/src/bushing_force.h, dashpot_law.h): one definition of the
// physics for the forward model and its adjoint.
#ifndef RTB_OFFLINE_STEP_LINEARIZATION_H
#define RTB_OFFLINE_STEP_LINEARIZATION_H

#include <array>
#include <vector>

#include "model/forward.h"
#include "rtb_offline.h"

namespace rtb {

// Tangent or cotangent of the memory the element carries between steps.
struct StateDual {
  double y[RTB_MAX_CELLS];  // cell DOFs
  double z;                 // Maxwell branch displacement
  double zs[RTB_MAX_BRANCHES];  // relaxation-spectrum branch displacements
  double xb;                // bushing displacement (moves only with a clearance)
  double m;                 // Mullins memory max |xb|
  void clear();
  // The entries a model of `cells` cells and `branches` spectrum branches
  // uses, copied from o; the capacity beyond is left as it is.
  void assign_used(const StateDual &o, int cells, int branches);
};

// Fill lin[s] with stage s's dashpot partials and point v.st[s].lin at it:
// step_jvp and step_jvp_columns then reuse them, with the stage matrices
// Thomas-factored, for every parameter direction (a Jacobian).
void step_precompute(StepView &v, StageLin lin[2]);

// d_new and the returned dF from d_old and the parameter direction dp.
double step_jvp(const StepView &v, const StateDual &d_old, const double *dp, StateDual &d_new);
// Every column of a Jacobian over one step: d[c] advanced in place and dF[c]
// from the direction dp[c], the step's branch and force partials computed
// once for all columns and the stages' substitutions run for all columns
// together, their chains of divisions overlapping (the same bits as
// step_jvp column by column).
void step_jvp_columns(const StepView &v, std::vector<StateDual> &d,
                      const std::vector<std::array<double, P_COUNT>> &dp, double *dF);
// Transpose: given the cotangents of the new state and of F, accumulate into
// bar_old (not cleared) and pbar.
void step_vjp(const StepView &v, const StateDual &bar_new, double Fbar, StateDual &bar_old,
              double *pbar);

}  // namespace rtb

#endif
