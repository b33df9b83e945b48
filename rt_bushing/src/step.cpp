/* step.cpp -- one step of the force element: integrator composition (SDIRK2
 * or backward Euler over the stage solve), force of eq. (11) with the
 * extensions, clearance (backlash) resolution, tangent dF/dx, public API.
 */
#include <float.h>
#include <math.h>
#include <string.h>

#include "bushing_force.h"
#include "dashpot_law.h"
#include "newton_step.h"
#include "rtb_internal.h"
#include "tridiagonal.h"
#include "no_heap.h"

extern "C" int rtb_integrator_stages(const rtb_params *p) {
  return (p->model == RTB_MODEL_RT && p->integrator == RTB_INTEGRATOR_SDIRK2) ? 2 : 1;
}

static rtb_status worse(rtb_status a, rtb_status b) {
  if (a < 0 || b < 0) return a < b ? a : b;
  return a > b ? a : b;
}

/* Stage composition.
 * BE:     y1 = y_n + dt phi(b(t_{n+1}) - K y1).
 * SDIRK2: Y1 = y_n + g dt k1,  Y2 = y_n + (1-g) dt k1 + g dt k2,  y_{n+1} = Y2,
 *         k_i = phi(b_i - K Y_i), b_1 at t_n + g dt (xb interpolated
 *         linearly), b_2 at t_{n+1}; L-stable and stiffly accurate. */
extern "C" rtb_status rtb_chain_advance(const rtb_params *p, const rtb_settings *set,
                                        const rtb_state *s, rtb_real xb_new, rtb_real dt,
                                        rtb_stage st[2], int *budget) {
  return rtb_chain_advance_from(p, set, s, xb_new, dt, NULL, NULL, NULL, NULL, st, budget);
}

extern "C" rtb_status rtb_chain_advance_from(const rtb_params *p, const rtb_settings *set,
                                             const rtb_state *s, rtb_real xb_new, rtb_real dt,
                                             const rtb_real *f1, const rtb_real *v1,
                                             const rtb_real *D1, const rtb_real *C1,
                                             rtb_stage st[2], int *budget) {
  const int n = p->cells;
  /* Free start of the first stage: the last step's end, (f_n, v_n), with
   * f_n = b(t_n) - K y_n from eq. (2) (no law evaluation). Fallback start:
   * velocities extrapolated linearly in time from the last two step ends.
   * The converged result does not depend on either. */
  rtb_real f_end[RTB_MAX_CELLS], guess[RTB_MAX_CELLS];
  rtb_chain_apply(n, p->Kpa, p->Kr, s->y, f_end);
  for (int k = 0; k < n; ++k) f_end[k] = (k == 0 ? p->Kpa * s->xb : 0.0) - f_end[k];
  const int ns = rtb_integrator_stages(p);
  const rtb_real lead = ns == 1 ? dt : RTB_SDIRK_GAMMA * dt;
  const rtb_real w = s->dt_prev > 0.0 ? fmin(lead / s->dt_prev, 1.0) : 0.0;
  for (int k = 0; k < n; ++k) guess[k] = s->v[k] + w * (s->v[k] - s->v_prev[k]);
  const rtb_real *fs = f1 && v1 ? f1 : f_end, *vs = f1 && v1 ? v1 : s->v;
  const rtb_real *Ds = f1 && v1 ? D1 : NULL, *Cs = f1 && v1 ? C1 : NULL;
  /* Both SDIRK2 stages have the step h = g dt: the second's first Newton
   * step takes the first stage's last factorization (its matrix differs by
   * the slopes' change over that last update, ~1e-4 relative at 1 kHz). */
  rtb_newton_lu lu;
  lu.n = 0;
  if (ns == 1) {
    st[0].h = dt;
    st[0].b1 = p->Kpa * xb_new;
    memcpy(st[0].c, s->y, sizeof(rtb_real) * n);
    return rtb_stage_solve(p, set, fs, vs, Ds, Cs, guess, &st[0], budget, &lu);
  }
  const rtb_real g = RTB_SDIRK_GAMMA;
  st[0].h = g * dt;
  st[0].b1 = p->Kpa * (s->xb + g * (xb_new - s->xb));
  memcpy(st[0].c, s->y, sizeof(rtb_real) * n);
  rtb_status a = rtb_stage_solve(p, set, fs, vs, Ds, Cs, guess, &st[0], budget, &lu);
  if (a < 0) return a;
  if (!st[0].converged) lu.n = 0;
  st[1].h = g * dt;
  st[1].b1 = p->Kpa * xb_new;
  for (int k = 0; k < n; ++k) {
    st[1].c[k] = s->y[k] + (1.0 - g) * dt * st[0].v[k];
    /* from (t_n, v_n) and (t_n + g dt, v1) to t_n + dt */
    guess[k] = st[0].v[k] + (1.0 - g) / g * (st[0].v[k] - s->v[k]);
  }
  /* Free start of the second stage: the first stage's solution, with the
   * slopes of its last sweep (no law evaluation; a smoothed one costs
   * RTB_SLAW_UNIT). */
  return worse(a, rtb_stage_solve(p, set, st[0].f, st[0].v, st[0].D,
                                  st[0].have_C ? st[0].C : NULL, guess, &st[1], budget, &lu));
}

/* Tangent of one converged stage: (I + h D K) dy = dc + h D e1 db1. */
static void stage_tangent(const rtb_params *p, const rtb_stage *st, const rtb_real *dc,
                          rtb_real db1, rtb_real *dy) {
  const int n = p->cells;
  if (n < 1 || n > RTB_MAX_CELLS) return;
  rtb_real lo[RTB_MAX_CELLS], di[RTB_MAX_CELLS], up[RTB_MAX_CELLS], work[RTB_MAX_CELLS];
  /* st->D: phi' at the stage's pair, from its last law sweep */
  for (int k = 0; k < n; ++k) dy[k] = (dc ? dc[k] : 0.0) + (k == 0 ? st->h * st->D[k] * db1 : 0.0);
  rtb_stage_matrix(n, st->h, st->D, p->Kpa, p->Kr, 0, lo, di, up);
  rtb_tridiag_solve(n, lo, di, up, dy, work);
}

/* d y1_new / d xb_new of the chain advance (RT). */
static rtb_real chain_dy1_dxb(const rtb_params *p, const rtb_stage st[2]) {
  rtb_real dy[RTB_MAX_CELLS];
  if (rtb_integrator_stages(p) == 1) {
    stage_tangent(p, &st[0], NULL, p->Kpa, dy);
    return dy[0];
  }
  const rtb_real g = RTB_SDIRK_GAMMA;
  rtb_real dc[RTB_MAX_CELLS];
  stage_tangent(p, &st[0], NULL, p->Kpa * g, dy);
  for (int k = 0; k < p->cells; ++k) dc[k] = (1.0 - g) / g * dy[k]; /* (1-g) dt dv1 */
  stage_tangent(p, &st[1], dc, p->Kpa, dy);
  return dy[0];
}

namespace {

/* Response of the bushing (no inertia) to a bushing displacement xb: the
 * cells, the branch memories and the force of bushing_force.h. */
struct Response {
  rtb_stage st[2];
  rtb_real y[RTB_MAX_CELLS];
  rtb_real z, z_spec[RTB_MAX_BRANCHES];
  rtb_real F, dF;  /* force and total dF/dxb */
  int iterations;
  int backtracks;
  rtb_real residual;  /* max relative stage residual (RT) */
  rtb_status status;
};

/* Work of every response of a step, for rtb_step_info. */
struct Cost {
  int iterations, backtracks, responses;
  void add(const Response &r) {
    iterations += r.iterations;
    backtracks += r.backtracks;
    ++responses;
  }
};

/* budget: the step's work left (rtb_settings.max_work). warm: r holds an earlier
 * response of this step (the clearance search); its first stage starts the
 * new one (closer than the last step's end). */
void respond(const rtb_state *s, const rtb_params *p, const rtb_settings *set,
             const rtb_spectrum *sp, rtb_real xb, rtb_real dt, bool tangent, int *budget,
             Response *r, Cost *cost, bool warm = false) {
  const int n = p->cells;
  rtb_real dy1 = 0.0;
  r->backtracks = 0;
  r->residual = 0.0;
  if (p->model == RTB_MODEL_RT) {
    const bool hint = warm && r->status >= 0;
    /* The earlier response's slopes too where recomputing them costs an
     * evaluation per cell (smoothed law); eq. (1)'s are a division. */
    const bool slopes = hint && p->smoothing > 0.0;
    r->status = rtb_chain_advance_from(p, set, s, xb, dt, hint ? r->st[0].f : NULL,
                                       hint ? r->st[0].v : NULL, slopes ? r->st[0].D : NULL,
                                       slopes && r->st[0].have_C ? r->st[0].C : NULL, r->st,
                                       budget);
    const int ns = rtb_integrator_stages(p);
    memcpy(r->y, r->st[ns - 1].y, sizeof(rtb_real) * n);
    r->iterations = r->st[0].iterations + (ns == 2 ? r->st[1].iterations : 0);
    r->backtracks = r->st[0].backtracks + (ns == 2 ? r->st[1].backtracks : 0);
    r->residual = fmax(r->st[0].residual, ns == 2 ? r->st[1].residual : 0.0);
    if (tangent && r->status >= 0) dy1 = chain_dy1_dxb(p, r->st);
  } else {
    /* No law: one unit per cell and active-set solve (a solve of N rows
     * costs about what N law evaluations do), capped by what is left, so a
     * response whose active set does not settle within 2N + 5 solves
     * cannot run past the budget (BM_RandomConfigs/budget:256: an STS
     * clearance configuration took 2 x 59 solves, 27 us, per step). */
    const int left = *budget / n;
    const int cap = left < 1 ? 1 : (left < RTB_STS_MAX_ITERS(n) ? left : RTB_STS_MAX_ITERS(n));
    r->status = rtb_sts_solve_capped(p, s->y, xb, r->y, &r->iterations, tangent ? &dy1 : NULL, cap);
    *budget -= n * r->iterations;
  }
  cost->add(*r);
  /* Branch memories; z evolves whenever its tau is set, so dF/dk is exact at k = 0. */
  rtb_maxwell_lin m;
  rtb_real dz = 0.0, dzw_spec = 0.0; /* d z/dxb, sum_j w_j d z_j/dxb */
  r->z = s->z_maxwell;
  if (p->maxwell_tau > 0.0) {
    rtb_maxwell_step(p->maxwell_tau, dt, s->xb, xb, s->z_maxwell, &m);
    r->z = m.z;
    dz = m.d_xb_new;
  }
  for (int j = 0; j < sp->M; ++j) {
    rtb_maxwell_step(sp->tau[j], dt, s->xb, xb, s->z_spec[j], &m);
    r->z_spec[j] = m.z;
    dzw_spec += sp->w[j] * m.d_xb_new;
  }
  rtb_force_lin L;
  rtb_force_eval(p, xb, s->xb, s->xb_max, r->y[0], r->z, r->z_spec, sp, dt, &L);
  r->F = L.F;
  /* L.d_xb holds y1 and the memories fixed; add their own dependence on xb. */
  r->dF = L.d_xb + L.d_y1 * dy1 + L.d_z * dz + L.d_z_spec * dzw_spec;
}

/* Where the bushing end may be: xb in [lo, hi] (hi = +inf for a slack
 * specimen, which never pushes); phase codes as rtb_state.contact. */
struct Gap {
  rtb_real lo, hi;
  bool held;
};

Gap gap_of(const rtb_params *p, rtb_real x) {
  Gap g;
  g.lo = x - 0.5 * p->backlash;
  g.hi = p->slack != 0.0 ? INFINITY : x + 0.5 * p->backlash;
  g.held = p->backlash_held != 0.0;
  return g;
}

}  // namespace

/* Clearance of total width g in series (backlash) and/or a slack specimen:
 * the bushing end xb stays within [lo, hi]. Floating end: inside, the bushing
 * carries no load, so xb = clamp(xb_free, lo, hi) with F(xb_free) = 0; F is
 * increasing in xb, so a safeguarded Newton/bisection finds it (for hi = inf
 * the bracket is first extended by Newton steps). Held end: xb stays where it
 * was, clamped into [lo, hi]. Bounded: at most 2 + iters + RTB_SLACK_EXTEND
 * responses per step (iters = RTB_BACKLASH_ITERS in the library), and by the
 * step's work budget: each response takes its law evaluations from it, and a
 * new one starts only while a sweep is left. The response in *r is always the
 * one at *xb_out (state, force and tangent agree); a search ended by its
 * iteration cap or by the budget returns RTB_NOT_CONVERGED and leaves its
 * relative force residual in *residual. */
#define RTB_SLACK_EXTEND 8
/* How far (in gap widths) the old contact point may have moved for the
 * search to start there (resolve_gap): beyond, the last step's force says
 * little (a dashpot force of a jump relaxes within the step). */
#define RTB_CONTACT_REACH 4.0
static int phase_at(const Gap &g, rtb_real xb) { return xb == g.lo ? 1 : (xb == g.hi ? -1 : 0); }

static rtb_status resolve_gap(const rtb_state *s, const rtb_params *p, const rtb_settings *set,
                              const rtb_spectrum *sp, rtb_real x, rtb_real dt, int iters,
                              int *budget, Response *r, Cost *cost, rtb_real *xb_out,
                              int *contact, rtb_real *residual) {
  const Gap g = gap_of(p, x);
  const int sweep = p->cells * rtb_law_unit(p);
  /* An end in contact starts at its contact point when the force there,
   * extrapolated from the last step with the stiffness |K0| + Kpa, still
   * pulls (session 36): else the start is the old position clamped into the
   * gap, which, where the input moved back, was inside it, still pulled,
   * and was followed by the contact point -- two responses on 45% of
   * BM_Extension's clearance steps. A jump across the gap (a force of the
   * other sign at the old contact point, or a move of more than
   * RTB_CONTACT_REACH gap widths) keeps the clamp's end. */
  rtb_real xb = fmin(fmax(s->xb, g.lo), g.hi);
  const int side = g.held ? 0 : s->contact;
  const rtb_real end = side == 1 ? g.lo : g.hi;
  if ((side == 1 || (side == -1 && isfinite(g.hi))) &&
      fabs(end - s->xb) <= RTB_CONTACT_REACH * p->backlash &&
      side * (s->force + (fabs(p->K0) + p->Kpa) * (end - s->xb)) >= 0.0)
    xb = end;
  respond(s, p, set, sp, xb, dt, true, budget, r, cost);
  *xb_out = xb;
  *residual = 0.0;
  if (g.held) { *contact = xb == g.lo ? 1 : (xb == g.hi ? -1 : 3); return RTB_OK; }
  *contact = phase_at(g, xb);
  if (r->status < 0) return RTB_OK;
  if ((xb == g.lo && r->F >= 0.0) || (xb == g.hi && r->F <= 0.0)) return RTB_OK;
  if (r->F == 0.0) { *contact = 0; return RTB_OK; }
  if (*budget < sweep) return RTB_NOT_CONVERGED;
  /* The root of F(xb) = 0 lies below xb if F > 0, else above: [a, b], of
   * which the end at xb is evaluated, the far one (a contact point) not
   * yet. The search starts at the Newton point from the previous end, not
   * at the bracket's middle: a floating end moves little per step, while
   * the bracket reaches to the contact point (x - g/2 while a slack strip
   * relaxes: 11-12 responses per floating step from the middle, 5 from
   * here, on a 1 Hz, 1 mm sine at 1 kHz). */
  rtb_real a = g.lo, b = g.hi;
  bool a_known = !(r->F > 0.0), b_known = r->F > 0.0;
  if (b_known) b = xb; else a = xb;
  const rtb_real scale = fabs(p->K0) + p->Kpa;
  rtb_real width = b - a; /* the tolerance's length scale */
  rtb_real nx = r->dF > 0.0 ? xb - r->F / r->dF : NAN;
  if (!isfinite(b)) {
    /* Slack: extend a bracket upwards by doubled Newton steps. */
    rtb_real t = xb, Ft = r->F, dFt = r->dF;
    for (int e = 0; e < RTB_SLACK_EXTEND && !isfinite(b); ++e) {
      if (*budget < sweep) return RTB_NOT_CONVERGED;
      const rtb_real step = dFt > 0.0 ? -Ft / dFt : fabs(t - x) + p->backlash + 1e-9;
      t += 2.0 * step * (rtb_real)(1 << e);
      respond(s, p, set, sp, t, dt, true, budget, r, cost, true);
      *xb_out = t;
      *contact = 0;
      if (r->status < 0) break;
      if (r->F > 0.0) b = t; else { a = t; Ft = r->F; dFt = r->dF; }
    }
    nx = dFt > 0.0 ? a - Ft / dFt : NAN; /* Newton from the bracket's low end */
    if (!isfinite(b)) return RTB_NOT_CONVERGED; /* best effort, bounded: r is at a */
    b_known = true;
    width = b - a;
  }
  /* Newton, safeguarded by the bracket. A contact point is responded to
   * only when Newton's point leaves the gap on its side (session 36: the
   * old search checked the far contact first, one response more on every
   * floating step). With the contact start above, BM_Extension's clearance
   * input takes 1.05 responses per step, at most 4 (1.51 and 5 before),
   * and every extension with the smoothing at most 1135 work units per
   * step (2496; tests/clearance_search_test.cpp, smoothed_law_cost_test.cpp).
   * A slack strip without a clearance (backlash 0) never starts at its
   * contact point: RTB_CONTACT_REACH is in gap widths. */
  *contact = 0;
  for (int it = 0; it < iters;) {
    if (!(nx > a && nx < b) && !(a_known && b_known)) {
      /* The one end not yet known, a contact point: the check is not one
       * of the search's iterations. */
      const rtb_real end = a_known ? b : a;
      if (*budget < sweep) return RTB_NOT_CONVERGED;
      respond(s, p, set, sp, end, dt, true, budget, r, cost); /* cold: as without a gap */
      *xb_out = end;
      *contact = end == g.lo ? 1 : -1;
      if (r->status < 0 || (end == g.lo ? r->F >= 0.0 : r->F <= 0.0)) return RTB_OK;
      *contact = 0;
      a_known = b_known = true;
      nx = r->dF > 0.0 ? end - r->F / r->dF : NAN;
      continue;
    }
    if (!(nx > a && nx < b)) nx = 0.5 * (a + b);
    if (*budget < sweep) return RTB_NOT_CONVERGED; /* r: the response at *xb_out */
    xb = nx;
    ++it;
    respond(s, p, set, sp, xb, dt, true, budget, r, cost, true);
    *xb_out = xb;
    if (r->status < 0) return RTB_OK; /* the caller returns r->status */
    if (r->F > 0.0) b = xb, b_known = true; else a = xb, a_known = true;
    *residual = fabs(r->F) / (scale * (fabs(xb) + width));
    if (fabs(r->F) <= set->tol * scale * (fabs(xb) + width) ||
        (a_known && b_known && b - a <= 4 * RTB_REAL_EPSILON * fabs(xb)))
      return RTB_OK;
    nx = r->dF > 0.0 ? xb - r->F / r->dF : NAN;
  }
  return RTB_NOT_CONVERGED;
}

static rtb_status check_call(const rtb_state *s, const rtb_params *p, rtb_real x, rtb_real dt) {
  if (!s || !p) return RTB_ERR_NULL;
  rtb_status v = rtb_params_validate(p);
  if (v != RTB_OK) return v;
  if (!s->initialised || s->abi_version != RTB_ABI_VERSION || s->model != p->model ||
      s->cells != p->cells)
    return RTB_ERR_STATE;
  if (!isfinite(x) || fabs(x) > RTB_X_MAX) return RTB_ERR_INPUT;
  if (!(dt >= RTB_DT_MIN && dt <= RTB_DT_MAX)) return RTB_ERR_DT;
  return RTB_OK;
}

/* The input's velocity and acceleration at the end t_n of a step of length h
 * (the inertia term, rtb_params.mass). The second difference of x is centred
 * between the last two velocity midpoints, (3h + h_p)/4 before t_n: one whole
 * step back on a uniform grid, so m a lagged the input by a step (1 ms at
 * 1 kHz, 7 degrees at 20 Hz: a fitted force lead then took up what the
 * element got wrong, blindgen inertia_s59 at 1 kHz named `delay` beside
 * `inertia`). Where the input is smooth it is extrapolated linearly to t_n
 * from the centred value of the step before: (2 x_n - 5 x_n-1 + 4 x_n-2 -
 * x_n-3) / h^2 on a uniform grid, second order with no lag, like the stages.
 * "Smooth": over the gap the slope changes by at most a quarter of the two
 * centred values ((w h)^2 / 2 of them for a sine of w: up to ~100 Hz at
 * 1 kHz). At a corner of the input (a triangle's, a ramp's end: the centred
 * values 0, S, 0, a change of S to 2S) the extrapolation would give 2S then
 * -S, five times the squared spike of the centred S; there, and where
 * displacement noise makes the slopes alternate, the centred value stands.
 * The factor age / gap is 1 on a uniform grid (one division per step, as
 * before) and in (0, 3) on any (gap >= h/4 + h_p/2). */
struct InputMotion {
  rtb_real v, a, a_c, age, slope, da_dx;
};
static InputMotion input_motion(const rtb_state *s, rtb_real x, rtb_real dt) {
  InputMotion m;
  const bool uniform = s->x_dt == dt || !(s->x_dt > 0.0);
  const rtb_real hp = uniform ? dt : s->x_dt;
  const rtb_real inv = 1.0 / dt;
  const rtb_real span = uniform ? dt : 0.5 * (dt + hp);  /* between the velocity midpoints */
  m.v = (x - s->x) * inv;                                  /* at t_n - h/2 */
  m.a_c = uniform ? (m.v - s->vx) * inv : (m.v - s->vx) / span;  /* at t_n - age */
  m.age = uniform ? dt : 0.25 * (3.0 * dt + hp);
  m.slope = 0.0;
  rtb_real w = 0.0; /* extrapolation factor */
  if (s->ax_age > 0.0) {
    const rtb_real gap = dt + s->ax_age - m.age; /* between the two centred values */
    const bool even = uniform && s->ax_age == dt;
    m.slope = even ? (m.a_c - s->ax_c) * inv : (m.a_c - s->ax_c) / gap;
    if (fabs(m.slope - s->ax_slope) * gap <= 0.25 * (fabs(m.a_c) + fabs(s->ax_c)))
      w = even ? 1.0 : m.age / gap;
  }
  m.a = m.a_c + w * (m.a_c - s->ax_c);
  m.da_dx = (1.0 + w) * inv * (uniform ? inv : 1.0 / span);
  return m;
}

extern "C" rtb_status rtb_step_core(const rtb_state *s, const rtb_params *p,
                                    const rtb_settings *set_in, rtb_real x, rtb_real dt,
                                    rtb_state *out, rtb_real *force, rtb_real *dforce_dx,
                                    rtb_stage stages[2], rtb_step_info *info,
                                    int backlash_iters) {
  rtb_status st = check_call(s, p, x, dt);
  if (st != RTB_OK) return st;
  rtb_settings set;
  st = rtb_settings_resolve(set_in, &set);
  if (st != RTB_OK) return st;

  rtb_spectrum sp;
  rtb_spectrum_layout(p, &sp);
  Response r;
  Cost cost = {0, 0, 0};
  rtb_real xb = x, clearance_residual = 0.0;
  int contact = 2;
  int budget = set.max_work;
  rtb_status clearance = RTB_OK;
  if (p->backlash > 0.0 || p->slack != 0.0)
    clearance = resolve_gap(s, p, &set, &sp, x, dt, backlash_iters, &budget, &r, &cost, &xb,
                            &contact, &clearance_residual);
  else
    respond(s, p, &set, &sp, xb, dt, dforce_dx != NULL, &budget, &r, &cost);
  if (r.status < 0) return r.status;
  r.status = worse(r.status, clearance);

  /* Inertia of the load path: F += m a(t_n). */
  const InputMotion im = input_motion(s, x, dt);
  const bool inertia = p->mass != 0.0;  /* no 0 * inf from a tiny dt */
  const rtb_real F = inertia ? r.F + p->mass * im.a : r.F;
  /* dF/dx: through xb = x (or x -+ g/2) in contact; a floating end does not
   * follow x, and a held one stays where it was. */
  const bool follows = contact == 2 || contact == 1 || contact == -1;
  const rtb_real dF = (follows ? r.dF : 0.0) + (inertia ? p->mass * im.da_dx : 0.0);
  if (!isfinite(F) || !isfinite(dF)) return RTB_ERR_OVERFLOW;

  /* Commit: every check is above, so `out` (which may be `s`) is written
   * only on success. Field by field rather than through a whole copy of the
   * state (~1 KB twice per step, 3% of a default step): a trial gets the
   * rest of *s first. v_prev takes s->v before v is overwritten. */
  const int n = p->cells;
  const rtb_stage &last = r.st[p->model == RTB_MODEL_RT ? rtb_integrator_stages(p) - 1 : 0];
  for (int k = 0; k < n; ++k)
    if (!isfinite(r.y[k]) || (p->model == RTB_MODEL_RT && !isfinite(last.v[k])))
      return RTB_ERR_OVERFLOW;
  if (out != s) *out = *s;
  out->x = x;
  out->xb = xb;
  out->force = F;
  out->time = s->time + dt;
  memcpy(out->y, r.y, sizeof(rtb_real) * n);
  if (p->model == RTB_MODEL_RT) {
    memcpy(out->v_prev, s->v, sizeof(rtb_real) * n);
    memcpy(out->v, last.v, sizeof(rtb_real) * n);
    out->dt_prev = dt;
  }
  out->z_maxwell = r.z;
  memcpy(out->z_spec, r.z_spec, sizeof(rtb_real) * (size_t)sp.M);
  out->contact = contact;
  out->xb_max = fmax(s->xb_max, fabs(xb));
  out->vx = im.v;
  out->ax = im.a;
  out->ax_c = im.a_c;
  out->ax_age = im.age;
  out->ax_slope = im.slope;
  out->x_dt = dt;
  out->steps = s->steps + 1;
  out->last_iterations = r.iterations;
  if (force) *force = F;
  if (dforce_dx) *dforce_dx = dF;
  if (stages && p->model == RTB_MODEL_RT) memcpy(stages, r.st, sizeof r.st);
  if (info) {
    info->iterations = cost.iterations;
    info->backtracks = cost.backtracks;
    info->clearance_iterations = (p->backlash > 0.0 || p->slack != 0.0) ? cost.responses : 0;
    info->stages = p->model == RTB_MODEL_RT ? rtb_integrator_stages(p) : 1;
    info->residual = r.residual;
    info->clearance_residual = contact == 0 ? clearance_residual : 0.0;  /* floating end */
    info->work = set.max_work - budget;
    info->pad_ = 0;
  }
  return r.status;
}

extern "C" rtb_status rtb_step_detailed(const rtb_state *s, const rtb_params *p,
                                        const rtb_settings *set, rtb_real x, rtb_real dt,
                                        rtb_state *out, rtb_real *force, rtb_real *dforce_dx,
                                        rtb_stage stages[2]) {
  return rtb_step_core(s, p, set, x, dt, out, force, dforce_dx, stages, NULL,
                       RTB_BACKLASH_ITERS);
}

extern "C" rtb_status rtb_state_init(rtb_state *s, const rtb_params *p, rtb_real x0) {
  if (!s || !p) return RTB_ERR_NULL;
  rtb_status v = rtb_params_validate(p);
  if (v != RTB_OK) return v;
  if (!isfinite(x0) || fabs(x0) > RTB_X_MAX) return RTB_ERR_INPUT;
  rtb_state t;
  memset(&t, 0, sizeof t);
  t.abi_version = RTB_ABI_VERSION;
  t.model = p->model;
  t.cells = p->cells;
  t.initialised = 1;
  t.x = t.xb = x0;
  /* Relaxed equilibrium: K y = b (every dashpot/friction force zero). */
  rtb_real work[RTB_MAX_CELLS];
  for (int k = 0; k < p->cells; ++k) t.y[k] = k == 0 ? p->Kpa * x0 : 0.0;
  rtb_chain_solve(p->cells, p->Kpa, p->Kr, t.y, work);
  t.z_maxwell = x0;
  for (int j = 0; j < RTB_MAX_BRANCHES; ++j) t.z_spec[j] = x0;
  t.contact = 2;
  t.xb_max = fabs(x0);
  t.force = rtb_static_force(p, x0);
  *s = t;
  return RTB_OK;
}

extern "C" rtb_status rtb_evaluate_ex(const rtb_state *s, const rtb_params *p,
                                      const rtb_settings *set, rtb_real x, rtb_real dt,
                                      rtb_state *trial, rtb_real *force, rtb_real *dforce_dx,
                                      rtb_step_info *info) {
  if (!s || !trial || !force) return RTB_ERR_NULL;
  if (trial == s) return RTB_ERR_ALIAS;
  return rtb_step_core(s, p, set, x, dt, trial, force, dforce_dx, NULL, info,
                       RTB_BACKLASH_ITERS);
}

extern "C" rtb_status rtb_evaluate(const rtb_state *s, const rtb_params *p,
                                   const rtb_settings *set, rtb_real x, rtb_real dt,
                                   rtb_state *trial, rtb_real *force, rtb_real *dforce_dx) {
  return rtb_evaluate_ex(s, p, set, x, dt, trial, force, dforce_dx, NULL);
}

extern "C" rtb_status rtb_commit(rtb_state *s, const rtb_state *trial) {
  if (!s || !trial) return RTB_ERR_NULL;
  if (!trial->initialised) return RTB_ERR_STATE;
  if (s != trial) *s = *trial;
  return RTB_OK;
}

extern "C" rtb_status rtb_step_ex(rtb_state *s, const rtb_params *p, const rtb_settings *set,
                                  rtb_real x, rtb_real dt, rtb_real *force,
                                  rtb_step_info *info) {
  if (!force) return RTB_ERR_NULL;
  /* In place: rtb_step_core writes its output only after every check, and
   * reads nothing of *s after its first write (no 1 KB state copied twice). */
  return rtb_step_core(s, p, set, x, dt, s, force, NULL, NULL, info, RTB_BACKLASH_ITERS);
}

extern "C" rtb_status rtb_step(rtb_state *s, const rtb_params *p, const rtb_settings *set,
                               rtb_real x, rtb_real dt, rtb_real *force) {
  return rtb_step_ex(s, p, set, x, dt, force, NULL);
}
