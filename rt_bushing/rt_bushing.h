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
 *
 * Thread safety: the library has no global mutable state. Calls on distinct
 * rtb_state objects may run concurrently in any number of threads. The
 * read-only inputs (rtb_params, rtb_settings, and the committed state `s` of
 * rtb_evaluate) may be shared between threads as long as no thread writes
 * them meanwhile; a state that is written (rtb_step, rtb_commit, the `trial`
 * of rtb_evaluate, rtb_state_init) must be used by one thread at a time.
 * rtb_status_message and rtb_get_info return pointers to constant strings.
 *
 * Stack: every library function's own frame is at most RTB_STACK_FRAME_MAX
 * bytes (checked at build time with GCC's -Wstack-usage, see CMakeLists.txt),
 * and the deepest call chain (rtb_evaluate with a clearance: API -> step ->
 * clearance -> response -> chain advance -> stage solve -> dashpot law) uses
 * at most RTB_STACK_DEPTH_MAX bytes in an optimised x86-64 build (the
 * single-axis chain measured 10.4 KiB at -O3, 12.2 KiB at -O2 by
 * tests/step_info_test.cpp, which paints a thread's stack; rtb_bushing6_*
 * adds its own frame; sanitizer and -O0 builds use more). Reserve at least
 * that much for a real-time thread that calls the library.
 */
#ifndef RT_BUSHING_H
#define RT_BUSHING_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* Exported functions. The library is built with -fvisibility=hidden: only
 * the functions marked RTB_API are visible outside a shared build. */
#ifndef RTB_API /* a host that links the sources into its own binary (the FMU) may
                   define it empty to keep every rtb_ symbol internal */
#if defined(__GNUC__)
#define RTB_API __attribute__((visibility("default")))
#else
#define RTB_API
#endif
#endif

#define RTB_STACK_FRAME_MAX 8192   /* bytes, per function (-Wstack-usage); the largest are
                                      rtb_bushing6_init/step (~6.4 KiB: six axis states)
                                      and rtb_step_core (~4.3 KiB) */
#define RTB_STACK_DEPTH_MAX 24576  /* bytes, deepest call chain (rtb_bushing6_step:
                                      its frame + one axis' rtb_step chain) */

/* ------------------------------------------------------------------ */
/* Types                                                               */
/* ------------------------------------------------------------------ */

#define RTB_ABI_VERSION 9     /* bumped on any layout change of the structs
                                 (2: `smoothing`, `sat_force`, `sat_disp` took reserved[0..2];
                                  3: slack, backlash_held, fric_asym, spec_* and the
                                  spectrum memory z_spec in rtb_state; fixed-width
                                  integer fields, struct sizes in rtb_info;
                                  4: rtb_step_info.work, the spent work budget;
                                  5: rtb_settings.max_work, the budget at run time;
                                  6: k2, the quadratic spring, took reserved[0];
                                  7: mullins_whole, the Mullins definition, took reserved[0];
                                  8: mullins_width, the Ogden-Roxburgh shape, took reserved[0];
                                  9: relax_width, the stretch-dependent relaxation, took reserved[0]) */
#define RTB_MAX_CELLS 32      /* capacity of rtb_state; N = 1 .. RTB_MAX_CELLS */
#define RTB_DEFAULT_CELLS 15  /* the paper's choice (section 3.4) */
#define RTB_N_RESERVED 2
#define RTB_MAX_BRANCHES 16  /* capacity of the relaxation spectrum (eight decades) */

/* The scalar: double, or float when compiled with -DRTB_SINGLE (for a
 * microcontroller with a single-precision FPU; the library and every client
 * must agree: RTB_SCALAR_BYTES and rtb_get_info tell which one was built). */
#ifdef RTB_SINGLE
typedef float rtb_real;
#define RTB_SCALAR_BYTES 4    /* sizeof(rtb_real); checked by generated headers */
#else
typedef double rtb_real;
#define RTB_SCALAR_BYTES 8    /* sizeof(rtb_real); checked by generated headers */
#endif

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
  RTB_ERR_SETTINGS = -13,     /* tolerance or iteration limit out of range */
  RTB_ERR_ALIAS = -14,        /* an output struct aliases an input (trial == s) */
  RTB_ERR_CAPACITY = -15      /* a capacity argument is negative */
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
  int32_t abi_version;   /* = RTB_ABI_VERSION */
  int32_t model;         /* rtb_model */
  int32_t cells;         /* N */
  int32_t integrator;    /* rtb_integrator (RT only; STS is rate-independent) */

  /* Core parameters p = (K0, Kpa, Kr, C0, alpha), eq. (2) and (11). */
  rtb_real K0;       /* global elastic stiffness [force/length]; the static
                        tangent at x = 0, K0 + 1/(1/Kpa + N/Kr) + sat_force/
                        sat_disp (rtb_static_force), must be >= 0. K0 < 0 is
                        for a softening spring that takes more than K0 at
                        large strain (the static law may then fall there;
                        with slack K0 + 1/(1/Kpa + N/Kr) >= 0, and K0 >= 0
                        with slack and relax_width: a floating end needs a
                        law that rises again) */
  rtb_real Kpa;      /* low-amplitude stiffness, > 0         [force/length] */
  rtb_real Kr;       /* cell spring stiffness, > 0           [force/length] */
  rtb_real C0;       /* RT dashpot coefficient, > 0  [force (time/length)^alpha] */
  rtb_real alpha;    /* RT dashpot exponent, [RTB_ALPHA_MIN, 1) */
  rtb_real Ff;       /* STS friction threshold, > 0 (STS only)    [force] */

  /* Physical extensions (issue #4); all act on the bushing displacement xb,
   * which equals the input x unless a backlash is set. */
  rtb_real k3;          /* cubic spring: F += k3 xb^3            [force/length^3] */
  rtb_real k_asym;      /* asymmetry: F += k_asym |xb|; stiffness K0+k_asym in
                           tension, K0-k_asym in compression; |k_asym| <=
                           K0 + 1/(1/Kpa + cells/Kr) + sat_force/sat_disp
                           (sat term 0 with slack): the static tangent stays
                           >= 0 on both sides, rtb_static_force */
  rtb_real maxwell_k;   /* extra Maxwell branch stiffness, >= 0  [force/length] */
  rtb_real maxwell_tau; /* its relaxation time, > 0 when maxwell_k > 0 [time] */
  rtb_real viscous_c;   /* parallel linear dashpot: F += c v, >= 0 [force time/length] */
  rtb_real mass;        /* inertia in the load path: F += m a, a the input's
                           acceleration at the step's end from the last four
                           samples (no lag where x is smooth; step.cpp,
                           input_motion)          [force time^2/length] */
  rtb_real backlash;    /* total clearance g in series, >= 0     [length] */
  rtb_real mullins;     /* Mullins softening fraction mu in [0, 1) below the
                           prior maximum |xb|: of K0, or of the whole RT force
                           when mullins_whole = 1 */

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
  /* ABI 6 (issue #10), from reserved[0]. */
  rtb_real k2;          /* quadratic spring: F += k2 xb^2, the other common
                           definition of a tension/compression asymmetry
                           (tangent K0 + 2 k2 xb; with k3 the polynomial
                           static law K0 x + k2 x^2 + k3 x^3) [force/length^2] */
  /* ABI 7 (issue #10), from reserved[0]. */
  rtb_real mullins_whole; /* 0: the Mullins softening eta = 1 - mu (1 - |xb|/max)
                           acts on K0 xb only (the equilibrium spring); 1: on
                           the whole RT force eta (K0 xb + Kpa (xb - y1)), i.e.
                           on every stiffness and dashpot of the rubber alike
                           (Ogden-Roxburgh's damage scales the material's
                           stress). Eq. (2) is homogeneous in (Kpa, Kr, C0),
                           so the cells move as without it. Exactly 0 or 1. */
  /* ABI 8 (issue #10), from reserved[0]. */
  rtb_real mullins_width; /* w > 0: the Mullins loss has Ogden and Roxburgh's
                           (1999) erf shape, eta = 1 - mu erf((max^2 - xb^2)/w^2)
                           below the prior max |xb| (their energy form with
                           the elastic energy ~ xb^2): nearly uniform below
                           the max when w << max. 0 (default): the linear
                           eta = 1 - mu (1 - |xb|/max). >= 0      [length] */
  /* ABI 9 (issue #10), from reserved[0]. */
  rtb_real relax_width; /* w > 0: relaxation that weakens with stretch. The
                           relaxing force (the cell chain Kpa (xb - y1), the
                           Maxwell branch, the spectrum) is scaled by
                           g = 1 / sqrt(1 + (xb/w)^2), the equilibrium
                           spring K0 and the elastic extensions are not: the
                           relaxed fraction F(inf)/F(0+) of a hold grows with
                           the stretch (VHB 4910's relaxations). Eq. (2) is
                           homogeneous in (Kpa, Kr, C0), so the cells move as
                           without it (STS: as if Kpa, Kr and Ff scaled
                           alike). 0 (default): off. >= 0         [length] */
  rtb_real reserved[RTB_N_RESERVED];
} rtb_params;

/* Hard work bound per step (issue #11). Every rtb_step / rtb_evaluate spends
 * at most W = rtb_settings.max_work (default RTB_STEP_WORK) units of
 * dashpot-law evaluations, whatever N, the
 * extensions, smoothing or clearance: one unit per eq. (1) evaluation (one
 * exp, one log), 3 per smoothed eq. (14) evaluation (each inverse iteration
 * included), N per STS active-set solve (a response's solves are capped by
 * what is left) and per solve of a near-friction stage's start (alpha <=
 * 0.1: the stage's friction limit, capped likewise, leaving one sweep). A
 * Newton sweep costs N evaluations, a
 * clearance response one or more sweeps; each starts only while a whole
 * sweep is left. The stage starts of the response under way still complete
 * (a consistent iterate needs them), so the hard bound is W + 6 N u
 * (u = 3 with smoothing, else 1): each of two stages starts with at
 * most three sweeps (the pair from the last step, the law at the predicted
 * velocity, rest). rtb_step_info.work reports what a step spent. When the
 * budget runs out the step commits its best iterate and returns
 * RTB_NOT_CONVERGED. A 1 kHz step at N = 15 uses about two sweeps of its
 * moving cells (~22 units at the default tolerance, BM_Extension's input);
 * with the smoothing s = 100 a median of 242 (session 47's smoothed
 * Chebyshev step; 307 in session 36, 387 before), with every extension,
 * smoothing and a clearance 242, at most 835 (459 and 2496 in session 35:
 * tests/smoothed_law_cost_test.cpp).
 * A unit costs ~26-28 ns on the benchmark machine (a 2-vCPU AMD EPYC guest;
 * the linear algebra of the Newton iterations is not counted),
 * so the default bounds a step at ~110 us; a host that needs a tighter bound
 * sets max_work (per call, so per element; or builds with -DRTB_STEP_WORK=W
 * to change the default): at 640 units the slowest of 90 000 steps over
 * 300 random valid configurations measured 24 us and 5.8% of those extreme
 * steps returned unconverged (0.37% at the default; session 46's library
 * 9.5% and 0.44%; session 22's 16.6% and 1.5%), at the price of more
 * RTB_NOT_CONVERGED steps on hard configurations (BM_RandomConfigs/budget:W,
 * docs/benchmarks.md). */
#ifndef RTB_STEP_WORK
#define RTB_STEP_WORK 4096
#endif

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
  X(K0, ANY, FIT, "force/length", "global elastic stiffness, eq. (11)")              \
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
  X(spec_tau_max, NONNEG, SETTING, "time", "relaxation spectrum slowest time")   \
  X(k2, ANY, FIT, "force/length^2", "quadratic spring (asymmetry)")                 \
  X(mullins_whole, FLAG, SETTING, "-", "Mullins softening of the whole RT force (1) or of K0 (0)") \
  X(mullins_width, NONNEG, FIT, "length", "Mullins erf width w (Ogden-Roxburgh), 0 = linear loss") \
  X(relax_width, NONNEG, FIT, "length", "stretch width w of the relaxing force's factor 1/sqrt(1+(xb/w)^2), 0 = off")

/* Numerical settings of the implicit solve. NULL means rtb_settings_default. */
typedef struct rtb_settings {
  rtb_real tol;          /* relative residual tolerance of each Newton solve
                            (default 1e-8 in double: forces within ~1e-10 of the
                            peak of those at 1e-12, where the offline tool fits;
                            2e-5 in float). A cell whose dashpot moves too slowly
                            to change the residual by 1e-3 tol is held still (no
                            law evaluation) */
  int32_t max_iter;      /* Newton iterations per stage, 1..100 (default 40) */
  int32_t max_backtrack; /* line-search halvings per iteration, 0..60 (default 30) */
  int32_t max_work;      /* work budget of one step, 1..RTB_MAX_WORK units (default
                            RTB_STEP_WORK; see there) */
  int32_t pad_;          /* unused (rtb_settings_default zeroes it) */
} rtb_settings;

#define RTB_MAX_WORK (1 << 24) /* largest rtb_settings.max_work */

/* State of one element. Plain data: copy it to save/restore (host rollback). */
typedef struct rtb_state {
  int32_t abi_version;
  int32_t model;
  int32_t cells;
  int32_t initialised;         /* 1 after rtb_state_init */
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
  rtb_real ax;                 /* input acceleration at the last step's end,
                                  the inertia term's a [length/time^2] */
  rtb_real ax_c;               /* ... as a centred second difference, */
  rtb_real ax_age;             /* ... placed this long before the end
                                  (0: none yet) [time] */
  rtb_real ax_slope;           /* ... and its slope from the one before */
  rtb_real x_dt;               /* length of the last step, any model [time] */
  rtb_real reserved[3];
  int64_t steps;               /* committed steps */
  int32_t last_iterations;     /* Newton iterations used by the last step */
  int32_t contact;             /* phase of the bushing end in the last step:
                                  2 no clearance/slack (xb = x), +1 / -1 in
                                  contact at x - g/2 / x + g/2, 0 floating
                                  free (F = 0), 3 held inside the clearance */
} rtb_state;

/* What one step cost and how well it converged (rtb_step_ex,
 * rtb_evaluate_ex). Counts cover every implicit solve of the step, including
 * the trial bushing positions of a clearance search. */
typedef struct rtb_step_info {
  int32_t iterations;           /* Newton iterations, all stages (RT) or
                                   active-set iterations (STS) */
  int32_t backtracks;           /* line-search halvings, all stages (RT) */
  int32_t clearance_iterations; /* bushing responses of the clearance search
                                   (0 without backlash) */
  int32_t stages;               /* implicit stages of the committed response */
  rtb_real residual;            /* final relative residual |H| / scale of the
                                   committed response (max over its stages;
                                   0 for STS, whose return map is exact) */
  rtb_real clearance_residual;  /* |F| / (scale (|xb| + g)) of the free bushing
                                   end when it is inside the gap, else 0 */
  int32_t work;                 /* units of the step's work budget spent,
                                   at most max_work + 6 N u (see
                                   RTB_STEP_WORK): the headroom a host has */
  int32_t pad_;                 /* zero */
} rtb_step_info;

/* ------------------------------------------------------------------ */
/* Set-up                                                              */
/* ------------------------------------------------------------------ */

/* Fill with the paper's section 3.4 example set (N=15; K0=1000, Kpa=800,
 * Kr=3000 N/mm, C0=40 N (s/mm)^0.2, alpha=0.2; STS: Ff=40 N). */
RTB_API rtb_status rtb_params_default(rtb_params *p, int model);
RTB_API rtb_status rtb_params_validate(const rtb_params *p);
/* rtb_params_validate that also names the offending field ("K0", "cells",
 * "reserved", "maxwell_tau", ...) in *field ("" when valid; field may be
 * NULL). The name is a static string. */
RTB_API rtb_status rtb_params_check(const rtb_params *p, const char **field);
RTB_API void rtb_settings_default(rtb_settings *s);
RTB_API const char *rtb_status_message(rtb_status status);

/* Initialise at rest with every cell DOF at its static equilibrium for the
 * displacement x0 (0 for a virgin bushing). */
RTB_API rtb_status rtb_state_init(rtb_state *s, const rtb_params *p, rtb_real x0);

/* ------------------------------------------------------------------ */
/* Stepping                                                            */
/* ------------------------------------------------------------------ */

/* Advance one step of length dt to displacement x; write the force.
 * On error (< 0) the state is unchanged and *force is not written.
 * `set` may be NULL. */
RTB_API rtb_status rtb_step(rtb_state *s, const rtb_params *p, const rtb_settings *set,
                            rtb_real x, rtb_real dt, rtb_real *force);

/* Evaluate a trial step without touching the committed state `s`: the result
 * goes into `trial` (may not alias `s`: RTB_ERR_ALIAS), its force into *force, and the
 * analytic tangent dF/dx of the discrete step into *dforce_dx (may be NULL).
 * A host's implicit iterations call this many times per step, then commit. */
RTB_API rtb_status rtb_evaluate(const rtb_state *s, const rtb_params *p,
                                const rtb_settings *set, rtb_real x, rtb_real dt,
                                rtb_state *trial, rtb_real *force, rtb_real *dforce_dx);

/* As rtb_step and rtb_evaluate, and also report the step's cost and
 * residuals into *info (may be NULL; not written on error). */
RTB_API rtb_status rtb_step_ex(rtb_state *s, const rtb_params *p, const rtb_settings *set,
                               rtb_real x, rtb_real dt, rtb_real *force, rtb_step_info *info);
RTB_API rtb_status rtb_evaluate_ex(const rtb_state *s, const rtb_params *p,
                                   const rtb_settings *set, rtb_real x, rtb_real dt,
                                   rtb_state *trial, rtb_real *force, rtb_real *dforce_dx,
                                   rtb_step_info *info);

/* Make a trial state the committed one (a plain copy, provided for clarity). */
RTB_API rtb_status rtb_commit(rtb_state *s, const rtb_state *trial);

/* ------------------------------------------------------------------ */
/* Inspection                                                          */
/* ------------------------------------------------------------------ */

/* Copy the first min(N, cap) cell DOFs y_k into out[0..cap-1]; returns that
 * count (>= 0), or RTB_ERR_NULL, RTB_ERR_STATE, RTB_ERR_CAPACITY (cap < 0). */
RTB_API int rtb_cell_states(const rtb_state *s, rtb_real *out, int cap);

typedef struct rtb_info {
  int32_t abi_version;
  int32_t max_cells;
  int32_t scalar_bytes;
  int32_t params_bytes;    /* sizeof(rtb_params) of the library build */
  int32_t state_bytes;     /* sizeof(rtb_state) */
  int32_t settings_bytes;  /* sizeof(rtb_settings) */
  const char *version;     /* library version string, "major.minor.patch" */
  const char *scalar;      /* "double", or "float" (RTB_SINGLE) */
} rtb_info;

RTB_API void rtb_get_info(rtb_info *info);

/* Static force for a displacement held forever: every dashpot has relaxed,
 * F = K0 x + g(x) x / (1/Kpa + N/Kr) (+ elastic extensions), g(x) =
 * 1/sqrt(1 + (x/relax_width)^2) (1 when relax_width = 0). RT only. */
RTB_API rtb_real rtb_static_force(const rtb_params *p, rtb_real x);

/* ================================================================== */
/* Six-axis bushing                                                    */
/* ================================================================== */
/*
 * A chassis bushing as six independent channels (Adams BUSHING style):
 * translations x, y, z and rotations rx, ry, rz. Each channel is a complete
 * single-axis element with its own rtb_params (RT or STS, any extensions, its
 * own N), embedded by value; the channels do not couple, so the 6x6 tangent
 * is diagonal. An axis that is off gives zero force and zero stiffness, and
 * its input is ignored.
 *
 * Units of the rotational channels: the element is unit-agnostic, so a
 * rotational channel reads "length" as angle and "force" as moment. With mm,
 * N, s and rad: input rad, output N mm; K0, Kpa, Kr in N mm/rad; C0 in
 * N mm (s/rad)^alpha; k3 in N mm/rad^3; viscous_c in N mm s/rad; mass in
 * N mm s^2/rad (rotary inertia, tonne mm^2); backlash and sat_disp in rad;
 * Ff and sat_force in N mm; every other field of RTB_PARAM_FIELDS likewise
 * (its "length" is rad, its "force" N mm).
 *
 * Guarantees are those of the single-axis calls: no heap, bounded work
 * (six single-axis steps), and all-or-nothing commit: on an error in ANY axis
 * the committed state is unchanged and no force is written.
 *
 *   rtb_bushing6_params p;  rtb_bushing6_params_default(&p, RTB_MODEL_RT);
 *   rtb_bushing6_state  s;  rtb_bushing6_init(&s, &p, NULL, NULL);
 *   double x[6] = {dx, dy, dz, ax, ay, az}, F[6];   // F = fx fy fz mx my mz
 *   int bad;  rtb_status st = rtb_bushing6_step(&s, &p, NULL, x, dt, F, &bad);
 */

#define RTB_AXES 6

typedef enum rtb_axis {
  RTB_AXIS_X = 0, RTB_AXIS_Y = 1, RTB_AXIS_Z = 2,   /* translations -> fx fy fz */
  RTB_AXIS_RX = 3, RTB_AXIS_RY = 4, RTB_AXIS_RZ = 5 /* rotations -> mx my mz */
} rtb_axis;

typedef struct rtb_bushing6_params {
  int active[RTB_AXES];        /* 1 = on, 0 = off (zero force; axis[] ignored) */
  rtb_params axis[RTB_AXES];   /* one complete parameter set per channel */
} rtb_bushing6_params;

/* Plain data: copy it to save/restore (host rollback). */
typedef struct rtb_bushing6_state {
  rtb_state axis[RTB_AXES];    /* an off axis holds zeros (initialised = 0) */
} rtb_bushing6_state;

/* Every call below that can fail on one axis writes that axis's index to
 * *bad_axis (or -1 when the failure is not an axis's); bad_axis may be NULL. */

/* Every axis on, each with rtb_params_default(model). */
RTB_API rtb_status rtb_bushing6_params_default(rtb_bushing6_params *p, int model);
/* active[] must be 0 or 1 (RTB_ERR_MODEL); each active axis must validate. */
RTB_API rtb_status rtb_bushing6_validate(const rtb_bushing6_params *p, int *bad_axis);
/* Relaxed state at displacements x0[6] (NULL: all zero). */
RTB_API rtb_status rtb_bushing6_init(rtb_bushing6_state *s, const rtb_bushing6_params *p,
                             const rtb_real x0[RTB_AXES], int *bad_axis);
/* Trial step of every axis to x[6] over dt: forces into force[6] and the
 * diagonal of the 6x6 tangent dF/dx into dforce_dx[6] (may be NULL). `s` is
 * never touched; `trial` (may not alias `s`) is complete only on success.
 * The status is the first error, else RTB_NOT_CONVERGED if any axis warned. */
RTB_API rtb_status rtb_bushing6_evaluate(const rtb_bushing6_state *s, const rtb_bushing6_params *p,
                                 const rtb_settings *set, const rtb_real x[RTB_AXES],
                                 rtb_real dt, rtb_bushing6_state *trial,
                                 rtb_real force[RTB_AXES], rtb_real dforce_dx[RTB_AXES],
                                 int *bad_axis);
RTB_API rtb_status rtb_bushing6_commit(rtb_bushing6_state *s, const rtb_bushing6_state *trial);
/* evaluate + commit: on error (< 0) neither *s nor force[] is written. */
RTB_API rtb_status rtb_bushing6_step(rtb_bushing6_state *s, const rtb_bushing6_params *p,
                             const rtb_settings *set, const rtb_real x[RTB_AXES], rtb_real dt,
                             rtb_real force[RTB_AXES], int *bad_axis);
/* "x", "y", "z", "rx", "ry", "rz" (NULL outside 0..5). */
const char *rtb_axis_name(int axis);

#ifdef __cplusplus
}
#endif
#endif /* RT_BUSHING_H */
