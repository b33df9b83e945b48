/* rtb_internal.h -- the stepper's building blocks, shared with the offline
 * half (its adjoint differentiates exactly these functions). Not part of the
 * real-time public API, but still allocation-free C-compatible code.
 */
#ifndef RTB_INTERNAL_H
#define RTB_INTERNAL_H

#include "../rt_bushing.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One implicit stage of eq. (2) in its dual (dashpot force) form:
 *   y = c + h v,   v = phi(f),   f = b - K y,   b = (b1, 0, ..., 0)
 * i.e.  H(f) = f + h K phi(f) - (b - K c) = 0.
 * phi is the inverse of eq. (1), or of its eq. (14) smoothing when
 * p->smoothing > 0 (dashpot_law.h, rtb_dashpot_*).                        */
typedef struct rtb_stage {
  double h;                    /* stage step length [time] */
  double b1;                   /* Kpa * xb at the stage time [force] */
  double c[RTB_MAX_CELLS];     /* explicit part of the stage [length] */
  double f[RTB_MAX_CELLS];     /* converged dashpot forces [force] */
  double v[RTB_MAX_CELLS];     /* converged cell velocities [length/time] */
  double y[RTB_MAX_CELLS];     /* stage cell DOFs [length] */
  int iterations;
  int converged;
} rtb_stage;

/* Solve one stage with Newton's method (per-DOF variable switching and a line
 * search on the convex dual energy). v_guess warm-starts the velocities.
 * Returns RTB_OK, RTB_NOT_CONVERGED or RTB_ERR_OVERFLOW. */
rtb_status rtb_stage_solve(const rtb_params *p, const rtb_settings *set,
                           const double *v_guess, rtb_stage *st);

/* SDIRK2 coefficient gamma = 1 - 1/sqrt(2) (Alexander 1977). */
#define RTB_SDIRK_GAMMA 0.29289321881345247560
int rtb_integrator_stages(const rtb_params *p);

/* Advance the cell chain from state s (y, xb) to xb_new over dt, storing the
 * stages (st[0..stages-1]). The new DOFs are st[stages-1].y. */
rtb_status rtb_chain_advance(const rtb_params *p, const rtb_settings *set,
                             const rtb_state *s, double xb_new, double dt,
                             rtb_stage st[2]);

/* Rate-independent STS step (section 3.1): exact backward-Euler return map of
 * the friction chain by a primal-dual active-set method. */
rtb_status rtb_sts_solve(const rtb_params *p, const double *y_old, double xb_new,
                         double *y_new, int *iterations, double *dy1_dxb);

/* The full step with all internals exposed; rtb_evaluate is a thin wrapper.
 * `stages` may be NULL. */
rtb_status rtb_step_detailed(const rtb_state *s, const rtb_params *p,
                             const rtb_settings *set, double x, double dt,
                             rtb_state *out, double *force, double *dforce_dx,
                             rtb_stage stages[2]);

/* Validate settings (NULL = defaults) into a usable copy. */
rtb_status rtb_settings_resolve(const rtb_settings *in, rtb_settings *out);

#ifdef __cplusplus
}
#endif
#endif
