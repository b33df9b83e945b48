/* law_lanes.h -- the unsmoothed law of eq. (1) for all cells of a stage
 * iterate at once (law_lanes.cpp; issue #11).
 */
#ifndef RTB_LAW_LANES_H
#define RTB_LAW_LANES_H

#include <stdbool.h>

#include "dashpot_law.h"
#include "rtb_scalar.h"

/* The vector kernels exist for x86-64 GCC builds in double precision;
 * elsewhere the sweep is the scalar law. */
#if defined(__GNUC__) && !defined(__clang__) && defined(__x86_64__) && !defined(RTB_SINGLE)
#define RTB_LAW_LANES 1
#else
#define RTB_LAW_LANES 0
#endif

#ifdef __cplusplus
extern "C" {
#endif

/* One law sweep of eq. (1) (L->s == 0) over cells 0..n-1: where steep[k],
 * f[k] = psi(v[k]) (rtb_law_eval_v), elsewhere v[k] = phi(f[k])
 * (rtb_law_eval_pow_f); D[k] = phi'(f[k]) at the new pair either way. The
 * arrays hold RTB_MAX_CELLS values; n <= RTB_MAX_CELLS. */
void rtb_law_sweep_lanes(const rtb_law *L, int n, const bool *steep, rtb_real *f, rtb_real *v,
                         rtb_real *D);

/* Lanes per vector that rtb_law_sweep_lanes uses on this CPU: 8 (AVX-512),
 * 4 (AVX2) or 1 (the scalar law). */
int rtb_law_lanes_width(void);

#if RTB_LAW_LANES
/* The kernels of one width (law_lanes_avx2.cpp, law_lanes_avx512.cpp), for
 * the dispatch and for tests: call only where the CPU has the instruction
 * set (rtb_law_lanes_width() >= the width). *_kernels: exp_x = exp(x) and
 * log_x = ln(x), valid for -707 <= x <= 708 and for positive normal x. */
void rtb_law_sweep_w4(const rtb_law *L, int n, const bool *steep, double *f, double *v, double *D);
void rtb_law_sweep_w8(const rtb_law *L, int n, const bool *steep, double *f, double *v, double *D);
void rtb_law_kernels_w4(int n, const double *x, double *exp_x, double *log_x);
void rtb_law_kernels_w8(int n, const double *x, double *exp_x, double *log_x);
#endif

#ifdef __cplusplus
}
#endif

/* The scalar law (libm) on cell k: the reference of the kernels and their
 * fallback outside the fast ranges. */
static inline void rtb_law_cell(const rtb_law *L, int k, const bool *steep, rtb_real *f,
                                rtb_real *v, rtb_real *D) {
  if (steep[k]) f[k] = rtb_law_eval_v(L, v[k], &D[k]);
  else v[k] = rtb_law_eval_pow_f(L, f[k], &D[k]);
}

#endif
