/* get_set.c -- fmi2Get/Set for Real, Integer, Boolean and String (FMI 2.0
 * section 2.1.7).
 *
 * A set call is all-or-nothing: every reference is checked (known, settable
 * in this mode) before any value is written. Values are not range-checked
 * here, because a consistent set may pass through invalid combinations while
 * a host sets parameters one at a time (k_asym before K0); the library checks
 * the whole set where it is used (fmi2ExitInitializationMode, fmi2DoStep) and
 * names the offending axis.
 */
#include "fmu_instance.h"
#include "variables.h"

#define GET_MODES                                                                 \
  (FMU_MODE_BIT(FMU_INITIALIZATION) | FMU_MODE_BIT(FMU_STEP_COMPLETE) |           \
   FMU_MODE_BIT(FMU_STEP_FAILED) | FMU_MODE_BIT(FMU_TERMINATED) | FMU_MODE_BIT(FMU_ERROR))
#define SET_MODES                                                                 \
  (FMU_MODE_BIT(FMU_INSTANTIATED) | FMU_MODE_BIT(FMU_INITIALIZATION) |            \
   FMU_MODE_BIT(FMU_STEP_COMPLETE))

typedef void *(*slot_fn)(fmu_data *d, fmi2ValueReference vr, int *role);
static void *real_slot(fmu_data *d, fmi2ValueReference vr, int *r) { return fmu_real_slot(d, vr, r); }
static void *int_slot(fmu_data *d, fmi2ValueReference vr, int *r) { return fmu_int_slot(d, vr, r); }
static void *bool_slot(fmu_data *d, fmi2ValueReference vr, int *r) { return fmu_bool_slot(d, vr, r); }

/* Common checks of a get/set call; fmi2OK when the call may proceed. */
static fmi2Status check_call(fmu_instance *in, const char *func, unsigned modes,
                             const fmi2ValueReference vr[], size_t nvr, const void *value) {
  if (fmu_require_mode(in, func, modes) != fmi2OK) return fmi2Error;
  if (nvr > 0 && (!vr || !value))
    return fmu_fail(in, fmi2Error, "%s: vr or value is NULL with nvr = %zu", func, nvr);
  return fmi2OK;
}

/* Each reference must be known for the type and, for a set, settable now:
 * outputs never, fixed parameters only before initialization ends. */
static fmi2Status check_refs(fmu_instance *in, const char *func, slot_fn slot, int setting,
                             const fmi2ValueReference vr[], size_t nvr) {
  for (size_t i = 0; i < nvr; ++i) {
    int role = 0;
    if (!slot(&in->d, vr[i], &role))
      return fmu_fail(in, fmi2Error, "%s: unknown value reference %u", func, vr[i]);
    if (!setting) continue;
    if (role == FMU_OUTPUT)
      return fmu_fail(in, fmi2Error, "%s: value reference %u is an output", func, vr[i]);
    if (role == FMU_FIXED && in->d.mode == FMU_STEP_COMPLETE)
      return fmu_fail(in, fmi2Error,
                      "%s: value reference %u is a fixed parameter (set it before "
                      "fmi2ExitInitializationMode)",
                      func, vr[i]);
  }
  return fmi2OK;
}

/* In initialization mode the outputs are the static forces the element will
 * start with (rtb_bushing6_init at the current inputs), computed when asked
 * for (a get of parameters alone does not need a valid set). */
static fmi2Status refresh_initial_outputs(fmu_instance *in, const char *func,
                                          const fmi2ValueReference vr[], size_t nvr) {
  if (in->d.mode != FMU_INITIALIZATION) return fmi2OK;
  int role = 0, outputs = 0;
  for (size_t i = 0; i < nvr; ++i)
    outputs += fmu_real_slot(&in->d, vr[i], &role) && role == FMU_OUTPUT;
  if (!outputs) return fmi2OK;
  rtb_bushing6_state s;
  int bad = -1;
  const rtb_status st = rtb_bushing6_init(&s, &in->d.params, in->d.x, &bad);
  if (st != RTB_OK) return fmu_fail_rtb(in, fmi2Error, func, st, bad);
  for (int a = 0; a < RTB_AXES; ++a) in->d.f[a] = s.axis[a].force;
  return fmi2OK;
}

/* One get or set call of any numeric type: checks, then every value moved.
 * fmi2Boolean is stored as 0/1 in an int, fmi2Integer as an int. */
static fmi2Status transfer(fmi2Component c, const char *func, fmu_type type, int setting,
                           const fmi2ValueReference vr[], size_t nvr, const void *src,
                           void *dst) {
  fmu_instance *in = fmu_cast(c);
  if (!in) return fmi2Error;
  const slot_fn slot = type == FMU_REAL ? real_slot : type == FMU_INTEGER ? int_slot : bool_slot;
  if (check_call(in, func, setting ? SET_MODES : GET_MODES, vr, nvr, setting ? src : dst) !=
          fmi2OK ||
      check_refs(in, func, slot, setting, vr, nvr) != fmi2OK ||
      (!setting && type == FMU_REAL && refresh_initial_outputs(in, func, vr, nvr) != fmi2OK))
    return fmi2Error;
  int role;
  for (size_t i = 0; i < nvr; ++i) {
    void *where = slot(&in->d, vr[i], &role);
    if (type == FMU_REAL && setting) *(double *)where = ((const double *)src)[i];
    else if (type == FMU_REAL) ((double *)dst)[i] = *(double *)where;
    else if (setting) *(int *)where = type == FMU_BOOLEAN ? ((const int *)src)[i] != fmi2False
                                                          : ((const int *)src)[i];
    else ((int *)dst)[i] = type == FMU_BOOLEAN ? *(int *)where != 0 : *(int *)where;
  }
  return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2GetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                   fmi2Real value[]) {
  return transfer(c, "fmi2GetReal", FMU_REAL, 0, vr, nvr, NULL, value);
}
FMI2_EXPORT fmi2Status fmi2GetInteger(fmi2Component c, const fmi2ValueReference vr[],
                                      size_t nvr, fmi2Integer value[]) {
  return transfer(c, "fmi2GetInteger", FMU_INTEGER, 0, vr, nvr, NULL, value);
}
FMI2_EXPORT fmi2Status fmi2GetBoolean(fmi2Component c, const fmi2ValueReference vr[],
                                      size_t nvr, fmi2Boolean value[]) {
  return transfer(c, "fmi2GetBoolean", FMU_BOOLEAN, 0, vr, nvr, NULL, value);
}
FMI2_EXPORT fmi2Status fmi2SetReal(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                   const fmi2Real value[]) {
  return transfer(c, "fmi2SetReal", FMU_REAL, 1, vr, nvr, value, NULL);
}
FMI2_EXPORT fmi2Status fmi2SetInteger(fmi2Component c, const fmi2ValueReference vr[],
                                      size_t nvr, const fmi2Integer value[]) {
  return transfer(c, "fmi2SetInteger", FMU_INTEGER, 1, vr, nvr, value, NULL);
}
FMI2_EXPORT fmi2Status fmi2SetBoolean(fmi2Component c, const fmi2ValueReference vr[],
                                      size_t nvr, const fmi2Boolean value[]) {
  return transfer(c, "fmi2SetBoolean", FMU_BOOLEAN, 1, vr, nvr, value, NULL);
}

/* The FMU has no String variables: any reference is unknown. */
FMI2_EXPORT fmi2Status fmi2GetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                     fmi2String value[]) {
  fmu_instance *in = fmu_cast(c);
  if (!in) return fmi2Error;
  if (check_call(in, "fmi2GetString", GET_MODES, vr, nvr, value) != fmi2OK) return fmi2Error;
  if (nvr > 0) return fmu_fail(in, fmi2Error, "fmi2GetString: the FMU has no String variables");
  return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2SetString(fmi2Component c, const fmi2ValueReference vr[], size_t nvr,
                                     const fmi2String value[]) {
  fmu_instance *in = fmu_cast(c);
  if (!in) return fmi2Error;
  if (check_call(in, "fmi2SetString", SET_MODES, vr, nvr, value) != fmi2OK) return fmi2Error;
  if (nvr > 0) return fmu_fail(in, fmi2Error, "fmi2SetString: the FMU has no String variables");
  return fmi2OK;
}
