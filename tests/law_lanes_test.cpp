// law_lanes_test.cpp -- the law sweep over all cells at once (rt_bushing/
// src/law_lanes*.cpp, issue #11): its exp and ln each within an ulp of the
// exact value (long double reference) over their fast ranges, and the sweep
// equal to the scalar law of dashpot_law.h (libm) to the rounding the
// exp(c ln u) form carries, at every cell count, with the scalar law's values
// and signs at the edges (0, -0, subnormal, overflow, underflow, infinity);
// every vector width this CPU has (AVX2: 4, AVX-512: 8) gives the same bits.
#include <gtest/gtest.h>

#include <cfenv>
#include <cfloat>
#include <cmath>
#include <algorithm>
#include <cstring>
#include <random>
#include <vector>

#include "law_lanes.h"

namespace {

// |got - exact| in units of the last place of the double nearest exact.
double ulps(double got, long double exact) {
  const double r = static_cast<double>(exact);
  const double ulp = std::nextafter(std::fabs(r), INFINITY) - std::fabs(r);
  return static_cast<double>(std::fabs(static_cast<long double>(got) - exact) / ulp);
}

// The widths this CPU runs (rtb_law_lanes_width() is the widest).
std::vector<int> widths_here() {
  std::vector<int> w;
#if RTB_LAW_LANES
  if (rtb_law_lanes_width() >= 4) w.push_back(4);
  if (rtb_law_lanes_width() >= 8) w.push_back(8);
#endif
  return w;
}

#if RTB_LAW_LANES
void kernels(int width, int n, const double *x, double *e, double *l) {
  if (width == 8) rtb_law_kernels_w8(n, x, e, l);
  else rtb_law_kernels_w4(n, x, e, l);
}
void sweep_at(int width, const rtb_law &L, int n, const bool *steep, double *f, double *v,
              double *D) {
  if (width == 8) rtb_law_sweep_w8(&L, n, steep, f, v, D);
  else rtb_law_sweep_w4(&L, n, steep, f, v, D);
}
#endif

TEST(LawLanes, ExpAndLogWithinAnUlp) {
  if (widths_here().empty())
    GTEST_SKIP() << "no AVX2 on this CPU (or not an x86-64 GCC build): the law uses libm";
#if RTB_LAW_LANES
  for (int width : widths_here()) {
    std::mt19937_64 rng(20130601);
    std::uniform_real_distribution<double> wide(-707.0, 708.0), near0(-1.0, 1.0),
        expo(-700.0, 700.0);
    const int n = 4096;
    std::vector<double> x(n), e(n), l(n);
    double worst_exp = 0.0, worst_log = 0.0;
    for (int round = 0; round < 50; ++round) {
      for (int k = 0; k < n; ++k) x[k] = k % 2 ? wide(rng) : near0(rng);
      kernels(width, n, x.data(), e.data(), l.data());
      for (int k = 0; k < n; ++k)
        worst_exp = std::fmax(worst_exp, ulps(e[k], std::exp(static_cast<long double>(x[k]))));
      // ln over the normal range; a third of the points near 1, where ln u is small
      for (int k = 0; k < n; ++k)
        x[k] = k % 3 ? std::exp(expo(rng)) : 1.0 + 0.5 * near0(rng);
      x[0] = DBL_MIN, x[1] = DBL_MAX, x[2] = 1.0, x[3] = std::nextafter(1.0, 2.0);
      kernels(width, n, x.data(), e.data(), l.data());
      for (int k = 0; k < n; ++k)
        if (x[k] != 1.0)
          worst_log = std::fmax(worst_log, ulps(l[k], std::log(static_cast<long double>(x[k]))));
        else EXPECT_EQ(l[k], 0.0);
    }
    EXPECT_LT(worst_exp, 1.0) << "width " << width;
    EXPECT_LT(worst_log, 1.0) << "width " << width;
    EXPECT_GT(worst_exp, 0.3) << "width " << width;  // the reference resolves below an ulp
  }
#endif
}

// The scalar law (dashpot_law.h, libm) on cells 0..n-1, as the sweep would.
void scalar_sweep(const rtb_law &L, int n, const bool *steep, double *f, double *v, double *D) {
  for (int k = 0; k < n; ++k) rtb_law_cell(&L, k, steep, f, v, D);
}

// |a - b| within tol relative to the larger (exactly equal for 0 and inf;
// both NaN, as the slope at an infinite input is in either path).
::testing::AssertionResult close(double a, double b, double tol) {
  if (a == b || (std::isnan(a) && std::isnan(b))) return ::testing::AssertionSuccess();
  const double scale = std::fmax(std::fabs(a), std::fabs(b));
  if (std::isfinite(a) && std::isfinite(b) && std::fabs(a - b) <= tol * scale)
    return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << a << " vs " << b << " (tol " << tol << ")";
}

TEST(LawLanes, SweepMatchesTheScalarLawForEveryCellCount) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> lg(-12.0, 12.0), unit(0.0, 1.0);
  for (int n = 1; n <= RTB_MAX_CELLS; ++n) {
    for (int round = 0; round < 100; ++round) {
      rtb_law L;
      const double alpha = std::exp(std::log(0.02) * unit(rng));  // 0.02 .. 1
      rtb_law_init(&L, std::exp(lg(rng)), alpha, 0.0, round % 2 ? 0.6 * unit(rng) - 0.3 : 0.0);
      bool steep[RTB_MAX_CELLS];
      double f[RTB_MAX_CELLS], v[RTB_MAX_CELLS], D[RTB_MAX_CELLS];
      double fs[RTB_MAX_CELLS], vs[RTB_MAX_CELLS], Ds[RTB_MAX_CELLS];
      double fin[RTB_MAX_CELLS], vin[RTB_MAX_CELLS];
      for (int k = 0; k < RTB_MAX_CELLS; ++k) {  // past n: must be left as they are
        steep[k] = unit(rng) < 0.5;
        const double sign = unit(rng) < 0.5 ? -1.0 : 1.0;
        const double mag = unit(rng) < 0.05 ? 0.0 : std::exp(lg(rng));
        fs[k] = f[k] = steep[k] ? 99.0 : sign * mag;
        vs[k] = v[k] = steep[k] ? sign * mag : 99.0;
        Ds[k] = D[k] = -1.0;
        fin[k] = f[k], vin[k] = v[k];
      }
      rtb_law_sweep_lanes(&L, n, steep, f, v, D);
      scalar_sweep(L, n, steep, fs, vs, Ds);
#if RTB_LAW_LANES
      for (int width : widths_here()) {  // every width gives the dispatch's bits
        double fw[RTB_MAX_CELLS], vw[RTB_MAX_CELLS], Dw[RTB_MAX_CELLS];
        std::copy(fs, fs + RTB_MAX_CELLS, fw);
        std::copy(vs, vs + RTB_MAX_CELLS, vw);
        std::fill(Dw, Dw + RTB_MAX_CELLS, -1.0);
        for (int k = 0; k < n; ++k) (steep[k] ? vw[k] : fw[k]) = steep[k] ? vin[k] : fin[k];
        sweep_at(width, L, n, steep, fw, vw, Dw);
        for (int k = 0; k < RTB_MAX_CELLS; ++k) {
          ASSERT_EQ(std::memcmp(&fw[k], &f[k], sizeof(double)), 0) << "width " << width << " " << k;
          ASSERT_EQ(std::memcmp(&vw[k], &v[k], sizeof(double)), 0) << "width " << width << " " << k;
          ASSERT_EQ(std::memcmp(&Dw[k], &D[k], sizeof(double)), 0) << "width " << width << " " << k;
        }
      }
#endif
      for (int k = 0; k < RTB_MAX_CELLS; ++k) {
        // out = exp(c ln u): 2 |c ln u| eps apart at most (half an ulp of ln u
        // and of the product each way), plus an ulp of each exp
        const double u = steep[k] ? std::fabs(v[k]) : std::fabs(f[k]) / L.C0;
        const double c = steep[k] ? alpha : 1.0 / alpha;
        const double tol = (2.0 * std::fabs(std::log(u) * c) + 6.0) * DBL_EPSILON;
        const double tol_v = std::isfinite(tol) ? tol : 0.0;
        ASSERT_TRUE(close(f[k], fs[k], tol_v)) << "n " << n << " cell " << k;
        ASSERT_TRUE(close(v[k], vs[k], tol_v)) << "n " << n << " cell " << k;
        ASSERT_TRUE(close(D[k], Ds[k], tol_v + 2 * DBL_EPSILON)) << "n " << n << " cell " << k;
        if (k >= n) ASSERT_EQ(D[k], -1.0) << "cells past n are not written";
      }
    }
  }
}

TEST(LawLanes, EdgesTakeTheScalarLaw) {
  // one edge cell among ordinary ones, so that it shares a vector with lanes
  // on the fast path: zero, subnormal, tiny and huge inputs, overflow and
  // underflow of the power, infinity
  const double edges[] = {0.0, -0.0, 4.9e-324, -1e-310, DBL_MIN, 1e-300, 1e300, -DBL_MAX, INFINITY};
  const double alphas[] = {0.004, 0.3, 1.0};
  for (double alpha : alphas)
    for (double x : edges)
      for (int steep_edge = 0; steep_edge < 2; ++steep_edge) {
        rtb_law L;
        rtb_law_init(&L, 2.0, alpha, 0.0, 0.1);
        bool steep[RTB_MAX_CELLS] = {true, steep_edge != 0, false, true, false};
        double f[RTB_MAX_CELLS] = {0.0, x, 1.5, 0.0, -0.25};
        double v[RTB_MAX_CELLS] = {0.3, x, 0.0, -2.0, 0.0};
        double D[RTB_MAX_CELLS], fs[RTB_MAX_CELLS], vs[RTB_MAX_CELLS], Ds[RTB_MAX_CELLS];
        std::copy(f, f + RTB_MAX_CELLS, fs);
        std::copy(v, v + RTB_MAX_CELLS, vs);
        rtb_law_sweep_lanes(&L, 5, steep, f, v, D);
        scalar_sweep(L, 5, steep, fs, vs, Ds);
#if RTB_LAW_LANES
        for (int width : widths_here()) {
          double fw[RTB_MAX_CELLS] = {0.0, x, 1.5, 0.0, -0.25};
          double vw[RTB_MAX_CELLS] = {0.3, x, 0.0, -2.0, 0.0}, Dw[RTB_MAX_CELLS];
          sweep_at(width, L, 5, steep, fw, vw, Dw);
          for (int k = 0; k < 5; ++k)
            EXPECT_TRUE(fw[k] == f[k] && vw[k] == v[k] &&
                        (Dw[k] == D[k] || (std::isnan(Dw[k]) && std::isnan(D[k]))))
                << "width " << width << " " << x << " cell " << k;
        }
#endif
        for (int k = 0; k < 5; ++k) {
          EXPECT_TRUE(close(f[k], fs[k], 1e-12)) << x << " alpha " << alpha << " cell " << k;
          EXPECT_TRUE(close(v[k], vs[k], 1e-12)) << x << " alpha " << alpha << " cell " << k;
          EXPECT_TRUE(close(D[k], Ds[k], 1e-12)) << x << " alpha " << alpha << " cell " << k;
          EXPECT_EQ(std::signbit(f[k]), std::signbit(fs[k])) << "x " << x << " cell " << k;
          EXPECT_EQ(std::signbit(v[k]), std::signbit(vs[k])) << "x " << x << " cell " << k;
        }
      }
}

// A host may trap FE_INVALID / FE_DIVBYZERO. The lanes past n hold whatever
// the arrays' capacity holds (NaN here) and cells at rest give 0 / 0 in a
// naive slope: neither may raise a flag the scalar law does not raise.
TEST(LawLanes, RaisesNoFloatingPointExceptionOfItsOwn) {
  for (int n : {1, 3, 5, 8, 11, 15, 32}) {
    rtb_law L;
    rtb_law_init(&L, 1.3, 0.4, 0.0, 0.2);
    bool steep[RTB_MAX_CELLS];
    double f[RTB_MAX_CELLS], v[RTB_MAX_CELLS], D[RTB_MAX_CELLS];
    for (int k = 0; k < RTB_MAX_CELLS; ++k) {
      steep[k] = k % 2 == 0;
      f[k] = v[k] = k >= n ? std::nan("") : (k % 3 == 0 ? 0.0 : (k % 2 ? -0.7 : 2.5));
    }
    std::feclearexcept(FE_ALL_EXCEPT);
    rtb_law_sweep_lanes(&L, n, steep, f, v, D);
    EXPECT_FALSE(std::fetestexcept(FE_INVALID)) << "n " << n;
    EXPECT_FALSE(std::fetestexcept(FE_DIVBYZERO)) << "n " << n;
    for (int k = 0; k < n; ++k) EXPECT_TRUE(std::isfinite(f[k]) && std::isfinite(D[k])) << k;
  }
}

}  // namespace
