/* law_lanes.cpp -- the unsmoothed law of eq. (1) for all cells of a stage
 * iterate at once (issue #11). A law sweep is one power per cell, |f| = C0
 * |v|^alpha on the steep cells and |v| = (|f| / C0)^(1/alpha) on the others,
 * N independent evaluations of exp(c ln u) and a division for the slope.
 *
 * Why not libm alone: glibc's exp and log are a call each per cell, with the
 * stage solver's values spilled around every call. On an x86-64 CPU with AVX
 * (checked at run time, so one binary serves every x86-64 host), four cells
 * go through one branch-free polynomial evaluation in 256-bit registers
 * (docs/benchmarks.md, session 20). The same code in 128-bit SSE2 registers
 * is slower than glibc, so CPUs without AVX, other architectures, other
 * compilers and the single-precision build keep the scalar law of
 * dashpot_law.h. Accuracy: under 1 ulp for exp and for ln over their fast
 * ranges (tests/law_lanes_test.cpp measures both against long double);
 * lanes outside them (0, subnormal or non-finite u, |c ln u| beyond ~707)
 * take the scalar law. The two paths agree to rounding (an ulp of each exp
 * and ln), not to the bit; every tolerance of the stepper is orders of
 * magnitude above that.
 */
#include "law_lanes.h"

#include <float.h>
#include <math.h>
#include <string.h>

#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(RTB_SINGLE)
#define RTB_LAW_LANES_AVX 1
#else
#define RTB_LAW_LANES_AVX 0
#endif

namespace {

/* The scalar law of dashpot_law.h for cell k (libm). */
void law_cell(const rtb_law *L, int k, const bool *steep, rtb_real *f, rtb_real *v, rtb_real *D) {
  if (steep[k]) f[k] = rtb_law_eval_v(L, v[k], &D[k]);
  else v[k] = rtb_law_eval_pow_f(L, f[k], &D[k]);
}

#if RTB_LAW_LANES_AVX

/* Every helper taking or returning a vector is an AVX function inlined into
 * the AVX callers: compiled without AVX it would pass a 256-bit value
 * differently (GCC's -Wpsabi). */
#define LANES_INLINE inline __attribute__((always_inline, target("avx")))

typedef double v4d __attribute__((vector_size(32)));
typedef unsigned long long v4u __attribute__((vector_size(32)));
typedef long long v4i __attribute__((vector_size(32)));

LANES_INLINE v4d splat(double x) { return (v4d){x, x, x, x}; }
LANES_INLINE v4u splat_u(unsigned long long x) { return (v4u){x, x, x, x}; }
LANES_INLINE v4u bits_of(v4d x) { v4u b; memcpy(&b, &x, sizeof b); return b; }
LANES_INLINE v4d double_of(v4u b) { v4d x; memcpy(&x, &b, sizeof x); return x; }
/* where mask (all ones / zero per lane): a, else b */
LANES_INLINE v4d select(v4i mask, v4d a, v4d b) { return mask ? a : b; }
LANES_INLINE v4d abs_lanes(v4d x) {
  return double_of(bits_of(x) & splat_u(0x7fffffffffffffffULL));
}

/* ln 2 split so that k ln2_hi is exact for |k| < 2^20 (ln2_hi has 32
 * trailing zero bits) and ln2_hi + ln2_lo = ln 2 to ~1e-27. */
const double LN2_HI = 0x1.62e42fee00000p-1, LN2_LO = 0x1.a39ef35793c76p-33;
const double SHIFT = 0x1.8p52;  /* x + SHIFT rounds x to an integer in the low bits */

/* exp(x) for -707 <= x <= 708: x = k ln2 + r, |r| <= ln2 / 2, and exp(r)
 * by its Taylor series to r^13 (truncation < 5e-18 relative; the series
 * economized to degree 11 measured 1.02 ulp, this one 0.97), the tail
 * grouped in pairs (Estrin) so that its terms do not wait on each other;
 * 2^k is put into the exponent field directly (k + 1023 in 1..2046 there). */
LANES_INLINE v4d exp_lanes(v4d x) {
  const v4d t = x * splat(0x1.71547652b82fep0) + splat(SHIFT);  /* x / ln2 rounded, + SHIFT */
  const v4d kd = t - splat(SHIFT);
  const v4d r = (x - kd * splat(LN2_HI)) - kd * splat(LN2_LO);
  const v4d r2 = r * r, r4 = r2 * r2;
  const v4d a = splat(1.0 / 2) + r * splat(1.0 / 6), b = splat(1.0 / 24) + r * splat(1.0 / 120);
  const v4d c = splat(1.0 / 720) + r * splat(1.0 / 5040);
  const v4d d = splat(1.0 / 40320) + r * splat(1.0 / 362880);
  const v4d e = splat(1.0 / 3628800) + r * splat(1.0 / 39916800);
  const v4d g = splat(1.0 / 479001600) + r * splat(1.0 / 6227020800.0);
  const v4d q = (a + b * r2) + r4 * ((c + d * r2) + r4 * (e + g * r2));
  const v4d p = splat(1.0) + (r + r2 * q);                   /* exp(r) */
  const v4u k = bits_of(t) - bits_of(splat(SHIFT));          /* k, two's complement */
  return p * double_of((k + splat_u(1023)) << 52);           /* p 2^k */
}

/* ln(u) for positive normal finite u: u = 2^e m, m in [sqrt(1/2), sqrt(2)),
 * f = m - 1 (exact), s = f / (2 + f), ln m = 2 atanh(s) written as
 * f - (f^2/2 - s (f^2/2 + R)), R = z P(z), z = s^2 <= 0.02944, P of degree
 * 6 (sum_j 2 z^j / (2j + 3) to z^15, economized on [0, 0.0295] by
 * Chebyshev polynomials in exact rational arithmetic: truncation of R
 * 9e-18; coefficients rounded to double), so that the leading term is the
 * exact f and the rounding of the rest stays below an ulp. */
LANES_INLINE v4d log_lanes(v4d u) {
  const v4u b = bits_of(u);
  v4d m = double_of((b & splat_u(0x000fffffffffffffULL)) | splat_u(0x3ff0000000000000ULL));
  const v4i big = (v4i)(m > splat(0x1.6a09e667f3bcdp0));     /* m > sqrt 2: halve it */
  m = select(big, m * splat(0.5), m);
  const v4u ex = (b >> 52) - (v4u)big;                       /* biased exponent, +1 where halved */
  const v4d e = double_of(ex | splat_u(0x4330000000000000ULL)) - splat(0x1p52 + 1023.0);
  const v4d f = m - splat(1.0);
  const v4d s = f / (splat(2.0) + f);
  const v4d z = s * s, z2 = z * z, z4 = z2 * z2;
  const v4d a = splat(0x1.5555555555558p-1) + z * splat(0x1.999999999519ap-2);
  const v4d bb = splat(0x1.2492492e143e6p-2) + z * splat(0x1.c71c62ba3869bp-3);
  const v4d c = splat(0x1.7462c0aff40b0p-3) + z * splat(0x1.39fcd91739d1bp-3);
  const v4d R = z * ((a + bb * z2) + z4 * (c + z2 * splat(0x1.2b6ada4e6ca7fp-3)));
  const v4d hfsq = splat(0.5) * f * f;
  return e * splat(LN2_HI) + (f - (hfsq - (s * (hfsq + R) + e * splat(LN2_LO))));
}

/* The law of eq. (1) on four cells, the same expressions as rtb_law_eval_v
 * and rtb_law_eval_pow_f: the input x (v where steep, else f), its level
 * C0s = C0 (1 +- asym) by its sign, u = |v| or |f| / C0s, m = u^c with c =
 * alpha or 1/alpha; the output C0s m or m with x's sign (0 at x = 0) and D =
 * |v| / (alpha |f|) at the new pair (0 where the output is 0). *ok: the
 * lanes whose power stayed in the fast ranges. */
struct Block {
  v4d f, v, D;
  v4i ok;
};
LANES_INLINE Block law_block(const rtb_law *L, int w, const bool *steep, const double *f,
                             const double *v) {
  v4d F, V;  /* lanes w.. read the arrays' unused capacity; their results are dropped */
  memcpy(&F, f, sizeof F);
  memcpy(&V, v, sizeof V);
  const v4i S = {-(long long)steep[0], w > 1 ? -(long long)steep[1] : 0,
                 w > 2 ? -(long long)steep[2] : 0, w > 3 ? -(long long)steep[3] : 0};
  const v4d X = select(S, V, F);
  const v4i neg = (v4i)(X < splat(0.0)), pos = (v4i)(X > splat(0.0));
  const v4d a = abs_lanes(X);
  const v4d C0s = select(neg, splat(L->C0m), splat(L->C0p));
  const v4d U = select(S, a, a * select(neg, splat(L->inv_C0m), splat(L->inv_C0p)));
  const v4d E = log_lanes(U) * select(S, splat(L->alpha), splat(L->inv_alpha));
  const v4i zero = (v4i)(a == splat(0.0));
  const v4d M = select(zero, splat(0.0), exp_lanes(E));  /* 0^c = 0 */
  const v4d out = select(S, C0s * M, M);                 /* |f| where steep, else |v| */
  const v4d Dl = select(S, a, M) / (splat(L->alpha) * select(S, out, a));
  const v4d Y = select(pos, out, select(neg, -out, splat(0.0)));
  Block b;
  b.f = select(S, Y, F);
  b.v = select(S, V, Y);
  b.D = select((v4i)(out > splat(0.0)), Dl, splat(0.0));
  b.ok = zero | ((U >= splat(DBL_MIN)) & (U <= splat(DBL_MAX)) & (E >= splat(-707.0)) &
                 (E <= splat(708.0)));
  return b;
}

/* Writes block b to cells k .. min(k + 4, n) - 1; returns the AND of its
 * fast flags. */
LANES_INLINE long long store_block(const Block &b, int k, int n, double *f, double *v, double *D,
                                   long long *fast) {
  if (n - k >= 4) {
    memcpy(f + k, &b.f, sizeof b.f);
    memcpy(v + k, &b.v, sizeof b.v);
    memcpy(D + k, &b.D, sizeof b.D);
    memcpy(fast + k, &b.ok, sizeof b.ok);
    return b.ok[0] & b.ok[1] & b.ok[2] & b.ok[3];
  }
  long long all = -1;
  for (int j = 0; j < n - k; ++j) {
    f[k + j] = b.f[j], v[k + j] = b.v[j], D[k + j] = b.D[j], fast[k + j] = b.ok[j];
    all &= b.ok[j];
  }
  return all;
}

/* Eight cells per iteration, two independent blocks whose instruction
 * chains the CPU overlaps; cells outside the fast ranges (rare) are redone
 * by the scalar law. */
__attribute__((target("avx"))) void sweep_by_lanes(const rtb_law *L, int n, const bool *steep,
                                                   double *f, double *v, double *D) {
  long long fast[RTB_MAX_CELLS];
  long long all_fast = -1;
  for (int k = 0; k < n; k += 8) {
    const Block b0 = law_block(L, n - k, steep + k, f + k, v + k);
    if (n - k > 4) {
      const Block b1 = law_block(L, n - k - 4, steep + k + 4, f + k + 4, v + k + 4);
      all_fast &= store_block(b1, k + 4, n, f, v, D, fast);
    }
    all_fast &= store_block(b0, k, n, f, v, D, fast);
  }
  if (all_fast) return;
  for (int k = 0; k < n; ++k)
    if (!fast[k]) law_cell(L, k, steep, f, v, D);
}

/* exp_lanes and log_lanes themselves, for tests/law_lanes_test.cpp. */
__attribute__((target("avx"))) void kernels_by_lanes(int n, const double *x, double *exp_x,
                                                     double *log_x) {
  for (int k = 0; k < n; k += 4) {
    v4d X = splat(1.0);
    for (int j = 0; j < 4 && k + j < n; ++j) X[j] = x[k + j];
    const v4d E = exp_lanes(X), L = log_lanes(X);
    for (int j = 0; j < 4 && k + j < n; ++j) { exp_x[k + j] = E[j]; log_x[k + j] = L[j]; }
  }
}

#endif /* RTB_LAW_LANES_AVX */
}  // namespace

extern "C" int rtb_law_lanes_kernels(int n, const double *x, double *exp_x, double *log_x) {
#if RTB_LAW_LANES_AVX
  if (__builtin_cpu_supports("avx")) {
    kernels_by_lanes(n, x, exp_x, log_x);
    return 1;
  }
#endif
  (void)n, (void)x, (void)exp_x, (void)log_x;
  return 0;
}

extern "C" void rtb_law_sweep_lanes(const rtb_law *L, int n, const bool *steep, rtb_real *f,
                                    rtb_real *v, rtb_real *D) {
#if RTB_LAW_LANES_AVX
  if (__builtin_cpu_supports("avx")) {
    sweep_by_lanes(L, n, steep, f, v, D);
    return;
  }
#endif
  for (int k = 0; k < n; ++k) law_cell(L, k, steep, f, v, D);
}
