/* rtb_scalar.h -- the library's scalar and its limits (issue #11).
 *
 * rtb_real (rt_bushing.h) is double, or float when the library and its host
 * are compiled with -DRTB_SINGLE (a microcontroller with a single-precision
 * FPU). Every internal computation uses rtb_real; the single build also
 * compiles with -fsingle-precision-constant (CMakeLists.txt, embedded/), so
 * no literal drags an expression into double. Tolerances follow the
 * scalar's epsilon: the same multiples of it in both builds.
 */
#ifndef RTB_SCALAR_H
#define RTB_SCALAR_H

#include <float.h>

#include "../rt_bushing.h"

#ifdef RTB_SINGLE
#define RTB_REAL_MAX FLT_MAX
#define RTB_REAL_MIN FLT_MIN
#define RTB_REAL_EPSILON FLT_EPSILON
/* default Newton tolerance: ~170 eps (double: 1e-12 = 4.5e3 eps, the value
 * the offline tool also uses, so a generated header run with the defaults
 * reproduces its simulation bit for bit; float cannot resolve below ~100 eps
 * because the residual itself is rounded at that level) */
#define RTB_TOL_DEFAULT 2e-5
#define RTB_TOL_MIN 1e-7           /* ~1 eps */
#define RTB_STS_TIE_REL 5e-5       /* active-set tie band, ~450 eps */
#else
#define RTB_REAL_MAX DBL_MAX
#define RTB_REAL_MIN DBL_MIN
#define RTB_REAL_EPSILON DBL_EPSILON
#define RTB_TOL_DEFAULT 1e-12
#define RTB_TOL_MIN 1e-16
#define RTB_STS_TIE_REL 1e-13
#endif

#endif
