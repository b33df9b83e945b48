// forward.h -- the forward model over a record: the real-time stepper run on
// the record's own (possibly non-uniform) time grid, with the stage data kept
// for the adjoint sweep.
#ifndef RTB_OFFLINE_FORWARD_H
#define RTB_OFFLINE_FORWARD_H

#include <vector>

#include "rt_bushing/src/rtb_internal.h"
#include "rtb_offline.h"

namespace rtb {

// Input history actually driven through the stepper: an optional ramp from
// rest to x[0] and an optional hold there (neither part of the misfit),
// followed by the record's samples.
struct DriveGrid {
  std::vector<double> x;     // displacement at every step end
  std::vector<double> dt;    // step lengths (dt[0] unused: initial state)
  int first_sample = 0;      // index in x of the record's sample 0
  bool held = false;         // x[0] was held before the record (StartMode::hold)
};
// Whether `opt` holds x[0] before this record (StartMode::automatic resolved).
bool holds_start(const Record &rec, const SimOptions &opt);
DriveGrid make_drive_grid(const Record &rec, const SimOptions &opt);

// One implicit stage as the linearization sees it (views into Trajectory).
// Dashpot partials of one converged stage (step_linearization.cpp fills it):
// the same for every tangent direction, so a Jacobian sweep computes them
// once per step instead of once per column.
struct StageLin {
  double D[RTB_MAX_CELLS];       // dv/df
  double dv_dC0[RTB_MAX_CELLS];  // dv/dC0 at fixed f
  double dv_dalpha[RTB_MAX_CELLS];
  double dv_dfa[RTB_MAX_CELLS];  // dv/dfric_asym at fixed f
  // The stage's tangent matrix A = I + h D K, Thomas-factored once for all
  // columns (rtb_tridiag_factor): sub-diagonal, pivots, eliminated
  // super-diagonal. Filled by step_precompute (the tangent's), not by the
  // adjoint, which solves with A^T.
  double lo[RTB_MAX_CELLS], piv[RTB_MAX_CELLS], w[RTB_MAX_CELLS];
};

struct StageView {
  double h;
  const double *f, *v, *y;  // converged dashpot forces, velocities, stage DOFs
  const StageLin *lin = nullptr;  // precomputed partials, or nullptr
};

// One step as the linearization sees it: the memory before and after, and
// the stages between.
struct StepView {
  const rtb_params *p;
  double dt;
  double xb_old, xb_new;      // bushing displacements
  double ax_new;              // input acceleration estimate (inertia)
  double z_old, z_new;        // Maxwell branch
  const double *zs_old, *zs_new;  // relaxation-spectrum branches (M each)
  double xbmax_old;           // Mullins memory before the step
  double x_new;               // input displacement
  int contact;                // rtb_state.contact: +1 / -1 in contact at x -/+ g/2,
                              // 0 floating free, 3 held, 2 no clearance (xb = x)
  const double *y_new;        // cell DOFs after the step
  StageView st[2];
};

// Everything the adjoint needs from one forward run, stored compactly: per
// step 5 scalars + spectrum memories + y + per stage (h, f, v, y).
struct Trajectory {
  std::vector<double> force;           // model force at each drive step
  int n_stages = 1, cells = 0, branches = 0;
  int first_sample = 0;
  long newton_iterations = 0;
  int not_converged = 0;               // steps reporting RTB_NOT_CONVERGED
  std::vector<double> data;            // empty without trace
  size_t stride() const { return 5 + branches + cells + n_stages * (1 + 3 * (size_t)cells); }
  StepView step(const rtb_params &p, const DriveGrid &g, size_t i) const;
};

// Run the stepper over the drive grid. keep_trace=false stores forces only.
// Settings are the library's defaults (rtb_settings_default: what runs in a
// controller that passes NULL), with the Newton tolerance replaced by `tol`
// when tol > 0. Throws std::runtime_error (with the step index) on a stepper
// error.
Trajectory run_forward(const rtb_params &p, const DriveGrid &grid, bool keep_trace,
                       double tol = 0.0);

}  // namespace rtb

#endif
