/* law_lanes_kernel.h -- the law sweep's vector kernels, written once for
 * any lane count and compiled per instruction set: law_lanes_avx2.cpp (4
 * doubles per 256-bit vector) and law_lanes_avx512.cpp (8 per 512-bit
 * vector) each set the target and
 *   LANES_W        lanes per vector (4 or 8),
 *   LANES_SWEEP    the name of the sweep's entry point,
 *   LANES_KERNELS  the name of the test entry point,
 * then include this file. GCC vector extensions, so the code reads as
 * scalar arithmetic; every operation is an IEEE operation on each lane, in
 * the order written, so both widths give the same bits (tests/
 * law_lanes_test.cpp checks it where the CPU has both). No FMA: the two
 * files turn contraction off themselves, whatever the build flags.
 */
#include <float.h>
#include <math.h>
#include <string.h>

#include "law_lanes.h"

namespace {

typedef double vd __attribute__((vector_size(8 * LANES_W)));
typedef unsigned long long vu __attribute__((vector_size(8 * LANES_W)));
typedef long long vi __attribute__((vector_size(8 * LANES_W)));

inline vd splat(double x) { return vd{} + x; }
inline vu splat_u(unsigned long long x) { return vu{} + x; }
inline vu bits_of(vd x) { vu b; memcpy(&b, &x, sizeof b); return b; }
inline vd double_of(vu b) { vd x; memcpy(&x, &b, sizeof x); return x; }
/* where mask (all ones / zero per lane): a, else b */
inline vd select(vi mask, vd a, vd b) { return mask ? a : b; }
inline vd abs_lanes(vd x) { return double_of(bits_of(x) & splat_u(0x7fffffffffffffffULL)); }

/* ln 2 split so that k ln2_hi is exact for |k| < 2^20 (ln2_hi has 32
 * trailing zero bits) and ln2_hi + ln2_lo = ln 2 to ~1e-27. */
const double LN2_HI = 0x1.62e42fee00000p-1, LN2_LO = 0x1.a39ef35793c76p-33;
const double SHIFT = 0x1.8p52;  /* x + SHIFT rounds x to an integer in the low bits */

/* exp(x) for -707 <= x <= 708: x = k ln2 + r, |r| <= ln2 / 2, and exp(r)
 * by its Taylor series to r^13 (truncation < 5e-18 relative; the series
 * economized to degree 11 measured 1.02 ulp, this one 0.97), the tail
 * grouped in pairs (Estrin) so that its terms do not wait on each other;
 * 2^k is put into the exponent field directly (k + 1023 in 1..2046 there). */
inline vd exp_lanes(vd x) {
  const vd t = x * splat(0x1.71547652b82fep0) + splat(SHIFT);  /* x / ln2 rounded, + SHIFT */
  const vd kd = t - splat(SHIFT);
  const vd r = (x - kd * splat(LN2_HI)) - kd * splat(LN2_LO);
  const vd r2 = r * r, r4 = r2 * r2;
  const vd a = splat(1.0 / 2) + r * splat(1.0 / 6), b = splat(1.0 / 24) + r * splat(1.0 / 120);
  const vd c = splat(1.0 / 720) + r * splat(1.0 / 5040);
  const vd d = splat(1.0 / 40320) + r * splat(1.0 / 362880);
  const vd e = splat(1.0 / 3628800) + r * splat(1.0 / 39916800);
  const vd g = splat(1.0 / 479001600) + r * splat(1.0 / 6227020800.0);
  const vd q = (a + b * r2) + r4 * ((c + d * r2) + r4 * (e + g * r2));
  const vd p = splat(1.0) + (r + r2 * q);                   /* exp(r) */
  const vu k = bits_of(t) - bits_of(splat(SHIFT));          /* k, two's complement */
  return p * double_of((k + splat_u(1023)) << 52);           /* p 2^k */
}

/* ln(u) for positive normal finite u: u = 2^e m, m in [sqrt(1/2), sqrt(2)),
 * f = m - 1 (exact), s = f / (2 + f), ln m = 2 atanh(s) written as
 * f - (f^2/2 - s (f^2/2 + R)), R = z P(z), z = s^2 <= 0.02944, P of degree
 * 6 (sum_j 2 z^j / (2j + 3) to z^15, economized on [0, 0.0295] by
 * Chebyshev polynomials in exact rational arithmetic: truncation of R
 * 9e-18; coefficients rounded to double), so that the leading term is the
 * exact f and the rounding of the rest stays below an ulp. */
inline vd log_lanes(vd u) {
  const vu b = bits_of(u);
  vd m = double_of((b & splat_u(0x000fffffffffffffULL)) | splat_u(0x3ff0000000000000ULL));
  const vi big = (vi)(m > splat(0x1.6a09e667f3bcdp0));     /* m > sqrt 2: halve it */
  m = select(big, m * splat(0.5), m);
  const vu ex = (b >> 52) - (vu)big;                       /* biased exponent, +1 where halved */
  const vd e = double_of(ex | splat_u(0x4330000000000000ULL)) - splat(0x1p52 + 1023.0);
  const vd f = m - splat(1.0);
  const vd s = f / (splat(2.0) + f);
  const vd z = s * s, z2 = z * z, z4 = z2 * z2;
  const vd a = splat(0x1.5555555555558p-1) + z * splat(0x1.999999999519ap-2);
  const vd bb = splat(0x1.2492492e143e6p-2) + z * splat(0x1.c71c62ba3869bp-3);
  const vd c = splat(0x1.7462c0aff40b0p-3) + z * splat(0x1.39fcd91739d1bp-3);
  const vd R = z * ((a + bb * z2) + z4 * (c + z2 * splat(0x1.2b6ada4e6ca7fp-3)));
  const vd hfsq = splat(0.5) * f * f;
  return e * splat(LN2_HI) + (f - (hfsq - (s * (hfsq + R) + e * splat(LN2_LO))));
}

/* The law of eq. (1) on LANES_W cells, the same expressions as
 * rtb_law_eval_v and rtb_law_eval_pow_f: the input x (v where steep, else
 * f), its level C0s = C0 (1 +- asym) by its sign, u = |v| or |f| / C0s, m =
 * u^c with c = alpha or 1/alpha; the output C0s m or m with x's sign (0 at
 * x = 0) and D = |v| / (alpha |f|) at the new pair (0 where the output is
 * 0). ok: the lanes whose power stayed in the fast ranges (or is 0^c). */
struct Block {
  vd f, v, D;
  vi ok;
};
inline Block law_block(const rtb_law *L, int w, const bool *steep, const double *f,
                       const double *v) {
  /* Lanes w.. read the arrays' unused capacity; they compute on 1.0, not on
   * what lies there, and their results are dropped. No lane meets 0 / 0 or a
   * NaN it did not bring, so a host that traps FE_INVALID or FE_DIVBYZERO
   * sees no more than from the scalar law (LawLanes.RaisesNoFloatingPoint-
   * ExceptionOfItsOwn). */
  vd F, V;
  memcpy(&F, f, sizeof F);
  memcpy(&V, v, sizeof V);
  vi S = {}, in = {};
  for (int j = 0; j < LANES_W && j < w; ++j) S[j] = steep[j] ? -1 : 0, in[j] = -1;
  const vd X = select(in, select(S, V, F), splat(1.0));
  const vi neg = X < splat(0.0), pos = X > splat(0.0);
  const vd a = abs_lanes(X);
  const vi zero = a == splat(0.0);
  const vd C0s = select(neg, splat(L->C0m), splat(L->C0p));
  const vd Ua = select(S, a, a * select(neg, splat(L->inv_C0m), splat(L->inv_C0p)));
  const vd U = select(zero, splat(1.0), Ua);            /* ln 1 = 0 where u = 0 */
  const vd E = log_lanes(U) * select(S, splat(L->alpha), splat(L->inv_alpha));
  const vd M = select(zero, splat(0.0), exp_lanes(E));  /* 0^c = 0 */
  const vd out = select(S, C0s * M, M);                 /* |f| where steep, else |v| */
  const vi moving = out > splat(0.0);
  const vd den = select(moving, splat(L->alpha) * select(S, out, a), splat(1.0));
  const vd Dl = select(S, a, M) / den;
  const vd Y = select(pos, out, select(neg, -out, splat(0.0)));
  Block b;
  b.f = select(S, Y, F);
  b.v = select(S, V, Y);
  b.D = select(moving, Dl, splat(0.0));
  b.ok = zero | ((U >= splat(DBL_MIN)) & (U <= splat(DBL_MAX)) & (E >= splat(-707.0)) &
                 (E <= splat(708.0)));
  return b;
}

/* Writes block b to cells k .. min(k + LANES_W, n) - 1; returns the AND of
 * its fast flags. */
inline long long store_block(const Block &b, int k, int n, double *f, double *v, double *D,
                             long long *fast) {
  const int w = n - k < LANES_W ? n - k : LANES_W;
  if (w == LANES_W) {
    memcpy(f + k, &b.f, sizeof b.f);
    memcpy(v + k, &b.v, sizeof b.v);
    memcpy(D + k, &b.D, sizeof b.D);
    memcpy(fast + k, &b.ok, sizeof b.ok);
  } else {
    for (int j = 0; j < w; ++j)
      f[k + j] = b.f[j], v[k + j] = b.v[j], D[k + j] = b.D[j], fast[k + j] = b.ok[j];
  }
  long long all = -1;
  for (int j = 0; j < w; ++j) all &= b.ok[j];
  return all;
}

static_assert(RTB_MAX_CELLS % LANES_W == 0, "a block never reads past the arrays' capacity");

}  // namespace

/* Two blocks per iteration, whose instruction chains the CPU overlaps;
 * cells outside the fast ranges (rare) are redone by the scalar law. */
extern "C" void LANES_SWEEP(const rtb_law *L, int n, const bool *steep, double *f, double *v,
                            double *D) {
  long long fast[RTB_MAX_CELLS];
  long long all_fast = -1;
  for (int k = 0; k < n; k += 2 * LANES_W) {
    const Block b0 = law_block(L, n - k, steep + k, f + k, v + k);
    if (n - k > LANES_W) {
      const int k1 = k + LANES_W;
      const Block b1 = law_block(L, n - k1, steep + k1, f + k1, v + k1);
      all_fast &= store_block(b1, k1, n, f, v, D, fast);
    }
    all_fast &= store_block(b0, k, n, f, v, D, fast);
  }
  if (all_fast) return;
  for (int k = 0; k < n; ++k)
    if (!fast[k]) rtb_law_cell(L, k, steep, f, v, D);
}

/* exp_lanes and log_lanes themselves, for tests/law_lanes_test.cpp. */
extern "C" void LANES_KERNELS(int n, const double *x, double *exp_x, double *log_x) {
  for (int k = 0; k < n; k += LANES_W) {
    vd X = splat(1.0);
    for (int j = 0; j < LANES_W && k + j < n; ++j) X[j] = x[k + j];
    const vd E = exp_lanes(X), L = log_lanes(X);
    for (int j = 0; j < LANES_W && k + j < n; ++j) { exp_x[k + j] = E[j]; log_x[k + j] = L[j]; }
  }
}
