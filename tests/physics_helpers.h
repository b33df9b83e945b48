// physics_helpers.h -- shared helpers of physics_test.cpp and accuracy_test.cpp:
// prescribed-displacement waveforms, a driver that runs the real-time stepper
// over a uniform time grid, and the hysteresis-loop measurements of Puel,
// Bourgeteau & Aubry (2013) (secant stiffness, maximum load, tangents at cusps).
//
// Header-only, no GoogleTest dependency: the driver reports the worst status
// and the number of RTB_NOT_CONVERGED steps; the tests assert on them.
#ifndef RTB_TESTS_PHYSICS_HELPERS_H
#define RTB_TESTS_PHYSICS_HELPERS_H

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <vector>

#include "rt_bushing/rt_bushing.h"

namespace rtbtest {

constexpr double kPi = 3.14159265358979323846;

// ------------------------------------------------------------------ params

// The section 3.4 example (K0=1000, Kpa=800, Kr=3000 N/mm, C0=40 N (s/mm)^0.2,
// alpha=0.2; STS: Ff=40 N) with N cells and the given integrator.
inline rtb_params paper_params(int model, int cells = RTB_DEFAULT_CELLS,
                               int integrator = RTB_INTEGRATOR_SDIRK2) {
  rtb_params p;
  rtb_params_default(&p, model);
  p.cells = cells;
  p.integrator = integrator;
  return p;
}

// The extensions of BM_Extension's "all" set (bench/worst_case_bench.cpp)
// but the eq. (14) smoothing and the softening spring: a cubic spring,
// tension/compression asymmetry, a Maxwell branch, a parallel dashpot,
// inertia, a 0.05 mm clearance and Mullins softening.
inline void add_extensions(rtb_params *p) {
  p->k3 = 50.0;
  p->k_asym = 200.0;
  p->maxwell_k = 300.0;
  p->maxwell_tau = 0.05;
  p->viscous_c = 2.0;
  p->mass = 1e-3;
  p->backlash = 0.05;
  p->mullins = 0.3;
}

inline rtb_params sts_params(int cells, double K0, double Kpa, double Kr, double Ff) {
  rtb_params p = paper_params(RTB_MODEL_STS, cells);
  p.K0 = K0;
  p.Kpa = Kpa;
  p.Kr = Kr;
  p.Ff = Ff;
  return p;
}

// Static (fully relaxed) force of the chain, section 3.4 / rtb_static_force:
// K0 x + x / (1/Kpa + N/Kr), written out independently of the library.
inline double static_force_closed_form(const rtb_params &p, double x) {
  return p.K0 * x + x / (1.0 / p.Kpa + p.cells / p.Kr);
}

// ------------------------------------------------------------------ inputs

// x = A sin(2 pi f t).
struct Sine {
  double A, f;
  double operator()(double t) const { return A * std::sin(2.0 * kPi * f * t); }
};

// Triangular periodic displacement of amplitude A and frequency f, starting at
// 0 and going up first: 0 -> A at T/4, -> -A at 3T/4, -> 0 at T.
struct Triangle {
  double A, f;
  double operator()(double t) const {
    double s = t * f;
    s -= std::floor(s);
    if (s < 0.25) return 4.0 * A * s;
    if (s < 0.75) return A * (2.0 - 4.0 * s);
    return A * (4.0 * s - 4.0);
  }
};

// Heaviside step "not truly discontinuous": a linear rise of duration `rise`
// from 0 to X starting at t0, then hold (section 5.5: rise = 0.1 s).
struct RampHold {
  double X, rise, t0 = 0.0;
  double operator()(double t) const {
    if (t <= t0) return 0.0;
    if (t >= t0 + rise) return X;
    return X * (t - t0) / rise;
  }
};

// Two successive steps (Figure 9): 0 -> X1 over [0, rise], hold, then
// X1 -> X1 + X2 over [t2, t2 + rise], hold.
struct TwoSteps {
  double X1, X2, rise, t2;
  double operator()(double t) const {
    return RampHold{X1, rise, 0.0}(t) + RampHold{X2, rise, t2}(t);
  }
};

// ------------------------------------------------------------------ driver

struct Trace {
  std::vector<double> t, x, F;  // index 0 is the initial state
  rtb_status worst = RTB_OK;    // most severe status seen (errors < 0 < warnings)
  long not_converged = 0;       // steps that returned RTB_NOT_CONVERGED
  long steps = 0;
  bool ok() const { return worst >= 0; }
};

inline rtb_status worse_status(rtb_status a, rtb_status b) {
  if (a < 0 || b < 0) return a < b ? a : b;
  return a > b ? a : b;
}

// Run `steps` uniform steps of length dt from an initialised state, driving
// x(t) = input(t) and recording every `stride`-th step (and the last one).
// Stops at the first error (status < 0).
template <class Input>
Trace simulate(const rtb_params &p, const Input &input, double dt, long steps,
               long stride = 1, const rtb_settings *set = nullptr, double x0 = 0.0) {
  Trace tr;
  rtb_state s;
  rtb_status st = rtb_state_init(&s, &p, x0);
  tr.worst = st;
  if (st < 0) return tr;
  tr.t.push_back(0.0);
  tr.x.push_back(x0);
  tr.F.push_back(s.force);
  for (long i = 1; i <= steps; ++i) {
    const double t = i * dt;
    const double x = input(t);
    double F = 0.0;
    st = rtb_step(&s, &p, set, x, dt, &F);
    tr.worst = worse_status(tr.worst, st);
    if (st == RTB_NOT_CONVERGED) ++tr.not_converged;
    if (st < 0) break;
    tr.steps = i;
    if (i % stride == 0 || i == steps) {
      tr.t.push_back(t);
      tr.x.push_back(x);
      tr.F.push_back(F);
    }
  }
  return tr;
}

// Same driver on an arbitrary increasing time grid t[0] = 0 < t[1] < ...
// (step i has length t[i] - t[i-1]); every step is recorded.
template <class Input>
Trace simulate_on_grid(const rtb_params &p, const Input &input, const std::vector<double> &grid,
                       const rtb_settings *set = nullptr, double x0 = 0.0) {
  Trace tr;
  rtb_state s;
  rtb_status st = rtb_state_init(&s, &p, x0);
  tr.worst = st;
  if (st < 0 || grid.empty()) return tr;
  tr.t.push_back(grid[0]);
  tr.x.push_back(x0);
  tr.F.push_back(s.force);
  for (std::size_t i = 1; i < grid.size(); ++i) {
    const double x = input(grid[i]);
    double F = 0.0;
    st = rtb_step(&s, &p, set, x, grid[i] - grid[i - 1], &F);
    tr.worst = worse_status(tr.worst, st);
    if (st == RTB_NOT_CONVERGED) ++tr.not_converged;
    if (st < 0) break;
    tr.steps = static_cast<long>(i);
    tr.t.push_back(grid[i]);
    tr.x.push_back(x);
    tr.F.push_back(F);
  }
  return tr;
}

// Linear interpolation of the recorded force at time t (t within the trace).
inline double force_at(const Trace &tr, double t) {
  auto it = std::lower_bound(tr.t.begin(), tr.t.end(), t);
  if (it == tr.t.begin()) return tr.F.front();
  if (it == tr.t.end()) return tr.F.back();
  const std::size_t j = static_cast<std::size_t>(it - tr.t.begin()), i = j - 1;
  const double w = (t - tr.t[i]) / (tr.t[j] - tr.t[i]);
  return (1.0 - w) * tr.F[i] + w * tr.F[j];
}

// Number of steps of length dt in a duration T (T/dt rounded).
inline long steps_for(double T, double dt) { return std::lround(T / dt); }

// ------------------------------------------------------------------ loop measures

// Samples [first, last] (inclusive indices into a Trace).
struct Window {
  std::size_t first, last;
};

// The last `samples_per_cycle` + 1 samples of a trace (one full cycle).
inline Window last_cycle(const Trace &tr, std::size_t samples_per_cycle) {
  const std::size_t last = tr.F.size() - 1;
  return {last - samples_per_cycle, last};
}

struct LoopFeatures {
  double x_max, x_min, F_max, F_min;
  double F_at_xmax, F_at_xmin;
  double secant_paper;  // section 3.4: max load / max displacement
  double secant_loop;   // section 2.2: slope of the line joining the two
                        // extreme points of the cycle
};

inline LoopFeatures loop_features(const Trace &tr, Window w) {
  LoopFeatures L{};
  std::size_t imax = w.first, imin = w.first, fmax = w.first, fmin = w.first;
  for (std::size_t i = w.first; i <= w.last; ++i) {
    if (tr.x[i] > tr.x[imax]) imax = i;
    if (tr.x[i] < tr.x[imin]) imin = i;
    if (tr.F[i] > tr.F[fmax]) fmax = i;
    if (tr.F[i] < tr.F[fmin]) fmin = i;
  }
  L.x_max = tr.x[imax];
  L.x_min = tr.x[imin];
  L.F_max = tr.F[fmax];
  L.F_min = tr.F[fmin];
  L.F_at_xmax = tr.F[imax];
  L.F_at_xmin = tr.F[imin];
  L.secant_paper = L.F_max / L.x_max;
  L.secant_loop = (L.F_at_xmax - L.F_at_xmin) / (L.x_max - L.x_min);
  return L;
}

// Largest |F_a - F_b| over a window, both traces sampled on the same grid.
inline double max_abs_diff(const Trace &a, const Trace &b, Window w) {
  double d = 0.0;
  for (std::size_t i = w.first; i <= w.last; ++i) d = std::max(d, std::fabs(a.F[i] - b.F[i]));
  return d;
}

inline double max_abs(const Trace &a, Window w) {
  double m = 0.0;
  for (std::size_t i = w.first; i <= w.last; ++i) m = std::max(m, std::fabs(a.F[i]));
  return m;
}

// Slope of the chord between samples i and j.
inline double chord(const Trace &tr, std::size_t i, std::size_t j) {
  return (tr.F[j] - tr.F[i]) / (tr.x[j] - tr.x[i]);
}

// ------------------------------------------------------------------ STS closed forms
//
// Ladder of eq. (2) with friction elements (section 3.1, alpha -> 0, C0 = Ff):
// under a symmetric periodic displacement of amplitude X the stabilised loop is
// a Masing loop; during a half cycle the load P = Kpa (y0 - y1) in the Kpa
// spring changes by 2 Pmax and DOF k reverses its slip when that change
// exceeds 2 k Ff. With m DOFs slipping at the tip, the spring forces are
// s_k = Pmax - k Ff (k <= m) and the remaining ones carry nothing, so
//   X = Pmax / Kpa + sum_{k=1..m} (Pmax - k Ff) / Kr.
// "Exactly N-1 cells loaded" (section 5.4) is the largest amplitude before
// DOF N slips, Pmax = N Ff:
//   X*   = N Ff / Kpa + N (N-1) Ff / (2 Kr),
//   Fmax = K0 X* + N Ff = Ksec X*          (Ksec of eq. (17)).
// Eq. (20) of the paper equals 2 Fmax, i.e. the peak-to-peak force range
// F(X*) - F(-X*) (and its inversion (21)-(24) is consistent with that when
// X_max is read as the peak-to-peak displacement 2 X*); see docs/accuracy.md.
struct StsClosedForm {
  double Tg1, Tg2, Ksec;  // eq. (18), (19), (17)
  double X_star;          // amplitude with exactly N-1 cells loaded
  double F_max;           // K0 X* + N Ff
  double eq20;            // eq. (20) literally (with K0 = K0^S)
};

inline StsClosedForm sts_closed_form(const rtb_params &p) {
  const double N = p.cells, K0 = p.K0, Kpa = p.Kpa, Kr = p.Kr, Ff = p.Ff;
  StsClosedForm c;
  c.Tg1 = K0 + Kpa;
  c.Tg2 = K0 + Kpa * Kr / ((N - 1.0) * Kpa + Kr);
  c.Ksec = K0 + Kpa * Kr / (0.5 * (N - 1.0) * Kpa + Kr);
  c.X_star = N * Ff / Kpa + N * (N - 1.0) * Ff / (2.0 * Kr);
  c.F_max = K0 * c.X_star + N * Ff;
  c.eq20 = K0 * (Ff * N * (N - 1.0) / Kr + 2.0 * Ff * N / Kpa) + 2.0 * N * Ff;
  return c;
}

// Eq. (21)-(24): STS parameters from the loop features (Tg1, Tg2, Fmax, Xmax).
struct StsParams {
  double K0, Kpa, Kr, Ff;
};

inline StsParams sts_invert(double Tg1, double Tg2, double Fmax, double Xmax, int N) {
  const double D = 2.0 * Fmax - (Tg1 + Tg2) * Xmax;
  StsParams s;
  s.K0 = (Fmax * (Tg1 + Tg2) - 2.0 * Tg1 * Tg2 * Xmax) / D;
  s.Kpa = (Tg1 - Tg2) * (Fmax - Tg1 * Xmax) / D;
  s.Kr = -(N - 1.0) * (Tg1 - Tg2) * (Fmax - Tg1 * Xmax) * (Fmax - Tg2 * Xmax) / (D * D);
  s.Ff = (Fmax - Tg1 * Xmax) * (Fmax - Tg2 * Xmax) / (N * D);
  return s;
}

}  // namespace rtbtest

#endif
