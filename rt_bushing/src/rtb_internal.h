/* rtb_internal.h -- the stepper's building blocks, shared with the offline
 * half (its adjoint differentiates exactly these functions). Not part of the
 * real-time public API, but still allocation-free C-compatible code.
 */
#ifndef RTB_INTERNAL_H
#define RTB_INTERNAL_H

#include "rtb_scalar.h"

#ifdef __cplusplus
extern "C" {
#endif

/* One implicit stage of eq. (2) in its dual (dashpot force) form:
 *   y = c + h v,   v = phi(f),   f = b - K y,   b = (b1, 0, ..., 0)
 * i.e.  H(f) = f + h K phi(f) - (b - K c) = 0.
 * phi is the inverse of eq. (1), or of its eq. (14) smoothing when
 * p->smoothing > 0 (dashpot_law.h, rtb_dashpot_*).                        */
typedef struct rtb_stage {
  rtb_real h;                    /* stage step length [time] */
  rtb_real b1;                   /* Kpa * xb at the stage time [force] */
  rtb_real c[RTB_MAX_CELLS];     /* explicit part of the stage [length] */
  rtb_real f[RTB_MAX_CELLS];     /* converged dashpot forces [force] */
  rtb_real v[RTB_MAX_CELLS];     /* converged cell velocities [length/time] */
  rtb_real y[RTB_MAX_CELLS];     /* stage cell DOFs [length] */
  rtb_real D[RTB_MAX_CELLS];     /* phi'(f) at the returned pair [length/(force time)] */
  rtb_real C[RTB_MAX_CELLS];     /* psi''/psi' there [1/(length/time)], if have_C */
  int have_C;                    /* C set (eq. (14) smoothing only) */
  int iterations;
  int backtracks;              /* line-search halvings over all iterations */
  int converged;
  rtb_real residual;           /* final |H|_inf / scale (relative residual) */
} rtb_stage;

/* Solve one stage with Newton's method (per-DOF variable switching and a line
 * search on the residual norm). (f0, v0), both or neither NULL: a start pair
 * on the dashpot curve (previous solution); D0 (may be NULL: computed from
 * the pair) its slopes phi'(f0); C0 (smoothed law; may be NULL) its
 * curvatures psi''/psi', without which a given D0 leaves the first Newton
 * step without its Chebyshev correction; v_guess (may be NULL) the fallback
 * start.
 * *budget: law evaluations left in this step, decremented
 * (stage_newton.cpp). lu (not NULL; newton_step.h): on entry, if lu->n is
 * the stage's active cell count and the free start is taken, the
 * factorization of a nearby Newton matrix of the same h (SDIRK2's first
 * stage's last, for the second stage), taken for the first Newton step; on
 * return the stage's last factorization (lu->n = 0: none). Returns RTB_OK,
 * RTB_NOT_CONVERGED or RTB_ERR_OVERFLOW. */
struct rtb_newton_lu;
rtb_status rtb_stage_solve(const rtb_params *p, const rtb_settings *set, const rtb_real *f0,
                           const rtb_real *v0, const rtb_real *D0, const rtb_real *C0,
                           const rtb_real *v_guess, rtb_stage *st, int *budget,
                           struct rtb_newton_lu *lu);

/* Work units of one dashpot-law evaluation in the step budget
 * (RTB_STEP_WORK): 1 for eq. (1), RTB_SLAW_UNIT for the smoothed eq. (14)
 * (four transcendental calls instead of two, measured ~3x the time). STS
 * has no law; each of its active-set solves is charged one unit per cell. */
#define RTB_SLAW_UNIT 3
static inline int rtb_law_unit(const rtb_params *p) {
  return p->model == RTB_MODEL_RT && p->smoothing > 0.0 ? RTB_SLAW_UNIT : 1;
}

/* SDIRK2 coefficient gamma = 1 - 1/sqrt(2) (Alexander 1977). */
#define RTB_SDIRK_GAMMA 0.29289321881345247560
int rtb_integrator_stages(const rtb_params *p);

/* Advance the cell chain from state s (y, xb) to xb_new over dt, storing the
 * stages (st[0..stages-1]). The new DOFs are st[stages-1].y. *budget: law
 * evaluations left in this step (decremented). */
rtb_status rtb_chain_advance(const rtb_params *p, const rtb_settings *set,
                             const rtb_state *s, rtb_real xb_new, rtb_real dt,
                             rtb_stage st[2], int *budget);
/* The same, with the first stage started from the pair (f1, v1) (both or
 * neither NULL) instead of the last step's end: another solution of the
 * first stage for a nearby xb_new, with its slopes D1 (may be NULL: then
 * computed from the pair, which costs a smoothed law an evaluation per
 * cell) and curvatures C1 (smoothed law; may be NULL). f1/v1/D1/C1 may
 * alias st[0].f/st[0].v/st[0].D/st[0].C. */
rtb_status rtb_chain_advance_from(const rtb_params *p, const rtb_settings *set,
                                  const rtb_state *s, rtb_real xb_new, rtb_real dt,
                                  const rtb_real *f1, const rtb_real *v1, const rtb_real *D1,
                                  const rtb_real *C1, rtb_stage st[2], int *budget);

/* Rate-independent STS step (section 3.1): exact backward-Euler return map of
 * the friction chain by a primal-dual active-set method. */
rtb_status rtb_sts_solve(const rtb_params *p, const rtb_real *y_old, rtb_real xb_new,
                         rtb_real *y_new, int *iterations, rtb_real *dy1_dxb);

/* Iteration caps of the bounded loops: the STS active set (the method
 * terminates for an M-matrix; the cap only guards the bound) and the
 * clearance search (responses after the two bracket ends). The *_capped
 * variants take the cap as an argument so that tests can reach the
 * give-up paths; the library always uses these constants. */
#define RTB_STS_MAX_ITERS(n) (2 * (n) + 5)
#define RTB_BACKLASH_ITERS 30
rtb_status rtb_sts_solve_capped(const rtb_params *p, const rtb_real *y_old, rtb_real xb_new,
                                rtb_real *y_new, int *iterations, rtb_real *dy1_dxb,
                                int max_iters);

/* The full step with all internals exposed; rtb_evaluate is a thin wrapper.
 * `stages` may be NULL. */
rtb_status rtb_step_detailed(const rtb_state *s, const rtb_params *p,
                             const rtb_settings *set, rtb_real x, rtb_real dt,
                             rtb_state *out, rtb_real *force, rtb_real *dforce_dx,
                             rtb_stage stages[2]);

/* rtb_step_detailed with the step's cost in *info (may be NULL) and the
 * clearance search capped at backlash_iters responses (RTB_BACKLASH_ITERS in
 * the library; smaller only in tests). */
rtb_status rtb_step_core(const rtb_state *s, const rtb_params *p, const rtb_settings *set,
                         rtb_real x, rtb_real dt, rtb_state *out, rtb_real *force,
                         rtb_real *dforce_dx, rtb_stage stages[2], rtb_step_info *info,
                         int backlash_iters);

/* Validate settings (NULL = defaults) into a usable copy. */
rtb_status rtb_settings_resolve(const rtb_settings *in, rtb_settings *out);

#ifdef __cplusplus
}
#endif
#endif
