/* law_lanes.h -- the unsmoothed law of eq. (1) for all cells of a stage
 * iterate at once (law_lanes.cpp; issue #11).
 */
#ifndef RTB_LAW_LANES_H
#define RTB_LAW_LANES_H

#include <stdbool.h>

#include "dashpot_law.h"
#include "rtb_scalar.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One law sweep of eq. (1) (L->s == 0) over cells 0..n-1: where steep[k],
 * f[k] = psi(v[k]) (rtb_law_eval_v), elsewhere v[k] = phi(f[k])
 * (rtb_law_eval_pow_f); D[k] = phi'(f[k]) at the new pair either way. The
 * arrays hold RTB_MAX_CELLS values; n <= RTB_MAX_CELLS. */
void rtb_law_sweep_lanes(const rtb_law *L, int n, const bool *steep, rtb_real *f, rtb_real *v,
                         rtb_real *D);

/* For tests: exp_x[k] = exp(x[k]) and log_x[k] = ln(x[k]) by the vector
 * kernels, valid for -707 <= x <= 708 and for positive normal x
 * respectively. Returns 0 (nothing written) where the kernels do not run
 * (no AVX, not an x86-64 GCC build, or single precision). */
int rtb_law_lanes_kernels(int n, const double *x, double *exp_x, double *log_x);

#ifdef __cplusplus
}
#endif

#endif
