// periodic_drive.cpp -- see periodic_drive.h.
#include "freq/periodic_drive.h"

#include <algorithm>
#include <cmath>

namespace rtb {

DriveGrid sine_drive_grid(const SineTest &s, const Discretization &d) {
  const int M = d.steps_per_cycle;
  const size_t n = (size_t)d.cycles * M + 1;
  const double h = 1.0 / (s.freq * M);
  DriveGrid g;
  g.x.resize(n);
  g.dt.assign(n, h);
  g.dt[0] = 0.0;
  // The phase reduced mod M keeps sin() exact over many periods.
  for (size_t i = 0; i < n; ++i) g.x[i] = s.amp * std::sin(2.0 * M_PI * (double)(i % M) / M);
  g.first_sample = 0;
  return g;
}

PeriodHarmonics period_harmonics(const DriveGrid &g, const std::vector<double> &force, int M,
                                 int k) {
  // Samples k M + 1 .. (k+1) M: phase w t_i = 2 pi i / M = 2 pi / M + 2 pi j / M.
  const size_t first = (size_t)k * M + 1;
  const double ph0 = 2.0 * M_PI / M;
  return PeriodHarmonics{first_harmonic(&g.x[first], M, ph0),
                         first_harmonic(&force[first], M, ph0)};
}

cplx last_period_weight(const Discretization &d, size_t i) {
  const size_t first = (size_t)(d.cycles - 1) * d.steps_per_cycle + 1;
  if (i < first) return 0.0;
  return harmonic_weight((int)(i - first), d.steps_per_cycle, 2.0 * M_PI / d.steps_per_cycle);
}

ComplexStiffness dynamic_stiffness_fixed(const rtb_params &p, const SineTest &s,
                                         const Discretization &d, double newton_tol) {
  const DriveGrid g = sine_drive_grid(s, d);
  const Trajectory tr = run_forward(p, g, false, newton_tol);
  const PeriodHarmonics h = period_harmonics(g, tr.force, d.steps_per_cycle, d.cycles - 1);
  return complex_stiffness(h.F1, h.X1);
}

namespace {

// Change between two results in units of the tolerance (the larger of the two).
double change_in_tol(const ComplexStiffness &a, const ComplexStiffness &b,
                     const DynStiffTolerance &t) {
  return std::max(std::fabs(a.stiffness - b.stiffness) / (std::fabs(b.stiffness) * t.stiffness_rel),
                  std::fabs(a.loss_angle_deg - b.loss_angle_deg) / t.loss_deg);
}

// Periodic result at M steps per cycle: C doubles until the tail test holds.
DynStiffPoint periodic_at(const rtb_params &p, const SineTest &s, int M, const DynStiffOptions &o) {
  DynStiffPoint r;
  r.test = s;
  for (int C = 4;; C *= 2) {
    r.disc = Discretization{M, C};
    const DriveGrid g = sine_drive_grid(s, r.disc);
    const Trajectory tr = run_forward(p, g, false, o.newton_tol);
    std::vector<ComplexStiffness> k(C);
    for (int c = 0; c < C; ++c) {
      const PeriodHarmonics h = period_harmonics(g, tr.force, M, c);
      k[c] = complex_stiffness(h.F1, h.X1);
    }
    r.k = k[C - 1];
    const double d1 = change_in_tol(k[C - 1], k[C - 2], o.tol);
    const double d0 = change_in_tol(k[C - 2], k[C - 3], o.tol);
    const double ratio = d0 > 0.0 ? d1 / d0 : 0.0;
    const double tail = ratio < 1.0 ? d1 * ratio / (1.0 - ratio) : INFINITY;
    // A loop that is periodic to rounding alternates by ~1e-15 from period to
    // period (ratio ~1): below 1e-6 tolerance units a change is not a transient.
    const double worst = d1 <= 1e-6 ? d1 : d1 + tail;  // last change plus what remains
    r.period_change_rel = std::fabs(k[C - 1].stiffness - k[C - 2].stiffness) / k[C - 1].stiffness;
    r.period_change_deg = std::fabs(k[C - 1].loss_angle_deg - k[C - 2].loss_angle_deg);
    if (std::isfinite(tail)) {  // report the extrapolated remaining change
      r.period_change_rel *= 1.0 + ratio / (1.0 - ratio);
      r.period_change_deg *= 1.0 + ratio / (1.0 - ratio);
    }
    r.converged = worst < 0.1;
    if (r.converged || 2 * C > o.max_cycles) return r;
  }
}

}  // namespace

DynStiffPoint dynamic_stiffness(const rtb_params &p, const SineTest &s, const DynStiffOptions &o) {
  DynStiffPoint coarse = periodic_at(p, s, o.min_steps, o);
  for (int M = 2 * o.min_steps;; M *= 2) {
    DynStiffPoint fine = periodic_at(p, s, M, o);
    fine.step_change_rel = std::fabs(fine.k.stiffness - coarse.k.stiffness) / fine.k.stiffness;
    fine.step_change_deg = std::fabs(fine.k.loss_angle_deg - coarse.k.loss_angle_deg);
    const bool steps_ok = change_in_tol(coarse.k, fine.k, o.tol) < 0.1;
    fine.converged = fine.converged && steps_ok;
    if (steps_ok || 2 * M > o.max_steps) return fine;
    coarse = fine;
  }
}

}  // namespace rtb
