/* host_test.c -- an FMI 2.0 co-simulation master, written from the standard,
 * that imports build/fmu/rt_bushing.fmu and checks it against the C library:
 *
 *   fmu_host FMU [RTB_CLI WORKDIR]
 *
 *  1. modelDescription.xml: version, capabilities, the six inputs and
 *     outputs, 6 x 21 parameters, outputs without direct feedthrough.
 *  2. Master loop with variable communication steps, six different channels
 *     and a parameter tuned mid-run: every output bit-for-bit equal to
 *     rtb_step on the same axis; a second instance, interleaved, equal to
 *     rtb_bushing6_step (the instances share nothing).
 *  3. Rollback (fmi2Get/SetFMUstate) and serialization: bit-identical replay,
 *     also in another instance and after a refused step.
 *  4. Bad calls: fmi2Error/fmi2Discard with a logged message, never a crash.
 *  5. With RTB_CLI: axis x against `rtb simulate` to 1e-9 relative, the other
 *     outputs exactly 0.
 * Every allocation of the FMU goes through the host's callbacks, and all are
 * freed. Exit status 0 on success.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "host_support.h"

static const char *const kOutputs[RTB_AXES] = {"fx", "fy", "fz", "mx", "my", "mz"};

typedef struct sim {
  const fmu_file *f;
  fmi2Component c;
  fmi2CallbackFunctions cb;
  host_log log;
  fmi2ValueReference in[RTB_AXES], out[RTB_AXES];
  double t;
} sim;

static int sim_instantiate(sim *s, const fmu_file *f, const char *name) {
  memset(s, 0, sizeof *s);
  s->f = f;
  s->cb = host_callbacks(&s->log);
  for (int a = 0; a < RTB_AXES; ++a) {
    s->in[a] = vr_of(&f->md, rtb_axis_name(a));
    s->out[a] = vr_of(&f->md, kOutputs[a]);
  }
  s->c = f->api.Instantiate(name, fmi2CoSimulation, f->md.guid, "file:///nonexistent", &s->cb,
                            fmi2False, fmi2False);
  CHECK(s->c != NULL, "fmi2Instantiate(%s) returned NULL", name);
  return s->c != NULL;
}

/* Switch every axis on (a compiled-in bushing may have some off), so the
 * checks below see six working channels; `ref` follows. */
static void activate_all(sim *s, rtb_bushing6_params *ref) {
  for (int a = 0; a < RTB_AXES; ++a) {
    char name[16];
    snprintf(name, sizeof name, "%s.active", rtb_axis_name(a));
    const fmi2ValueReference vr = vr_of(&s->f->md, name);
    const fmi2Boolean on = fmi2True;
    CHECK(s->f->api.SetBoolean(s->c, &vr, 1, &on) == fmi2OK, "set %s: %s", name, s->log.last);
    if (ref) ref->active[a] = 1;
  }
}

static int sim_initialize(sim *s, const double x0[RTB_AXES]) {
  const fmi2_api *api = &s->f->api;
  int ok = api->SetupExperiment(s->c, fmi2False, 0.0, 0.0, fmi2False, 0.0) == fmi2OK;
  ok = ok && api->EnterInitializationMode(s->c) == fmi2OK;
  ok = ok && api->SetReal(s->c, s->in, RTB_AXES, x0) == fmi2OK;
  ok = ok && api->ExitInitializationMode(s->c) == fmi2OK;
  CHECK(ok, "initialization failed: %s", s->log.last);
  s->t = 0.0;
  return ok;
}

/* Set the inputs for the end of the step, take it, read the outputs. */
static fmi2Status sim_step(sim *s, const double x[RTB_AXES], double h, double F[RTB_AXES]) {
  const fmi2_api *api = &s->f->api;
  if (api->SetReal(s->c, s->in, RTB_AXES, x) != fmi2OK) return fmi2Error;
  const fmi2Status st = api->DoStep(s->c, s->t, h, fmi2True);
  if (st == fmi2OK || st == fmi2Warning) s->t += h;
  if (api->GetReal(s->c, s->out, RTB_AXES, F) != fmi2OK) return fmi2Error;
  return st;
}

static void set_real(sim *s, const char *name, double v) {
  const fmi2ValueReference vr = vr_of(&s->f->md, name);
  CHECK(s->f->api.SetReal(s->c, &vr, 1, &v) == fmi2OK, "set %s: %s", name, s->log.last);
}

static double input(int axis, int which, double t) {
  const double amp = axis >= RTB_AXIS_RX ? 0.02 : 0.5; /* rad / mm */
  return amp * (which ? -2.0 : 1.0) * sin(2.0 * M_PI * (1.0 + axis) * t) + 0.01 * (axis + 1);
}

static double step_size(int i) { return i % 3 == 0 ? 2e-3 : i % 3 == 1 ? 1e-3 : 5e-4; }

/* ------------------------------------------------------------------ 1 */
static void check_model_description(const md_info *md) {
  CHECK(strcmp(md->fmi_version, "2.0") == 0, "fmiVersion %s", md->fmi_version);
  CHECK(strcmp(md->model_identifier, "rt_bushing") == 0, "modelIdentifier %s",
        md->model_identifier);
  CHECK(md->can_get_set_state && md->can_serialize_state && md->variable_step,
        "capabilities: canGetAndSetFMUstate %d canSerializeFMUstate %d variable step %d",
        md->can_get_set_state, md->can_serialize_state, md->variable_step);
  for (int a = 0; a < RTB_AXES; ++a) {
    const md_var *in = md_find(md, rtb_axis_name(a)), *out = md_find(md, kOutputs[a]);
    char k0[16];
    snprintf(k0, sizeof k0, "%s.K0", rtb_axis_name(a));
    const md_var *p = md_find(md, k0);
    CHECK(in && strcmp(in->causality, "input") == 0 && strcmp(in->type, "Real") == 0,
          "input %s", rtb_axis_name(a));
    CHECK(out && strcmp(out->causality, "output") == 0, "output %s", kOutputs[a]);
    CHECK(p && strcmp(p->variability, "tunable") == 0, "tunable parameter %s", k0);
    if (in && out)
      CHECK(strcmp(in->unit, a < RTB_AXIS_RX ? "mm" : "rad") == 0 &&
                strcmp(out->unit, a < RTB_AXIS_RX ? "N" : "N.mm") == 0,
            "units of %s: %s -> %s", rtb_axis_name(a), in->unit, out->unit);
  }
  CHECK(md->n_output_unknowns == RTB_AXES && md->output_dependencies_empty,
        "ModelStructure: %d outputs, dependencies empty %d", md->n_output_unknowns,
        md->output_dependencies_empty);
}

/* ------------------------------------------------------------------ 2 */
/* Instance A: six different channels set through the FMI interface; the
 * reference is rtb_step per axis. Instance B: the compiled-in bushing driven
 * by other inputs; the reference is rtb_bushing6_step. */
static void configure_mixed(sim *s, rtb_bushing6_params *ref) {
  const fmi2ValueReference vy = vr_of(&s->f->md, "y.integrator"),
                           vz = vr_of(&s->f->md, "z.model"), vc = vr_of(&s->f->md, "ry.cells"),
                           vrz = vr_of(&s->f->md, "rz.active");
  activate_all(s, ref);
  const fmi2Integer one = RTB_INTEGRATOR_BE, sts = RTB_MODEL_STS, five = 5;
  const fmi2Boolean off = fmi2False;
  CHECK(s->f->api.SetInteger(s->c, &vy, 1, &one) == fmi2OK &&
            s->f->api.SetInteger(s->c, &vz, 1, &sts) == fmi2OK &&
            s->f->api.SetInteger(s->c, &vc, 1, &five) == fmi2OK &&
            s->f->api.SetBoolean(s->c, &vrz, 1, &off) == fmi2OK,
        "setting fixed parameters: %s", s->log.last);
  set_real(s, "rx.k3", 50.0);
  set_real(s, "rx.viscous_c", 2.0);
  ref->axis[RTB_AXIS_Y].integrator = RTB_INTEGRATOR_BE;
  ref->axis[RTB_AXIS_Z].model = RTB_MODEL_STS;
  ref->axis[RTB_AXIS_RY].cells = 5;
  ref->active[RTB_AXIS_RZ] = 0;
  ref->axis[RTB_AXIS_RX].k3 = 50.0;
  ref->axis[RTB_AXIS_RX].viscous_c = 2.0;
}

static void test_library_match(const fmu_file *f, const rtb_bushing6_params *start) {
  rtb_bushing6_params ra = *start, rb = *start;
  sim A, B;
  if (!sim_instantiate(&A, f, "A") || !sim_instantiate(&B, f, "B")) return;
  configure_mixed(&A, &ra);
  activate_all(&B, &rb);
  double x0[RTB_AXES], xa[RTB_AXES], xb[RTB_AXES], Fa[RTB_AXES], Fb[RTB_AXES], Fr[RTB_AXES];
  for (int a = 0; a < RTB_AXES; ++a) x0[a] = input(a, 0, 0.0);
  if (!sim_initialize(&A, x0) || !sim_initialize(&B, x0)) return;
  rtb_state ref_a[RTB_AXES];
  rtb_bushing6_state ref_b;
  for (int a = 0; a < RTB_AXES; ++a)
    if (ra.active[a]) CHECK(rtb_state_init(&ref_a[a], &ra.axis[a], x0[a]) == RTB_OK, "ref init");
  CHECK(rtb_bushing6_init(&ref_b, &rb, x0, NULL) == RTB_OK, "ref6 init");
  CHECK(f->api.GetReal(A.c, A.out, RTB_AXES, Fa) == fmi2OK &&
            Fa[RTB_AXIS_X] == rtb_static_force(&ra.axis[RTB_AXIS_X], x0[RTB_AXIS_X]),
        "initial output fx = %.17g", Fa[RTB_AXIS_X]);

  int mismatches = 0;
  for (int i = 1; i <= 400; ++i) {
    const double h = step_size(i), t1 = A.t + h;
    for (int a = 0; a < RTB_AXES; ++a) xa[a] = input(a, 0, t1), xb[a] = input(a, 1, t1);
    if (i == 200) { /* a tunable parameter between two steps */
      set_real(&A, "x.K0", 1500.0);
      ra.axis[RTB_AXIS_X].K0 = 1500.0;
    }
    CHECK(sim_step(&A, xa, h, Fa) == fmi2OK && sim_step(&B, xb, h, Fb) == fmi2OK,
          "step %d: %s %s", i, A.log.last, B.log.last);
    for (int a = 0; a < RTB_AXES; ++a) {
      Fr[a] = 0.0;
      if (ra.active[a]) rtb_step(&ref_a[a], &ra.axis[a], NULL, xa[a], h, &Fr[a]);
    }
    mismatches += memcmp(Fa, Fr, sizeof Fr) != 0;
    CHECK(rtb_bushing6_step(&ref_b, &rb, NULL, xb, h, Fr, NULL) >= 0, "ref6 step");
    mismatches += memcmp(Fb, Fr, sizeof Fr) != 0;
  }
  CHECK(mismatches == 0, "%d of 800 steps differ from the library (bit for bit)", mismatches);
  if (mismatches == 0) printf("fmu_host: 2 x 400 variable steps bit-for-bit equal to the library\n");
  CHECK(Fa[RTB_AXIS_RZ] == 0.0 && Fa[RTB_AXIS_Z] != 0.0 && Fa[RTB_AXIS_Z] != Fb[RTB_AXIS_Z],
        "the off axis gives 0, the others differ");
  double t_last = -1.0;
  CHECK(f->api.GetRealStatus(A.c, fmi2LastSuccessfulTime, &t_last) == fmi2OK && t_last == A.t,
        "fmi2LastSuccessfulTime %.17g, expected %.17g", t_last, A.t);
  CHECK(f->api.Terminate(A.c) == fmi2OK && f->api.Terminate(B.c) == fmi2OK, "terminate");
  f->api.FreeInstance(A.c);
  f->api.FreeInstance(B.c);
}

/* ------------------------------------------------------------------ 3 */
#define REPLAY 50

static void run_steps(sim *s, int first, double F[REPLAY][RTB_AXES]) {
  for (int i = 0; i < REPLAY; ++i) {
    double x[RTB_AXES];
    const double h = step_size(first + i);
    for (int a = 0; a < RTB_AXES; ++a) x[a] = input(a, 0, s->t + h);
    CHECK(sim_step(s, x, h, F[i]) == fmi2OK, "replay step %d: %s", i, s->log.last);
  }
}

static void test_rollback(const fmu_file *f) {
  const int f0 = g_failures;
  const fmi2_api *api = &f->api;
  sim A, C;
  double zero[RTB_AXES] = {0}, first[REPLAY][RTB_AXES], again[REPLAY][RTB_AXES];
  double none[REPLAY][RTB_AXES];
  if (!sim_instantiate(&A, f, "rollback")) return;
  activate_all(&A, NULL);
  if (!sim_initialize(&A, zero)) return;
  run_steps(&A, 0, none);
  fmi2FMUstate S = NULL;
  CHECK(api->GetFMUstate(A.c, &S) == fmi2OK && S, "fmi2GetFMUstate");
  const double t_saved = A.t;
  run_steps(&A, REPLAY, first);
  CHECK(api->SetFMUstate(A.c, S) == fmi2OK, "fmi2SetFMUstate");
  A.t = t_saved;
  run_steps(&A, REPLAY, again);
  CHECK(memcmp(first, again, sizeof first) == 0, "replay after fmi2SetFMUstate differs");

  /* A refused step (negative h) puts the instance in the error state; a
   * rollback revives it and the replay is still identical. */
  const int errors = A.log.errors;
  CHECK(api->DoStep(A.c, A.t, -1e-3, fmi2True) == fmi2Error && A.log.errors > errors,
        "negative step not refused with a message");
  CHECK(api->DoStep(A.c, A.t, 1e-3, fmi2True) == fmi2Error, "step allowed in the error state");
  CHECK(api->SetFMUstate(A.c, S) == fmi2OK, "fmi2SetFMUstate after an error");
  A.t = t_saved;
  run_steps(&A, REPLAY, again);
  CHECK(memcmp(first, again, sizeof first) == 0, "replay after an error differs");

  /* Serialized, then restored into another instance. */
  size_t size = 0;
  CHECK(api->SerializedFMUstateSize(A.c, S, &size) == fmi2OK && size > 0, "state size");
  fmi2Byte *bytes = (fmi2Byte *)malloc(size);
  CHECK(api->SerializeFMUstate(A.c, S, bytes, size) == fmi2OK, "serialize");
  CHECK(api->FreeFMUstate(A.c, &S) == fmi2OK && S == NULL, "free state");
  fmi2FMUstate S2 = NULL;
  if (sim_instantiate(&C, f, "restored")) {
    CHECK(api->DeSerializeFMUstate(C.c, bytes, size, &S2) == fmi2OK, "deserialize");
    CHECK(api->SetFMUstate(C.c, S2) == fmi2OK, "set deserialized state");
    C.t = t_saved;
    run_steps(&C, REPLAY, again);
    CHECK(memcmp(first, again, sizeof first) == 0, "replay from serialized state differs");
    /* Damaged bytes are refused with a message. */
    fmi2FMUstate bad = NULL;
    const int e0 = C.log.errors;
    CHECK(api->DeSerializeFMUstate(C.c, bytes, size - 1, &bad) == fmi2Error && !bad,
          "truncated state accepted");
    bytes[0] ^= 0x55;
    CHECK(api->DeSerializeFMUstate(C.c, bytes, size, &bad) == fmi2Error && !bad,
          "state with a bad magic accepted");
    CHECK(C.log.errors == e0 + 2, "deserialization errors not logged");
    CHECK(api->FreeFMUstate(C.c, &S2) == fmi2OK, "free state 2");
    api->FreeInstance(C.c);
  }
  free(bytes);
  api->FreeInstance(A.c);
  if (g_failures == f0)
    printf("fmu_host: rollback and serialized state replay bit-identically (%zu bytes)\n", size);
}

/* ------------------------------------------------------------------ 4 */
/* `call` must return `expected` and log at least one error message. */
#define EXPECT_REFUSED(s, call, expected)                                              \
  do {                                                                                 \
    const int e0_ = (s)->log.errors + (s)->log.messages;                               \
    const fmi2Status st_ = (call);                                                     \
    CHECK(st_ == (expected), "%s returned %d", #call, (int)st_);                       \
    CHECK((s)->log.errors + (s)->log.messages > e0_, "%s logged nothing", #call);      \
  } while (0)

static void test_null_component(const fmu_file *f) {
  const fmi2_api *api = &f->api;
  fmi2ValueReference vr = 0;
  double r = 0;
  int i = 0;
  fmi2FMUstate st = NULL;
  size_t n = 0;
  fmi2String str = NULL;
  fmi2Status s2 = fmi2OK;
  int fails = 0;
  fails += api->SetDebugLogging(NULL, fmi2True, 0, NULL) != fmi2Error;
  fails += api->SetupExperiment(NULL, 0, 0, 0, 0, 0) != fmi2Error;
  fails += api->EnterInitializationMode(NULL) != fmi2Error;
  fails += api->ExitInitializationMode(NULL) != fmi2Error;
  fails += api->Terminate(NULL) != fmi2Error;
  fails += api->Reset(NULL) != fmi2Error;
  fails += api->GetReal(NULL, &vr, 1, &r) != fmi2Error;
  fails += api->GetInteger(NULL, &vr, 1, &i) != fmi2Error;
  fails += api->GetBoolean(NULL, &vr, 1, &i) != fmi2Error;
  fails += api->GetString(NULL, &vr, 1, &str) != fmi2Error;
  fails += api->SetReal(NULL, &vr, 1, &r) != fmi2Error;
  fails += api->SetInteger(NULL, &vr, 1, &i) != fmi2Error;
  fails += api->SetBoolean(NULL, &vr, 1, &i) != fmi2Error;
  fails += api->SetString(NULL, &vr, 1, &str) != fmi2Error;
  fails += api->GetFMUstate(NULL, &st) != fmi2Error;
  fails += api->SetFMUstate(NULL, st) != fmi2Error;
  fails += api->FreeFMUstate(NULL, &st) != fmi2Error;
  fails += api->SerializedFMUstateSize(NULL, st, &n) != fmi2Error;
  fails += api->SerializeFMUstate(NULL, st, NULL, 0) != fmi2Error;
  fails += api->DeSerializeFMUstate(NULL, NULL, 0, &st) != fmi2Error;
  fails += api->GetDirectionalDerivative(NULL, &vr, 1, &vr, 1, &r, &r) != fmi2Error;
  fails += api->EnterEventMode(NULL) != fmi2Error;
  fails += api->NewDiscreteStates(NULL, NULL) != fmi2Error;
  fails += api->EnterContinuousTimeMode(NULL) != fmi2Error;
  fails += api->CompletedIntegratorStep(NULL, 0, &i, &i) != fmi2Error;
  fails += api->SetTime(NULL, 0) != fmi2Error;
  fails += api->SetContinuousStates(NULL, &r, 1) != fmi2Error;
  fails += api->GetDerivatives(NULL, &r, 1) != fmi2Error;
  fails += api->GetEventIndicators(NULL, &r, 1) != fmi2Error;
  fails += api->GetContinuousStates(NULL, &r, 1) != fmi2Error;
  fails += api->GetNominalsOfContinuousStates(NULL, &r, 1) != fmi2Error;
  fails += api->SetRealInputDerivatives(NULL, &vr, 1, &i, &r) != fmi2Error;
  fails += api->GetRealOutputDerivatives(NULL, &vr, 1, &i, &r) != fmi2Error;
  fails += api->DoStep(NULL, 0, 1e-3, 0) != fmi2Error;
  fails += api->CancelStep(NULL) != fmi2Error;
  fails += api->GetStatus(NULL, fmi2DoStepStatus, &s2) != fmi2Error;
  fails += api->GetRealStatus(NULL, fmi2LastSuccessfulTime, &r) != fmi2Error;
  fails += api->GetIntegerStatus(NULL, fmi2DoStepStatus, &i) != fmi2Error;
  fails += api->GetBooleanStatus(NULL, fmi2Terminated, &i) != fmi2Error;
  fails += api->GetStringStatus(NULL, fmi2PendingStatus, &str) != fmi2Error;
  api->FreeInstance(NULL);
  CHECK(fails == 0, "%d functions did not return fmi2Error for a NULL component", fails);
}

static void test_instantiate_refusals(const fmu_file *f) {
  host_log log;
  memset(&log, 0, sizeof log);
  fmi2CallbackFunctions cb = host_callbacks(&log);
  CHECK(!f->api.Instantiate("g", fmi2CoSimulation, "{wrong}", NULL, &cb, 0, 0), "wrong GUID");
  CHECK(!f->api.Instantiate("m", fmi2ModelExchange, f->md.guid, NULL, &cb, 0, 0), "ME");
  CHECK(!f->api.Instantiate("", fmi2CoSimulation, f->md.guid, NULL, &cb, 0, 0), "empty name");
  CHECK(!f->api.Instantiate("n", fmi2CoSimulation, f->md.guid, NULL, NULL, 0, 0), "no callbacks");
  CHECK(log.errors == 3, "%d refusals logged, expected 3", log.errors);
  CHECK(strcmp(f->api.GetVersion(), "2.0") == 0 &&
            strcmp(f->api.GetTypesPlatform(), "default") == 0,
        "fmi2GetVersion / fmi2GetTypesPlatform");
}

/* Reset (allowed in every state) then initialize again. */
static void revive(sim *s) {
  const double zero[RTB_AXES] = {0};
  CHECK(s->f->api.Reset(s->c) == fmi2OK, "reset");
  activate_all(s, NULL);
  sim_initialize(s, zero);
}

static void test_bad_calls(const fmu_file *f) {
  const int f0 = g_failures;
  const fmi2_api *api = &f->api;
  test_null_component(f);
  test_instantiate_refusals(f);
  sim s;
  if (!sim_instantiate(&s, f, "bad")) return;
  activate_all(&s, NULL);
  double F[RTB_AXES], x[RTB_AXES] = {0.1, 0, 0, 0, 0, 0};
  fmi2ValueReference unknown = 99999, cells = vr_of(&f->md, "x.cells");
  fmi2Integer n = 3;
  fmi2String str = "s";
  EXPECT_REFUSED(&s, api->DoStep(s.c, 0.0, 1e-3, fmi2True), fmi2Error); /* not initialized */
  revive(&s);
  EXPECT_REFUSED(&s, api->GetReal(s.c, NULL, 1, F), fmi2Error);
  revive(&s);
  EXPECT_REFUSED(&s, api->GetReal(s.c, &unknown, 1, F), fmi2Error);
  revive(&s);
  EXPECT_REFUSED(&s, api->SetReal(s.c, s.out, 1, F), fmi2Error); /* an output */
  revive(&s);
  EXPECT_REFUSED(&s, api->SetInteger(s.c, &cells, 1, &n), fmi2Error); /* fixed, after init */
  revive(&s);
  EXPECT_REFUSED(&s, api->SetString(s.c, &unknown, 1, &str), fmi2Error);
  revive(&s);
  EXPECT_REFUSED(&s, api->DoStep(s.c, 0.5, 1e-3, fmi2True), fmi2Error); /* wrong time */
  revive(&s);
  EXPECT_REFUSED(&s, api->DoStep(s.c, 0.0, 0.0, fmi2True), fmi2Error);
  revive(&s);
  EXPECT_REFUSED(&s, api->DoStep(s.c, 0.0, NAN, fmi2True), fmi2Error);
  revive(&s);
  /* A bad input value or parameter: refused, the outputs keep their values. */
  CHECK(sim_step(&s, x, 1e-3, F) == fmi2OK, "good step");
  double before[RTB_AXES], after[RTB_AXES];
  memcpy(before, F, sizeof F);
  x[RTB_AXIS_RY] = NAN;
  EXPECT_REFUSED(&s, sim_step(&s, x, 1e-3, after), fmi2Error);
  CHECK(strstr(s.log.last, "axis ry") != NULL, "message does not name the axis: %s", s.log.last);
  CHECK(memcmp(before, after, sizeof F) == 0, "outputs changed by a refused step");
  revive(&s);
  set_real(&s, "x.alpha", 5.0);
  x[RTB_AXIS_RY] = 0.0;
  EXPECT_REFUSED(&s, sim_step(&s, x, 1e-3, after), fmi2Error);
  CHECK(strstr(s.log.last, "x.alpha") != NULL, "message does not name the parameter: %s",
        s.log.last);
  revive(&s);
  /* Functions that do not apply to a co-simulation FMU. */
  double r = 0;
  int i = 0;
  fmi2ValueReference vr = s.out[0];
  EXPECT_REFUSED(&s, api->GetDirectionalDerivative(s.c, &vr, 1, s.in, 1, &r, &r), fmi2Error);
  revive(&s);
  EXPECT_REFUSED(&s, api->EnterEventMode(s.c), fmi2Error);
  revive(&s);
  EXPECT_REFUSED(&s, api->SetTime(s.c, 1.0), fmi2Error);
  revive(&s);
  EXPECT_REFUSED(&s, api->GetDerivatives(s.c, &r, 1), fmi2Error);
  revive(&s);
  EXPECT_REFUSED(&s, api->SetRealInputDerivatives(s.c, s.in, 1, &i, &r), fmi2Error);
  revive(&s);
  EXPECT_REFUSED(&s, api->CancelStep(s.c), fmi2Error);
  revive(&s);
  fmi2Status ds;
  EXPECT_REFUSED(&s, api->GetStatus(s.c, fmi2DoStepStatus, &ds), fmi2Discard);
  CHECK(sim_step(&s, x, 1e-3, F) == fmi2OK, "the instance works after the refusals: %s",
        s.log.last);
  api->FreeInstance(s.c);
  if (g_failures == f0) printf("fmu_host: bad calls refused with messages\n");
}

/* ------------------------------------------------------------------ 5 */
#define SIM_ROWS 800

static int read_simulate_csv(const char *path, double *F, int cap) {
  FILE *in = fopen(path, "r");
  if (!in) return 0;
  char line[1024];
  int n = 0, header = 0;
  while (fgets(line, sizeof line, in) && n < cap) {
    if (line[0] == '#') continue;
    if (!header) { /* time,displacement,force */
      header = 1;
      continue;
    }
    char *p = strchr(line, ',');
    p = p ? strchr(p + 1, ',') : NULL;
    if (p) F[n++] = strtod(p + 1, NULL);
  }
  fclose(in);
  return n;
}

static void test_against_simulate(const fmu_file *f, const rtb_bushing6_params *start,
                                  const char *rtb, const char *dir) {
  static double t[SIM_ROWS], x[SIM_ROWS], Fsim[SIM_ROWS];
  char json[512], csv[512], out[512], cmd[2048];
  snprintf(json, sizeof json, "%s/fmu_host_x.json", dir);
  snprintf(csv, sizeof csv, "%s/fmu_host_x.csv", dir);
  snprintf(out, sizeof out, "%s/fmu_host_x_sim.csv", dir);
  CHECK(write_params_json(json, &start->axis[RTB_AXIS_X]), "write %s", json);
  FILE *c = fopen(csv, "w");
  if (!c) return;
  fprintf(c, "time,displacement\n");
  for (int i = 0; i < SIM_ROWS; ++i) {
    t[i] = i * 1e-3;
    x[i] = 0.8 * sin(2.0 * M_PI * 3.0 * t[i]) + 0.3 * sin(2.0 * M_PI * 11.0 * t[i]);
    fprintf(c, "%.17g,%.17g\n", t[i], x[i]);
  }
  fclose(c);
  snprintf(cmd, sizeof cmd, "'%s' simulate --params '%s' --input '%s' --out '%s' --quiet", rtb,
           json, csv, out);
  CHECK(system(cmd) == 0, "`%s` failed", cmd);
  CHECK(read_simulate_csv(out, Fsim, SIM_ROWS) == SIM_ROWS, "%s: expected %d rows", out, SIM_ROWS);

  sim s;
  double zero[RTB_AXES] = {0}, F[RTB_AXES], in[RTB_AXES] = {0}, scale = 0.0, worst = 0.0;
  if (!sim_instantiate(&s, f, "simulate")) return;
  activate_all(&s, NULL);
  if (!sim_initialize(&s, zero)) return;
  for (int i = 0; i < SIM_ROWS; ++i) scale = fmax(scale, fabs(Fsim[i]));
  int nonzero_other = 0;
  for (int i = 1; i < SIM_ROWS; ++i) {
    in[RTB_AXIS_X] = x[i];
    CHECK(sim_step(&s, in, t[i] - t[i - 1], F) == fmi2OK, "step %d", i);
    worst = fmax(worst, fabs(F[RTB_AXIS_X] - Fsim[i]) / scale);
    for (int a = 1; a < RTB_AXES; ++a) nonzero_other += F[a] != 0.0;
  }
  CHECK(scale > 0.0 && worst <= 1e-9, "fx vs rtb simulate: %.3g relative (max |F| %.6g)", worst,
        scale);
  CHECK(nonzero_other == 0, "%d nonzero outputs on the undriven axes", nonzero_other);
  f->api.FreeInstance(s.c);
  remove(json), remove(csv), remove(out);
  printf("fmu_host: fx matches rtb simulate to %.3g relative over %d steps\n", worst,
         SIM_ROWS - 1);
}

int main(int argc, char **argv) {
  if (argc != 2 && argc != 4) {
    fprintf(stderr, "usage: fmu_host FMU [RTB_CLI WORKDIR]\n");
    return 2;
  }
  fmu_file f;
  if (!fmu_open(argv[1], &f)) {
    fmu_close(&f);
    return 1;
  }
  rtb_bushing6_params start;
  check_model_description(&f.md);
  if (reference_params(&f.md, &start) && rtb_bushing6_validate(&start, NULL) == RTB_OK) {
    test_library_match(&f, &start);
    test_rollback(&f);
    test_bad_calls(&f);
    if (argc == 4) test_against_simulate(&f, &start, argv[2], argv[3]);
  } else {
    CHECK(0, "the start values of modelDescription.xml are not a valid bushing");
  }
  CHECK(host_live_allocations() == 0 && host_total_allocations() > 0,
        "%ld of %ld FMU allocations not freed", host_live_allocations(),
        host_total_allocations());
  fmu_close(&f);
  if (g_failures) {
    fprintf(stderr, "fmu_host: %d failure(s)\n", g_failures);
    return 1;
  }
  printf("fmu_host: OK (%ld allocations through the host's callbacks, all freed)\n",
         host_total_allocations());
  return 0;
}
