// newton_step_test.cpp -- the stage Newton matrix's LU (rt_bushing/src/
// newton_step.h): the twisted continuant factorization, its rescaling and
// its division-chain fallback solve J x = b to rounding, checked by the
// componentwise backward error against J itself (eq. (2)'s chain stiffness:
// J = I + h K D), over the range of slopes the stage solver meets.
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <random>
#include <vector>

#include "newton_step.h"

namespace {

// |J x - b|_k / (|J| |x| + |b|)_k, max over k: the backward error of x.
double backward_error(int n, double hK0, double hKr, const std::vector<double> &D,
                      const std::vector<double> &x, const std::vector<double> &b) {
  double worst = 0.0;
  for (int k = 0; k < n; ++k) {
    const double dk = 1.0 + (k == 0 ? hK0 : 2.0 * hKr) * D[k];
    double r = dk * x[k] - b[k], s = std::fabs(dk * x[k]) + std::fabs(b[k]);
    if (k > 0) r += -hKr * D[k - 1] * x[k - 1], s += std::fabs(hKr * D[k - 1] * x[k - 1]);
    if (k < n - 1) r += -hKr * D[k + 1] * x[k + 1], s += std::fabs(hKr * D[k + 1] * x[k + 1]);
    if (s > 0.0) worst = std::fmax(worst, std::fabs(r) / s);
  }
  return worst;
}

// Slopes log-uniform over [10^lo, 10^hi], a fifth of them zero (cells at rest).
std::vector<double> slopes(std::mt19937_64 &g, int n, double lo, double hi) {
  std::uniform_real_distribution<double> e(lo, hi), u(0.0, 1.0);
  std::vector<double> D(n);
  for (double &d : D) d = u(g) < 0.2 ? 0.0 : std::pow(10.0, e(g));
  return D;
}

void expect_solves(int n, double hK0, double hKr, const std::vector<double> &D, std::mt19937_64 &g) {
  std::normal_distribution<double> N(0.0, 1.0);
  std::vector<double> b(n), x(n), x2(n);
  for (double &v : b) v = N(g);
  rtb_newton_lu lu;
  ASSERT_EQ(rtb_newton_factor(n, hK0, hKr, D.data(), &lu), 0);
  rtb_newton_substitute(&lu, 1.0, b.data(), x.data());
  for (double v : x) ASSERT_TRUE(std::isfinite(v));
  EXPECT_LE(backward_error(n, hK0, hKr, D, x, b), 64 * n * DBL_EPSILON) << "n " << n;
  // The sign argument solves J x = -b with the same factors.
  rtb_newton_substitute(&lu, -1.0, b.data(), x2.data());
  for (int k = 0; k < n; ++k) EXPECT_EQ(x2[k], -x[k]);
}

TEST(NewtonLU, SolvesToRoundingOverTheSlopeRange) {
  std::mt19937_64 g(11);
  for (int n : {1, 2, 3, 4, 5, 15, 16, 32})
    for (int rep = 0; rep < 200; ++rep) {
      const std::vector<double> D = slopes(g, n, -9.0, 9.0);
      expect_solves(n, 0.3 + rep * 1e-3, 0.1, D, g);
    }
}

TEST(NewtonLU, RescalesTheContinuantOfStiffChains) {
  // 32 steep cells at ~1e40: the leading minors reach 1e1280 unscaled.
  std::mt19937_64 g(12);
  for (int rep = 0; rep < 50; ++rep) expect_solves(32, 2.0, 1.0, slopes(g, 32, 38.0, 42.0), g);
}

TEST(NewtonLU, FallsBackToTheDivisionChainForNearRigidCells) {
  // Entries beyond RTB_NEWTON_ENTRY_MAX (products of two would overflow).
  std::mt19937_64 g(13);
  for (int rep = 0; rep < 50; ++rep) expect_solves(15, 2.0, 1.0, slopes(g, 15, 45.0, 120.0), g);
}

TEST(NewtonLU, MatchesTheDivisionChainPivots) {
  // The continuant's pivot ratios equal the division chain's pivots to
  // rounding: downwards above the meeting row, upwards below it.
  std::mt19937_64 g(14);
  const int n = 15;
  const double hK0 = 0.9, hKr = 0.4;
  for (int rep = 0; rep < 100; ++rep) {
    const std::vector<double> D = slopes(g, n, -4.0, 4.0);
    rtb_newton_lu lu;
    ASSERT_EQ(rtb_newton_factor(n, hK0, hKr, D.data(), &lu), 0);
    ASSERT_EQ(lu.m, n / 2);
    double piv = 1.0 + hK0 * D[0];
    for (int k = 1; k < lu.m; ++k) {
      piv = 1.0 + 2.0 * hKr * D[k] - (hKr * D[k - 1]) * (hKr * D[k]) / piv;
      EXPECT_NEAR(lu.inv[k] * piv, 1.0, 1e-13) << "row " << k;
    }
    piv = 1.0 + 2.0 * hKr * D[n - 1];
    for (int k = n - 2; k > lu.m; --k) {
      piv = 1.0 + 2.0 * hKr * D[k] - (hKr * D[k + 1]) * (hKr * D[k]) / piv;
      EXPECT_NEAR(lu.inv[k] * piv, 1.0, 1e-13) << "row " << k;
    }
  }
}

}  // namespace
