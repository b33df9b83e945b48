// harmonic.h -- first harmonics of periodic signals, the quantities of a
// dynamic-stiffness test (SAE J1085, ISO 10846): for x = X1 e^{i w t} and the
// force's fundamental F1 e^{i w t}, the complex stiffness is K* = F1 / X1,
// reported as |K*| (dynamic stiffness) and arg K* (loss angle).
//
// Convention: Z1 = (2/T) int_0^T z(t) e^{-i w t} dt, so z(t) = Re(Z1 e^{i w t})
// for a pure cosine/sine (a sine A sin(w t) has X1 = -i A).
#ifndef RTB_OFFLINE_FREQ_HARMONIC_H
#define RTB_OFFLINE_FREQ_HARMONIC_H

#include <complex>
#include <vector>

namespace rtb {

using cplx = std::complex<double>;

// Z1 from M uniform samples covering exactly one period, sample j at phase
// w t_j = phase0 + 2 pi j / M (the rectangle rule, exact for trigonometric
// polynomials of degree < M - 1). Linear in z: dZ1/dz_j = harmonic_weight().
cplx first_harmonic(const double *z, int M, double phase0);
cplx harmonic_weight(int j, int M, double phase0);  // (2/M) e^{-i (phase0 + 2 pi j/M)}

// Least-squares fit z ~ c + Re(Z1 e^{i w t}) over samples (t_k, z_k) (any
// grid): the fundamental of a measured record over whole periods, where the
// rectangle rule would need a uniform grid.
cplx fit_harmonic(const std::vector<double> &t, const std::vector<double> &z, double omega,
                  size_t begin, size_t end);

// |K*| and arg K* [deg] of K* = F1 / X1.
struct ComplexStiffness {
  double stiffness = 0.0;       // |F1/X1|  [force/length]
  double loss_angle_deg = 0.0;  // arg(F1/X1) [deg], in (-180, 180]
};
ComplexStiffness complex_stiffness(cplx F1, cplx X1);

}  // namespace rtb

#endif
