// tridiagonal_test.cpp -- the Thomas elimination every chain system uses
// (rt_bushing/src/tridiagonal.h): factored once and substituted per
// right-hand side (the offline Jacobian's columns), alone or all columns
// together, it gives the same bits as a solve from scratch; the solution
// satisfies A x = b; a zero pivot leaves the right-hand side untouched.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "rt_bushing/rt_bushing.h"
#include "tridiagonal.h"

namespace {

// A stage matrix I + h D K of a random chain (D >= 0: column diagonally
// dominant, the case the stepper, tangent and adjoint all solve).
struct Chain {
  int n;
  double lo[RTB_MAX_CELLS], di[RTB_MAX_CELLS], up[RTB_MAX_CELLS];
};

Chain random_stage(std::mt19937 &g, int n) {
  std::uniform_real_distribution<double> u(0.0, 1.0);
  double D[RTB_MAX_CELLS];
  for (int k = 0; k < n; ++k) D[k] = std::pow(10.0, 6.0 * u(g) - 3.0);
  Chain c;
  c.n = n;
  rtb_stage_matrix(n, 1e-3 * (0.1 + u(g)), D, 50.0 + 500.0 * u(g), 10.0 + 1000.0 * u(g), 0, c.lo,
                   c.di, c.up);
  return c;
}

// Substituted one column at a time or all together (rtb_tridiag_subst_many),
// every column gets the bits of a solve from scratch.
TEST(Tridiagonal, FactoredOnceSolvesEveryColumnAsASolveFromScratch) {
  std::mt19937 g(32);
  std::normal_distribution<double> nd;
  constexpr int kCols = 5;
  for (int n : {1, 2, 15, RTB_MAX_CELLS}) {
    const Chain c = random_stage(g, n);
    double piv[RTB_MAX_CELLS], w[RTB_MAX_CELLS], work[RTB_MAX_CELLS];
    ASSERT_EQ(rtb_tridiag_factor(n, c.lo, c.di, c.up, piv, w), 0);
    double b[kCols][RTB_MAX_CELLS], x1[kCols][RTB_MAX_CELLS], x2[kCols][RTB_MAX_CELLS],
        x3[kCols][RTB_MAX_CELLS];
    double *cols[kCols];
    for (int col = 0; col < kCols; ++col) {
      for (int k = 0; k < n; ++k) b[col][k] = x1[col][k] = x2[col][k] = x3[col][k] = nd(g);
      cols[col] = x3[col];
      rtb_tridiag_subst(n, c.lo, piv, w, x1[col]);
      ASSERT_EQ(rtb_tridiag_solve(n, c.lo, c.di, c.up, x2[col], work), 0);
    }
    rtb_tridiag_subst_many(n, c.lo, piv, w, kCols, cols);
    for (int col = 0; col < kCols; ++col) {
      double bmax = 0.0;
      for (int k = 0; k < n; ++k) bmax = std::fmax(bmax, std::fabs(b[col][k]));
      for (int k = 0; k < n; ++k) {
        EXPECT_EQ(x1[col][k], x2[col][k]) << "n " << n << " k " << k;  // the same bits
        EXPECT_EQ(x3[col][k], x2[col][k]) << "n " << n << " k " << k;
        double Ax = c.di[k] * x1[col][k];
        if (k > 0) Ax += c.lo[k] * x1[col][k - 1];
        if (k + 1 < n) Ax += c.up[k] * x1[col][k + 1];
        EXPECT_NEAR(Ax, b[col][k], 1e-12 * bmax) << "n " << n << " k " << k;
      }
    }
  }
}

TEST(Tridiagonal, AZeroPivotIsReportedAndLeavesTheRightHandSide) {
  // Second pivot 0.5 - 1 * (1 / 2) = 0, after the first row was eliminated.
  const double lo[3] = {0.0, 1.0, 0.5}, di[3] = {2.0, 0.5, 2.0}, up[3] = {1.0, 0.5, 0.0};
  double rhs[3] = {1.0, 2.0, 3.0}, work[3];
  EXPECT_EQ(rtb_tridiag_solve(3, lo, di, up, rhs, work), -1);
  EXPECT_EQ(rhs[0], 1.0);
  EXPECT_EQ(rhs[1], 2.0);
  EXPECT_EQ(rhs[2], 3.0);
  EXPECT_EQ(rtb_tridiag_solve(0, lo, di, up, rhs, work), -1);
  EXPECT_EQ(rtb_tridiag_solve(RTB_MAX_CELLS + 1, lo, di, up, rhs, work), -1);
}

}  // namespace
