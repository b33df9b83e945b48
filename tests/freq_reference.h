// freq_reference.h -- references for the frequency-domain tests that share
// no code with the element or the offline tool:
//  * the closed-form complex stiffness of the linear ladder (alpha = 1),
//  * an explicit RK4 integration of eq. (2) under a sine, with its own
//    Fourier integral, for the nonlinear dashpot.
#ifndef RTB_TESTS_FREQ_REFERENCE_H
#define RTB_TESTS_FREQ_REFERENCE_H

#include <cmath>
#include <complex>
#include <vector>

namespace rtbtest {

// Eq. (2) with a linear dashpot C0 v (alpha = 1), y0 = X e^{i w t}:
//   (Kpa + Kr + i w C0) y1 - Kr y2 = Kpa X,
//   -Kr y_{k-1} + (2 Kr + i w C0) y_k - Kr y_{k+1} = 0,  y_{N+1} = 0,
// F = K0 X + Kpa (X - y1). The interior recurrence has the solutions
// y_k = a sinh((N + 1 - k) theta) with cosh(theta) = 1 + i w C0 / (2 Kr)
// (they vanish at k = N + 1). The first equation, written as the recurrence
// at k = 1 plus (Kpa - Kr) y1, gives
//   a [Kr sinh((N+1) theta) + (Kpa - Kr) sinh(N theta)] = Kpa X,
// hence
//   K*(w) = K0 + Kpa Kr (sinh((N+1)theta) - sinh(N theta))
//                 / (Kr sinh((N+1)theta) + (Kpa - Kr) sinh(N theta)).
// At w = 0 (theta -> 0, sinh(n theta) ~ n theta) it is K0 + 1/(1/Kpa + N/Kr),
// the relaxed stiffness of rtb_static_force.
inline std::complex<double> ladder_complex_stiffness(double K0, double Kpa, double Kr, double C0,
                                                     int N, double omega) {
  using C = std::complex<double>;
  const C theta = std::acosh(C(1.0, omega * C0 / (2.0 * Kr)));
  const C sN1 = std::sinh(double(N + 1) * theta), sN = std::sinh(double(N) * theta);
  return K0 + Kpa * Kr * (sN1 - sN) / (Kr * sN1 + (Kpa - Kr) * sN);
}

// Eq. (2) with the dashpot of eq. (1), integrated explicitly: the dashpot
// velocities are v = phi(f) = sign(f) (|f|/C0)^(1/alpha) of the forces
// f = b - K y (b = Kpa x e1), so y' = phi(Kpa x(t) e1 - K y). Classic RK4 at
// `steps` steps per period from rest; returns K* = F1/X1 of the last period
// by the trapezoid rule on the step ends (X1 = -i A for x = A sin(w t)).
struct LadderParams {
  double K0, Kpa, Kr, C0, alpha;
  int N;
};

inline std::complex<double> ladder_rk4_complex_stiffness(const LadderParams &p, double freq,
                                                         double amp, int cycles, int steps) {
  const int N = p.N;
  const double T = 1.0 / freq, h = T / steps, w = 2.0 * M_PI * freq;
  auto rhs = [&](double t, const std::vector<double> &y, std::vector<double> &dy) {
    const double x = amp * std::sin(w * t);
    for (int k = 0; k < N; ++k) {
      const double left = k == 0 ? p.Kpa * (x - y[0]) : p.Kr * (y[k - 1] - y[k]);
      const double right = p.Kr * (y[k] - (k + 1 < N ? y[k + 1] : 0.0));
      const double f = left - right;
      dy[k] = (f >= 0 ? 1.0 : -1.0) * std::pow(std::fabs(f) / p.C0, 1.0 / p.alpha);
    }
  };
  std::vector<double> y(N, 0.0), k1(N), k2(N), k3(N), k4(N), tmp(N);
  std::complex<double> F1 = 0.0;
  for (int c = 0; c < cycles; ++c)
    for (int j = 0; j < steps; ++j) {
      const double t = (c * steps + j) * h;
      rhs(t, y, k1);
      for (int k = 0; k < N; ++k) tmp[k] = y[k] + 0.5 * h * k1[k];
      rhs(t + 0.5 * h, tmp, k2);
      for (int k = 0; k < N; ++k) tmp[k] = y[k] + 0.5 * h * k2[k];
      rhs(t + 0.5 * h, tmp, k3);
      for (int k = 0; k < N; ++k) tmp[k] = y[k] + h * k3[k];
      rhs(t + h, tmp, k4);
      for (int k = 0; k < N; ++k) y[k] += h / 6.0 * (k1[k] + 2 * k2[k] + 2 * k3[k] + k4[k]);
      if (c == cycles - 1) {  // last period: F at the step end, periodic trapezoid rule
        const double te = t + h, x = amp * std::sin(w * te);
        const double F = p.K0 * x + p.Kpa * (x - y[0]);
        F1 += (2.0 / steps) * F * std::exp(std::complex<double>(0.0, -w * te));
      }
    }
  return F1 / std::complex<double>(0.0, -amp);
}

}  // namespace rtbtest

#endif
