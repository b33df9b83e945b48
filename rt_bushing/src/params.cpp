/* params.cpp -- parameter defaults and validation, settings, status texts. */
#include <math.h>
#include <string.h>

#include "rtb_internal.h"
#include "tridiagonal.h"
#include "no_heap.h"

#define RTB_VERSION_STRING "0.1.0"

extern "C" rtb_status rtb_params_default(rtb_params *p, int model) {
  if (!p) return RTB_ERR_NULL;
  if (model != RTB_MODEL_RT && model != RTB_MODEL_STS) return RTB_ERR_MODEL;
  memset(p, 0, sizeof *p);
  p->abi_version = RTB_ABI_VERSION;
  p->model = model;
  p->cells = RTB_DEFAULT_CELLS;
  p->integrator = RTB_INTEGRATOR_SDIRK2;
  /* Section 3.4 example values (issue #2), N/mm and N (s/mm)^alpha. */
  p->K0 = 1000.0;
  p->Kpa = 800.0;
  p->Kr = 3000.0;
  p->C0 = 40.0;
  p->alpha = 0.2;
  p->Ff = 40.0;
  return RTB_OK;
}

/* Rule of one field (RTB_PARAM_FIELDS). `required` fields of rule POSITIVE
 * must be > 0; the others >= 0 (e.g. C0 of an STS model). */
enum field_rule { POSITIVE, NONNEG, ANY, ALPHA, FRACTION, FLAG, SIGNED_FRACTION };

static int required_positive(const rtb_params *p, const char *name) {
  if (!strcmp(name, "Kpa") || !strcmp(name, "Kr")) return 1;
  if (!strcmp(name, "C0")) return p->model == RTB_MODEL_RT;
  if (!strcmp(name, "Ff")) return p->model == RTB_MODEL_STS;
  return 0;
}

static rtb_status check_rule(const rtb_params *p, const char *name, rtb_real v, field_rule rule) {
  if (!isfinite(v)) return RTB_ERR_PARAM_NONFINITE;
  switch (rule) {
    case POSITIVE: return (v > 0.0 || (v == 0.0 && !required_positive(p, name)))
                              ? RTB_OK : RTB_ERR_PARAM_RANGE;
    case NONNEG: return v >= 0.0 ? RTB_OK : RTB_ERR_PARAM_RANGE;
    case ANY: return RTB_OK;
    case ALPHA:
      return (p->model != RTB_MODEL_RT || (v >= RTB_ALPHA_MIN && v < 1.0)) ? RTB_OK : RTB_ERR_ALPHA;
    case FRACTION: return (v >= 0.0 && v < 1.0) ? RTB_OK : RTB_ERR_PARAM_RANGE;
    case FLAG: return (v == 0.0 || v == 1.0) ? RTB_OK : RTB_ERR_PARAM_RANGE;
    case SIGNED_FRACTION: return (v > -1.0 && v < 1.0) ? RTB_OK : RTB_ERR_PARAM_RANGE;
  }
  return RTB_ERR_PARAM_RANGE;
}

/* Static stiffness of the cell chain, all dashpots relaxed: Kpa and N
 * springs Kr in series. */
static rtb_real chain_static(const rtb_params *p) { return 1.0 / (1.0 / p->Kpa + p->cells / p->Kr); }

/* Rules that tie two fields together; *field names the one to change. */
static rtb_status check_pairs(const rtb_params *p, const char **field) {
  /* The static tangent at x = 0, K0 + chain + sat_force/sat_disp (all
   * dashpots relaxed, rtb_static_force), must not be negative, on either
   * side of the asymmetry's kink: |k_asym| <= K0 + chain + sat. K0 < 0 lets a
   * softening spring take more than K0 (an elastomer that loses most of its
   * static stiffness at large strain); the law at large |x| may then fall,
   * except for a slack specimen: its floating end needs a force that grows
   * again above the input (a root to float to), so K0 + chain >= 0 there. */
  const rtb_real sat = p->sat_disp > 0.0 && p->slack == 0.0 ? p->sat_force / p->sat_disp : 0.0;
  /* The chain's static stiffness (>= 0) costs three dependent divisions,
   * and every step checks its parameters: it decides a rule only where
   * K0 + sat < 0 (rounded addition is monotone, so K0 + chain + sat >= 0
   * follows from K0 + sat >= 0) or an asymmetry is set (|0| <= the tangent's
   * positive part always holds). */
  const bool chain_decides = !(p->K0 + sat >= 0.0) || p->k_asym != 0.0;
  const rtb_real chain = chain_decides ? chain_static(p) : 0.0;
  /* a slack end floating with a bounded relaxing force g R needs a law that
   * still grows: K0 >= 0 and |k_asym| <= K0 there */
  const int grows = p->slack != 0.0 && p->relax_width > 0.0;
  const rtb_real tangent = grows ? p->K0 : p->K0 + chain + sat;
  struct { int bad; const char *name; } rules[] = {
      {!(p->K0 + chain + sat >= 0.0), "K0"},                     /* K0 >= -(chain + sat) */
      {grows && p->K0 < 0.0, "K0"},
      /* the same tangent on either side of a kink k_asym |x|: a tension side
       * softer than K0 alone stays admissible while the chain holds it up */
      {!(fabs(p->k_asym) <= (tangent > 0.0 ? tangent : 0.0)), "k_asym"},
      {p->maxwell_k > 0.0 && !(p->maxwell_tau > 0.0), "maxwell_tau"},
      {p->sat_force > 0.0 && !(p->sat_disp > 0.0), "sat_disp"},
      {(p->spec_k > 0.0 || p->spec_tau_max > 0.0) && !(p->spec_tau_min > 0.0), "spec_tau_min"},
      {p->spec_tau_min > 0.0 && !(p->spec_tau_max >= p->spec_tau_min), "spec_tau_max"},
      {p->model == RTB_MODEL_STS && p->fric_asym != 0.0, "fric_asym"},  /* RT dashpot only */
      {p->slack != 0.0 && p->backlash_held != 0.0, "backlash_held"},    /* slack floats */
  };
  for (size_t i = 0; i < sizeof rules / sizeof rules[0]; ++i)
    if (rules[i].bad) { *field = rules[i].name; return RTB_ERR_PARAM_RANGE; }
  return RTB_OK;
}

extern "C" rtb_status rtb_params_check(const rtb_params *p, const char **field) {
  const char *dummy;
  const char **bad = field ? field : &dummy;
  *bad = "";
  if (!p) return RTB_ERR_NULL;
  if (p->abi_version != RTB_ABI_VERSION) { *bad = "abi_version"; return RTB_ERR_ABI; }
  if (p->model != RTB_MODEL_RT && p->model != RTB_MODEL_STS) { *bad = "model"; return RTB_ERR_MODEL; }
  if (p->integrator != RTB_INTEGRATOR_SDIRK2 && p->integrator != RTB_INTEGRATOR_BE) {
    *bad = "integrator";
    return RTB_ERR_MODEL;
  }
  if (p->cells < 1 || p->cells > RTB_MAX_CELLS) { *bad = "cells"; return RTB_ERR_CELLS; }
  rtb_status st;
#define RTB_CHECK_FIELD(name, rule, kind, unit, text)      \
  st = check_rule(p, #name, p->name, rule);                \
  if (st != RTB_OK) { *bad = #name; return st; }
  RTB_PARAM_FIELDS(RTB_CHECK_FIELD)
#undef RTB_CHECK_FIELD
  for (int i = 0; i < RTB_N_RESERVED; ++i)
    if (p->reserved[i] != 0.0) { *bad = "reserved"; return RTB_ERR_RESERVED; }
  return check_pairs(p, bad);
}

extern "C" rtb_status rtb_params_validate(const rtb_params *p) {
  return rtb_params_check(p, NULL);
}

extern "C" void rtb_settings_default(rtb_settings *s) {
  if (!s) return;
  s->tol = RTB_TOL_DEFAULT;
  s->max_iter = 40;
  s->max_backtrack = 30;
  s->max_work = RTB_STEP_WORK;
  s->pad_ = 0;
}

extern "C" rtb_status rtb_settings_resolve(const rtb_settings *in, rtb_settings *out) {
  rtb_settings_default(out);
  if (!in) return RTB_OK;
  if (!(in->tol >= RTB_TOL_MIN && in->tol <= 1e-2)) return RTB_ERR_SETTINGS;
  if (in->max_iter < 1 || in->max_iter > 100) return RTB_ERR_SETTINGS;
  if (in->max_backtrack < 0 || in->max_backtrack > 60) return RTB_ERR_SETTINGS;
  if (in->max_work < 1 || in->max_work > RTB_MAX_WORK) return RTB_ERR_SETTINGS;
  *out = *in;
  return RTB_OK;
}

extern "C" const char *rtb_status_message(rtb_status status) {
  switch (status) {
    case RTB_OK: return "ok";
    case RTB_NOT_CONVERGED: return "implicit solve did not reach its tolerance; best iterate committed";
    case RTB_ERR_NULL: return "a required pointer is NULL";
    case RTB_ERR_ABI: return "abi_version does not match this library (rebuild against rt_bushing.h)";
    case RTB_ERR_MODEL: return "unknown model or integrator";
    case RTB_ERR_CELLS: return "cells must be between 1 and RTB_MAX_CELLS";
    case RTB_ERR_PARAM_NONFINITE: return "a parameter is NaN or infinite";
    case RTB_ERR_PARAM_RANGE: return "a parameter is out of range (stiffness/coefficient sign or bound)";
    case RTB_ERR_ALPHA: return "alpha must satisfy RTB_ALPHA_MIN <= alpha < 1";
    case RTB_ERR_RESERVED: return "reserved parameter slots must be zero";
    case RTB_ERR_INPUT: return "displacement is non-finite or beyond RTB_X_MAX";
    case RTB_ERR_DT: return "dt is non-finite or outside [RTB_DT_MIN, RTB_DT_MAX]";
    case RTB_ERR_STATE: return "state is not initialised for these parameters";
    case RTB_ERR_OVERFLOW: return "the step would produce a non-finite value";
    case RTB_ERR_SETTINGS: return "settings out of range";
    case RTB_ERR_ALIAS: return "an output struct aliases an input (rtb_evaluate: trial == s)";
    case RTB_ERR_CAPACITY: return "a capacity argument is negative";
  }
  return "unknown status";
}

extern "C" void rtb_get_info(rtb_info *info) {
  if (!info) return;
  info->abi_version = RTB_ABI_VERSION;
  info->max_cells = RTB_MAX_CELLS;
  info->scalar_bytes = (int32_t)sizeof(rtb_real);
  info->params_bytes = (int32_t)sizeof(rtb_params);
  info->state_bytes = (int32_t)sizeof(rtb_state);
  info->settings_bytes = (int32_t)sizeof(rtb_settings);
  info->version = RTB_VERSION_STRING;
#ifdef RTB_SINGLE
  info->scalar = "float";
#else
  info->scalar = "double";
#endif
}

extern "C" rtb_real rtb_static_force(const rtb_params *p, rtb_real x) {
  if (!p) return 0.0;
  /* All dashpots relaxed: the chain parallel to K0. */
  const rtb_real chain = chain_static(p);
  const rtb_real sat = p->sat_disp > 0.0 ? p->sat_force * tanh(x / p->sat_disp) : 0.0;
  const rtb_real u = p->relax_width > 0.0 ? x / p->relax_width : 0.0;
  return p->K0 * x + chain * x / sqrt(1.0 + u * u) + p->k2 * x * x + p->k3 * x * x * x +
         p->k_asym * fabs(x) + sat;
}

extern "C" int rtb_cell_states(const rtb_state *s, rtb_real *out, int cap) {
  if (!s || !out) return RTB_ERR_NULL;
  if (!s->initialised) return RTB_ERR_STATE;
  if (cap < 0) return RTB_ERR_CAPACITY;
  const int n = s->cells < cap ? s->cells : cap;
  for (int k = 0; k < n; ++k) out[k] = s->y[k];
  return n;
}
