// periodic_drive.h -- the dynamic-stiffness test of the element: drive
// x = A sin(2 pi f t) from rest (the element at rest at x = 0) for C whole
// periods of M steps each, and take the first harmonics X1, F1 of the last
// period (harmonic.h). The stepper is the real-time one (model/forward.h), so
// the figures are those of the discrete model a controller runs.
//
// Convergence (the accuracy targets are 0.1% in |K*| and 0.05 deg in the loss
// angle; every check asks for a tenth of that):
//  * periodicity, at fixed M: the harmonic of every period of one run is
//    taken; the run is long enough when the last period-to-period change d_C
//    plus its geometric tail d_C r/(1 - r), r = d_C / d_{C-1}, is below a
//    tenth of the tolerance (a change below 1e-6 of the tolerance is rounding
//    and passes). Otherwise C doubles (4 .. max_cycles).
//  * steps per cycle: M doubles from min_steps until the results at M and 2M
//    (each periodic) differ by less than a tenth of the tolerance; the 2M
//    result is reported. SDIRK2 is second order, so its remaining error is
//    about a third of that last change.
#ifndef RTB_OFFLINE_FREQ_PERIODIC_DRIVE_H
#define RTB_OFFLINE_FREQ_PERIODIC_DRIVE_H

#include <vector>

#include "freq/harmonic.h"
#include "model/forward.h"

namespace rtb {

struct SineTest {
  double freq = 0.0;  // [1/time]
  double amp = 0.0;   // displacement amplitude A [length]
};

// A fixed discretization: M steps per period, C periods from rest.
struct Discretization {
  int steps_per_cycle = 128;
  int cycles = 8;
};

// x_i = A sin(2 pi f i T/M), i = 0 .. C M; x_0 = 0 is the state at rest.
DriveGrid sine_drive_grid(const SineTest &s, const Discretization &d);

// X1 and F1 of period k (0-based) of a run on sine_drive_grid.
struct PeriodHarmonics {
  cplx X1, F1;
};
PeriodHarmonics period_harmonics(const DriveGrid &g, const std::vector<double> &force, int M,
                                 int k);
// dF1/dF_i of the last period: the weight of force sample i (zero outside it).
cplx last_period_weight(const Discretization &d, size_t i);

struct DynStiffTolerance {
  double stiffness_rel = 1e-3;  // relative, on |K*|
  double loss_deg = 0.05;       // absolute, on the loss angle [deg]
};

struct DynStiffOptions {
  DynStiffTolerance tol;
  int min_steps = 128, max_steps = 8192;  // steps per cycle
  int max_cycles = 512;
  double newton_tol = 1e-12;              // rtb_settings.tol
};

struct DynStiffPoint {
  SineTest test;
  ComplexStiffness k;
  Discretization disc;          // the discretization that produced k
  double step_change_rel = 0;   // |K*| change between M/2 and M steps per cycle
  double step_change_deg = 0;   // loss-angle change between M/2 and M
  double period_change_rel = 0; // last period-to-period change of |K*| (with its tail)
  double period_change_deg = 0;
  bool converged = false;       // all checks met within the limits
};

// The converged dynamic stiffness of p at one (frequency, amplitude).
// Throws std::runtime_error if the stepper fails.
DynStiffPoint dynamic_stiffness(const rtb_params &p, const SineTest &s, const DynStiffOptions &o);

// K* of the last period at a fixed discretization (what the table fit uses).
ComplexStiffness dynamic_stiffness_fixed(const rtb_params &p, const SineTest &s,
                                         const Discretization &d, double newton_tol = 1e-12);

}  // namespace rtb

#endif
