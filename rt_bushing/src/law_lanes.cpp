/* law_lanes.cpp -- the unsmoothed law of eq. (1) for all cells of a stage
 * iterate at once (issue #11). A law sweep is one power per cell, |f| = C0
 * |v|^alpha on the steep cells and |v| = (|f| / C0)^(1/alpha) on the others,
 * N independent evaluations of exp(c ln u) and a division for the slope.
 *
 * Why not libm alone: glibc's exp and log are a call each per cell, with the
 * stage solver's values spilled around every call, and this core runs the
 * step at its dispatch width (docs/benchmarks.md, session 18): fewer
 * instructions is what pays. The kernels (law_lanes_kernel.h) evaluate a
 * vector of cells with one branch-free polynomial exp and ln: 8 per 512-bit
 * vector where the CPU has AVX-512 (F and DQ), 4 per 256-bit vector where it
 * has AVX2, chosen here at run time so that one x86-64 binary serves every
 * host; other CPUs, architectures, compilers and the single-precision build
 * keep the scalar law of dashpot_law.h. Measured (session 20): the same
 * kernels in 128-bit SSE2 registers were slower than glibc, and 256-bit
 * AVX without AVX2 no faster than AVX2.
 *
 * The CPU check reads libgcc's __cpu_model, filled by a constructor before
 * main: a host that steps the element from its own static constructors
 * before that gets the scalar law (the same physics to rounding), never a
 * wrong kernel.
 *
 * AVX-512 on Intel CPUs before Ice Lake lowers the core's clock while
 * 512-bit instructions run; a host that cares builds with
 * -DRTB_LANES_NO_AVX512 and gets the 4-lane kernels there.
 *
 * Accuracy: exp and ln under 1 ulp over their fast ranges
 * (tests/law_lanes_test.cpp, against long double); cells outside them (0
 * is handled in the lanes; subnormal or non-finite u, |c ln u| beyond ~707)
 * take the scalar law. The kernels and the scalar law agree to rounding (an
 * ulp of each exp and ln), not to the bit; every tolerance of the stepper is
 * orders of magnitude above that. Both widths give the same bits.
 */
#include "law_lanes.h"

extern "C" int rtb_law_lanes_width(void) {
#if RTB_LAW_LANES
#ifndef RTB_LANES_NO_AVX512
  if (__builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512dq")) return 8;
#endif
  if (__builtin_cpu_supports("avx2")) return 4;
#endif
  return 1;
}

extern "C" void rtb_law_sweep_lanes(const rtb_law *L, int n, const bool *steep, rtb_real *f,
                                    rtb_real *v, rtb_real *D) {
#if RTB_LAW_LANES
  const int width = rtb_law_lanes_width();
  if (width == 8) return rtb_law_sweep_w8(L, n, steep, f, v, D);
  if (width == 4) return rtb_law_sweep_w4(L, n, steep, f, v, D);
#endif
  for (int k = 0; k < n; ++k) rtb_law_cell(L, k, steep, f, v, D);
}
