/*
 * rt_bushing.h -- real-time Rate-dependent Triboelastic (RT) force element.
 *
 * Puel, Bourgeteau & Aubry (2013), "Parameter identification of nonlinear
 * time-dependent rubber bushings models ...", MSSP 36(2). Equation numbers in
 * comments refer to that paper.
 *
 * Plain C ABI (C99 and C++). Caller-owned memory, fixed capacity, no heap, no
 * exceptions, no global mutable state, bounded work per step.
 *
 * Units: the library is unit-agnostic; use one consistent set, e.g.
 *   length mm, force N, time s  ->  K [N/mm], C0 [N (s/mm)^alpha],
 *   k3 [N/mm^3], viscous_c [N s/mm], mass [N s^2/mm] (= tonne), tau [s].
 *
 * Typical use:
 *   rtb_params p;  rtb_params_default(&p, RTB_MODEL_RT);   // or a generated header
 *   rtb_state  s;  rtb_state_init(&s, &p, 0.0);
 *   for (...) { double F; rtb_status st = rtb_step(&s, &p, NULL, x, dt, &F); }
 */
#ifndef RT_BUSHING_H
#define RT_BUSHING_H

#ifdef __cplusplus
extern "C" {
#endif

/* ------------------------------------------------------------------ */
/* Types                                                               */
/* ------------------------------------------------------------------ */

#define RTB_ABI_VERSION 3     /* bumped on any layout change of the structs
                                 (2: `smoothing`, `sat_force`, `sat_disp` took reserved[0..2];
                                  3: slack, backlash_held, fric_asym, spec_* and the
                                  spectrum memory z_spec in rtb_state) */
#define RTB_MAX_CELLS 32      /* capacity of rtb_state; N = 1 .. RTB_MAX_CELLS */
#define RTB_DEFAULT_CELLS 15  /* the paper's choice (section 3.4) */
#define RTB_N_RESERVED 6
#define RTB_MAX_BRANCHES 16  /* capacity of the relaxation spectrum (eight decades) */

typedef double rtb_real;
#define RTB_SCALAR_BYTES 8    /* sizeof(rtb_real); checked by generated headers */

/* Lower bound on the dashpot exponent: alpha -> 0 is the STS friction limit
 * (section 3.2); below this use RTB_MODEL_STS. */
#define RTB_ALPHA_MIN 1e-3

/* Accepted input ranges (anything outside is RTB_ERR_INPUT, state untouched). */
#define RTB_DT_MIN 1e-9
#define RTB_DT_MAX 1e3
#define RTB_X_MAX 1e12

typedef enum rtb_status {
  RTB_OK = 0,
  RTB_NOT_CONVERGED = 1,      /* warning: the step was committed with the best
                                 iterate (finite force); see rtb_settings */
  RTB_ERR_NULL = -1,          /* a required pointer is NULL */
  RTB_ERR_ABI = -2,           /* abi_version field does not match this library */
  RTB_ERR_MODEL = -3,         /* unknown model or integrator */
  RTB_ERR_CELLS = -4,         /* cells outside 1 .. RTB_MAX_CELLS */
  RTB_ERR_PARAM_NONFINITE = -5,
  RTB_ERR_PARAM_RANGE = -6,   /* a stiffness/coefficient outside its range */
  RTB_ERR_ALPHA = -7,         /* alpha outside [RTB_ALPHA_MIN, 1) */
  RTB_ERR_RESERVED = -8,      /* reserved parameter slots must be zero */
  RTB_ERR_INPUT = -9,         /* displacement non-finite or |x| > RTB_X_MAX */
  RTB_ERR_DT = -10,           /* dt non-finite or outside [RTB_DT_MIN, RTB_DT_MAX] */
  RTB_ERR_STATE = -11,        /* state not initialised for these parameters */
  RTB_ERR_OVERFLOW = -12,     /* the step would produce a non-finite value */
  RTB_ERR_SETTINGS = -13      /* tolerance or iteration limit out of range */
} rtb_status;

typedef enum rtb_model {
  RTB_MODEL_RT = 1,   /* eq. (2): N cells of spring Kr || dashpot C0 sign(v)|v|^alpha */
  RTB_MODEL_STS = 2   /* section 3.1: N cells of spring Kr || friction element Ff */
} rtb_model;

typedef enum rtb_integrator {
  RTB_INTEGRATOR_SDIRK2 = 0,  /* default: 2-stage L-stable SDIRK, order 2 */
  RTB_INTEGRATOR_BE = 1       /* backward Euler, order 1, one stage */
} rtb_integrator;

/*
 * Model parameters. The struct has a fixed size: new model extensions take
 * slots from `reserved` (which must be zero) and bump RTB_ABI_VERSION, so a
 * host compiled against an older header is told (RTB_ERR_ABI) rather than
 * silently misread. Every extension is off when its field is zero.
 */
typedef struct rtb_params {
  int abi_version;   /* = RTB_ABI_VERSION */
  int model;         /* rtb_model */
  int cells;         /* N */
  int integrator;    /* rtb_integrator (RT only; STS is rate-independent) */

  /* Core parameters p = (K0, Kpa, Kr, C0, alpha), eq. (2) and (11). */
  rtb_real K0;       /* global elastic stiffness, >= 0       [force/length] */
  rtb_real Kpa;      /* low-amplitude stiffness, > 0         [force/length] */
  rtb_real Kr;       /* cell spring stiffness, > 0           [force/length] */
  rtb_real C0;       /* RT dashpot coefficient, > 0  [force (time/length)^alpha] */
  rtb_real alpha;    /* RT dashpot exponent, [RTB_ALPHA_MIN, 1) */
  rtb_real Ff;       /* STS friction threshold, > 0 (STS only)    [force] */

  /* Physical extensions (issue #4); all act on the bushing displacement xb,
   * which equals the input x unless a backlash is set. */
  rtb_real k3;          /* cubic spring: F += k3 xb^3            [force/length^3] */
  rtb_real k_asym;      /* asymmetry: F += k_asym |xb|; stiffness K0+k_asym in
                           tension, K0-k_asym in compression; |k_asym| <= K0 */
  rtb_real maxwell_k;   /* extra Maxwell branch stiffness, >= 0  [force/length] */
  rtb_real maxwell_tau; /* its relaxation time, > 0 when maxwell_k > 0 [time] */
  rtb_real viscous_c;   /* parallel linear dashpot: F += c v, >= 0 [force time/length] */
  rtb_real mass;        /* inertia in the load path: F += m a     [force time^2/length] */
  rtb_real backlash;    /* total clearance g in series, >= 0     [length] */
  rtb_real mullins;     /* Mullins softening fraction mu in [0, 1) of K0 below
                           the prior maximum |xb| */

  /* Model setting, not a physical parameter (ABI 2, from reserved[0]). */
  rtb_real smoothing;   /* s of the paper's sigmoid smoothing, eq. (14), >= 0
                           [time/length] (1/velocity); 0 = off (default, exact
                           eq. (1)). s > 0 replaces the RT dashpot law by
                           f = C0 sign_s(v) |v|_s^alpha. Not needed by this
                           stepper (see README); kept to reproduce the paper's
                           Table 1. Ignored by RTB_MODEL_STS. */

  /* Softening (saturating) spring, ABI 2 from reserved[1..2]:
   * F += sat_force tanh(xb / sat_disp). Initial stiffness sat_force/sat_disp,
   * saturating at sat_force: with K0 and k3 an elastic law that softens then
   * stiffens (elastomers at large strain, issue #5). Off when sat_force = 0. */
  rtb_real sat_force;   /* >= 0                                   [force] */
  rtb_real sat_disp;    /* > 0 when sat_force > 0                 [length] */

  /* ABI 3 (issue #10), from reserved[0..6]. */
  rtb_real slack;       /* 1: the specimen cannot push (strip, cable, tension-
                           only mount): when the force at xb = x would be
                           negative the end floats free (F = 0, xb > x) while
                           the cells keep relaxing. 0 = off. Exactly 0 or 1. */
  rtb_real backlash_held; /* 0: inside the clearance the bushing end floats
                           free (F = 0); 1: it is held where it is (xb frozen,
                           the force relaxes). Exactly 0 or 1. */
  rtb_real fric_asym;   /* a in (-1, 1): dashpot level C0 (1 + a) for positive
                           cell velocity, C0 (1 - a) for negative (RT only). */
  rtb_real spec_k;      /* relaxation spectrum (long memory): total stiffness
                           of M Maxwell branches, >= 0            [force/length] */
  rtb_real spec_exp;    /* its weight exponent beta: branch j has stiffness
                           spec_k tau_j^-beta / sum_i tau_i^-beta  [-] */
  rtb_real spec_tau_min;/* fastest branch time, > 0 when spec_k > 0 [time] */
  rtb_real spec_tau_max;/* slowest, >= spec_tau_min; branches log-spaced, two
                           per decade, at most RTB_MAX_BRANCHES    [time] */
  rtb_real reserved[RTB_N_RESERVED];
} rtb_params;

/*
 * The real-valued fields of rtb_params, in declaration order, as one list
 * (an X-macro): X(field, rule, kind, unit, text). Validation, the offline
 * tool's JSON reader/writer, its header emitter and its parameter names are
 * all generated from it, so a new field is added here and in the struct only.
 *   rule: POSITIVE (> 0 where required, else >= 0), NONNEG (>= 0), ANY,
 *         ALPHA ([RTB_ALPHA_MIN, 1) for RT), FRACTION ([0, 1)),
 *         FLAG (exactly 0 or 1), SIGNED_FRACTION ((-1, 1)).
 *   kind: FIT (identifiable), SETTING (fixed model setting, not fitted).
 */
#define RTB_PARAM_FIELDS(X)                                                          \
  X(K0, NONNEG, FIT, "force/length", "global elastic stiffness, eq. (11)")           \
  X(Kpa, POSITIVE, FIT, "force/length", "low-amplitude stiffness, eq. (11)")         \
  X(Kr, POSITIVE, FIT, "force/length", "cell spring stiffness, eq. (2)")             \
  X(C0, POSITIVE, FIT, "force (time/length)^alpha", "RT dashpot coefficient, eq. (1)") \
  X(alpha, ALPHA, FIT, "-", "RT dashpot exponent, eq. (1)")                          \
  X(Ff, POSITIVE, SETTING, "force", "STS friction threshold")                        \
  X(k3, ANY, FIT, "force/length^3", "cubic spring")                                  \
  X(k_asym, ANY, FIT, "force/length", "tension/compression asymmetry")               \
  X(maxwell_k, NONNEG, FIT, "force/length", "Maxwell branch stiffness")              \
  X(maxwell_tau, NONNEG, FIT, "time", "Maxwell relaxation time")                     \
  X(viscous_c, NONNEG, FIT, "force time/length", "parallel linear dashpot")          \
  X(mass, NONNEG, FIT, "force time^2/length", "inertia")                             \
  X(backlash, NONNEG, FIT, "length", "clearance (total width)")                      \
  X(mullins, FRACTION, FIT, "-", "Mullins softening fraction")                       \
  X(smoothing, NONNEG, SETTING, "time/length", "eq. (14) smoothing s, 0 = off")      \
  X(sat_force, NONNEG, FIT, "force", "softening spring force")                       \
  X(sat_disp, NONNEG, FIT, "length", "softening spring displacement")                \
  X(slack, FLAG, SETTING, "-", "tension only: floats free instead of pushing")       \
  X(backlash_held, FLAG, SETTING, "-", "clearance end held (1) or free (0)")         \
  X(fric_asym, SIGNED_FRACTION, FIT, "-", "dashpot level asymmetry a: C0 (1 +- a)")  \
  X(spec_k, NONNEG, FIT, "force/length", "relaxation spectrum stiffness")            \
  X(spec_exp, ANY, FIT, "-", "relaxation spectrum weight exponent")                  \
  X(spec_tau_min, NONNEG, SETTING, "time", "relaxation spectrum fastest time")       \
  X(spec_tau_max, NONNEG, SETTING, "time", "relaxation spectrum slowest time")

/* Numerical settings of the implicit solve. NULL means rtb_settings_default. */
typedef struct rtb_settings {
  rtb_real tol;      /* relative residual tolerance of each Newton solve (1e-12) */
  int max_iter;      /* Newton iterations per stage, 1..100 (default 40) */
  int max_backtrack; /* line-search halvings per iteration, 0..60 (default 30) */
} rtb_settings;

/* State of one element. Plain data: copy it to save/restore (host rollback). */
typedef struct rtb_state {
  int abi_version;
  int model;
  int cells;
  int initialised;             /* 1 after rtb_state_init */
  rtb_real x;                  /* last committed input displacement [length] */
  rtb_real xb;                 /* bushing-side displacement (x minus clearance) */
  rtb_real force;              /* last committed force [force] */
  rtb_real time;               /* accumulated dt [time] */
  rtb_real y[RTB_MAX_CELLS];   /* cell DOFs y_k of eq. (2) [length] */
  rtb_real v[RTB_MAX_CELLS];   /* cell velocities at the end of the last step */
  rtb_real v_prev[RTB_MAX_CELLS]; /* ... and of the step before (predictor) */
  rtb_real dt_prev;            /* length of the last step [time] */
  rtb_real z_maxwell;          /* Maxwell branch internal displacement */
  rtb_real xb_max;             /* prior maximum |xb| (Mullins memory) */
  rtb_real vx;                 /* last input velocity estimate (inertia) */
  rtb_real z_spec[RTB_MAX_BRANCHES]; /* relaxation-spectrum branch displacements */
  rtb_real reserved[8];
  long steps;                  /* committed steps */
  int last_iterations;         /* Newton iterations used by the last step */
  int contact;                 /* phase of the bushing end in the last step:
                                  2 no clearance/slack (xb = x), +1 / -1 in
                                  contact at x - g/2 / x + g/2, 0 floating
                                  free (F = 0), 3 held inside the clearance */
} rtb_state;

/* ------------------------------------------------------------------ */
/* Set-up                                                              */
/* ------------------------------------------------------------------ */

/* Fill with the paper's section 3.4 example set (N=15; K0=1000, Kpa=800,
 * Kr=3000 N/mm, C0=40 N (s/mm)^0.2, alpha=0.2; STS: Ff=40 N). */
rtb_status rtb_params_default(rtb_params *p, int model);
rtb_status rtb_params_validate(const rtb_params *p);
/* rtb_params_validate that also names the offending field ("K0", "cells",
 * "reserved", "maxwell_tau", ...) in *field ("" when valid; field may be
 * NULL). The name is a static string. */
rtb_status rtb_params_check(const rtb_params *p, const char **field);
void rtb_settings_default(rtb_settings *s);
const char *rtb_status_message(rtb_status status);

/* Initialise at rest with every cell DOF at its static equilibrium for the
 * displacement x0 (0 for a virgin bushing). */
rtb_status rtb_state_init(rtb_state *s, const rtb_params *p, rtb_real x0);

/* ------------------------------------------------------------------ */
/* Stepping                                                            */
/* ------------------------------------------------------------------ */

/* Advance one step of length dt to displacement x; write the force.
 * On error (< 0) the state is unchanged and *force is not written.
 * `set` may be NULL. */
rtb_status rtb_step(rtb_state *s, const rtb_params *p, const rtb_settings *set,
                    rtb_real x, rtb_real dt, rtb_real *force);

/* Evaluate a trial step without touching the committed state `s`: the result
 * goes into `trial` (may not alias `s`), its force into *force, and the
 * analytic tangent dF/dx of the discrete step into *dforce_dx (may be NULL).
 * A host's implicit iterations call this many times per step, then commit. */
rtb_status rtb_evaluate(const rtb_state *s, const rtb_params *p,
                        const rtb_settings *set, rtb_real x, rtb_real dt,
                        rtb_state *trial, rtb_real *force, rtb_real *dforce_dx);

/* Make a trial state the committed one (a plain copy, provided for clarity). */
rtb_status rtb_commit(rtb_state *s, const rtb_state *trial);

/* ------------------------------------------------------------------ */
/* Inspection                                                          */
/* ------------------------------------------------------------------ */

/* Copy the N cell DOFs y_k into out[0..cap-1]; returns the count or < 0. */
int rtb_cell_states(const rtb_state *s, rtb_real *out, int cap);

typedef struct rtb_info {
  int abi_version;
  int max_cells;
  int scalar_bytes;
  const char *version;   /* library version string, "major.minor.patch" */
  const char *scalar;    /* "double" */
} rtb_info;

void rtb_get_info(rtb_info *info);

/* Static force for a displacement held forever: every dashpot has relaxed,
 * F = K0 x + x / (1/Kpa + N/Kr) (+ elastic extensions). RT only. */
rtb_real rtb_static_force(const rtb_params *p, rtb_real x);

#ifdef __cplusplus
}
#endif
#endif /* RT_BUSHING_H */
