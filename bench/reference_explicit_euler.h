/* reference_explicit_euler.h -- the seed paper's real-time integrator, for
 * benchmarking only (not part of the library).
 *
 * Puel, Bourgeteau & Aubry (2013), section 3.5: the RT model was run inside
 * ADAMS (VARSUB) with an explicit Euler scheme whose step is the multibody
 * step divided "by a given factor, which allows to guarantee the stability of
 * the Euler time integration scheme".
 *
 * Eq. (2) is implicit in the velocities (K y + psi(y') = b with
 * psi(v) = C0 sign(v)|v|^alpha), so explicit Euler can only be applied to its
 * primal (solved-for-velocity) form
 *
 *     y' = phi(b(t) - K y),   phi(f) = sign(f) (|f| / C0)^(1/alpha),
 *
 * b = (Kpa y0(t), 0, ..., 0), K the tridiagonal chain stiffness. One host step
 * of length dt is divided into m substeps h = dt/m; the input y0 is
 * interpolated linearly between the previous and the new host sample (a host
 * only provides the displacement at its own steps), and the force is that of
 * eq. (11): F = K0 y0 + Kpa (y0 - y1).
 *
 * Stability: the Jacobian of the right-hand side is -D K with
 * D = diag(phi'(f_k)), phi'(f) = (1/alpha) |f|^(1/alpha - 1) / C0^(1/alpha).
 * Explicit Euler needs h * rho(D K) <= 2, and rho(D K) <= max_k phi'(f_k) * 4 Kr
 * (Gershgorin), so the stable substep shrinks like |f|^-(1/alpha - 1): for the
 * paper's alpha = 0.2 like |f|^-4. The step that is stable at one force level
 * is unstable at a larger one, and because phi' grows with the force an
 * instability amplifies itself (overshoot -> larger f -> stiffer) and blows up.
 *
 * Plain C++ (header-only), no allocation; N <= RTB_MAX_CELLS.
 */
#ifndef RTB_BENCH_REFERENCE_EXPLICIT_EULER_H
#define RTB_BENCH_REFERENCE_EXPLICIT_EULER_H

#include <cmath>

#include "rt_bushing/rt_bushing.h"

namespace rtb_ref {

struct ExplicitEuler {
  int n = 0;
  double K0 = 0, Kpa = 0, Kr = 0, C0 = 0, inv_alpha = 0;
  double x = 0;                      /* last host displacement y0 */
  double y[RTB_MAX_CELLS] = {};      /* cell DOFs */
  double max_stiffness = 0;          /* max over substeps of h * rho(D K) */
  bool finite = true;                /* false once anything went non-finite */

  /* Virgin bushing at rest, x = 0 (the paper's initial condition). */
  void init(const rtb_params &p) {
    n = p.cells;
    K0 = p.K0;
    Kpa = p.Kpa;
    Kr = p.Kr;
    C0 = p.C0;
    inv_alpha = 1.0 / p.alpha;
    x = 0.0;
    for (int k = 0; k < RTB_MAX_CELLS; ++k) y[k] = 0.0;
    max_stiffness = 0.0;
    finite = true;
  }

  /* phi(f) = sign(f) (|f|/C0)^(1/alpha), evaluated like the library's
   * rtb_law_velocity (exp/log) so both pay the same transcendental cost. */
  double phi(double f) const {
    if (f == 0.0) return 0.0;
    const double m = std::exp(std::log(std::fabs(f) / C0) * inv_alpha);
    return f > 0.0 ? m : -m;
  }

  /* Dashpot forces f = b - K y for the input x0. */
  void forces(double x0, double *f) const {
    if (n == 1) {
      f[0] = Kpa * x0 - (Kpa + Kr) * y[0];
      return;
    }
    f[0] = Kpa * x0 - (Kpa + Kr) * y[0] + Kr * y[1];
    for (int k = 1; k < n - 1; ++k) f[k] = Kr * (y[k - 1] - 2.0 * y[k] + y[k + 1]);
    f[n - 1] = Kr * (y[n - 2] - 2.0 * y[n - 1]);
  }

  /* h * rho(D K) at the current state: explicit Euler is linearly stable
   * where this is <= 2. D K is similar to the symmetric tridiagonal
   * S = D^1/2 K D^1/2, whose largest eigenvalue is found by Sturm-count
   * bisection (exact to ~1e-12 relative; analysis only, not real-time). */
  double stability_number(double x0, double h) const {
    double f[RTB_MAX_CELLS], a[RTB_MAX_CELLS], b[RTB_MAX_CELLS], d[RTB_MAX_CELLS];
    forces(x0, f);
    for (int k = 0; k < n; ++k) d[k] = f[k] == 0.0 ? 0.0 : std::sqrt(inv_alpha * phi(f[k]) / f[k]);
    double hi = 0.0;
    for (int k = 0; k < n; ++k) {
      a[k] = d[k] * d[k] * (k == 0 ? Kpa + Kr : 2.0 * Kr);
      b[k] = k + 1 < n ? Kr * d[k] * d[k + 1] : 0.0; /* |off-diagonal| */
      const double r = a[k] + b[k] + (k > 0 ? b[k - 1] : 0.0);
      if (r > hi) hi = r; /* Gershgorin upper bound */
    }
    if (!(hi > 0.0)) return hi == 0.0 ? 0.0 : INFINITY;
    if (!std::isfinite(hi)) return INFINITY;
    double lo = 0.0;
    for (int it = 0; it < 200 && hi - lo > 1e-13 * hi; ++it) {
      const double lam = 0.5 * (lo + hi);
      int below = 0; /* eigenvalues of S below lam (LDL^T pivots < 0) */
      double q = a[0] - lam;
      if (q < 0.0) ++below;
      for (int k = 1; k < n; ++k) {
        if (q == 0.0) q = 1e-300;
        q = a[k] - lam - b[k - 1] * b[k - 1] / q;
        if (q < 0.0) ++below;
      }
      if (below == n) hi = lam; else lo = lam;
    }
    return h * hi;
  }

  /* One host step to displacement x_new over dt with m explicit substeps.
   * Returns the force of eq. (11). If track_stability, records the maximum
   * over the substeps of h * rho(D K) in max_stiffness (slow; analysis). */
  template <bool track_stability = false>
  double step(double x_new, double dt, int m) {
    const double h = dt / m;
    const double dx = (x_new - x) / m;
    double f[RTB_MAX_CELLS];
    for (int j = 0; j < m; ++j) {
      const double x0 = x + j * dx; /* input at the start of the substep */
      if (track_stability) {
        const double s = stability_number(x0, h);
        if (!(s <= max_stiffness)) max_stiffness = s;
      }
      forces(x0, f);
      for (int k = 0; k < n; ++k) y[k] += h * phi(f[k]);
    }
    x = x_new;
    for (int k = 0; k < n; ++k)
      if (!std::isfinite(y[k])) finite = false;
    return K0 * x + Kpa * (x - y[0]);
  }
};

}  // namespace rtb_ref

#endif
