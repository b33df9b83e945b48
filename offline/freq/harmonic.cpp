// harmonic.cpp -- see harmonic.h.
#include "freq/harmonic.h"

#include <Eigen/Dense>
#include <cmath>

namespace rtb {

cplx harmonic_weight(int j, int M, double phase0) {
  const double ph = phase0 + 2.0 * M_PI * j / M;
  return (2.0 / M) * cplx(std::cos(ph), -std::sin(ph));
}

cplx first_harmonic(const double *z, int M, double phase0) {
  cplx s = 0.0;
  for (int j = 0; j < M; ++j) s += z[j] * harmonic_weight(j, M, phase0);
  return s;
}

cplx fit_harmonic(const std::vector<double> &t, const std::vector<double> &z, double omega,
                  size_t begin, size_t end) {
  const Eigen::Index n = (Eigen::Index)(end - begin);
  Eigen::MatrixXd A(n, 3);
  Eigen::VectorXd b(n);
  const double t0 = t[begin];  // phases relative to the window start: better conditioned
  for (Eigen::Index k = 0; k < n; ++k) {
    const double ph = omega * (t[begin + k] - t0);
    A(k, 0) = 1.0;
    A(k, 1) = std::cos(ph);
    A(k, 2) = std::sin(ph);
    b[k] = z[begin + k];
  }
  const Eigen::Vector3d c = A.colPivHouseholderQr().solve(b);
  // a cos + b sin = Re((a - i b) e^{i ph}); shift back to absolute time.
  return cplx(c[1], -c[2]) * std::exp(cplx(0.0, -omega * t0));
}

ComplexStiffness complex_stiffness(cplx F1, cplx X1) {
  const cplx K = F1 / X1;
  return ComplexStiffness{std::abs(K), std::arg(K) * 180.0 / M_PI};
}

}  // namespace rtb
