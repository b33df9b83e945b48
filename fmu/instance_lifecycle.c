/* instance_lifecycle.c -- instantiation, the initialization handshake,
 * termination and reset (FMI 2.0 sections 2.1.5-2.1.6, 4.2.4).
 *
 * The element's state is initialised at fmi2ExitInitializationMode, relaxed
 * at the inputs set at that moment (rtb_bushing6_init), so the first outputs
 * are the static forces of the initial displacements.
 */
#include <math.h>
#include <string.h>

#include "fmu_instance.h"

FMI2_EXPORT const char *fmi2GetTypesPlatform(void) { return "default"; }
FMI2_EXPORT const char *fmi2GetVersion(void) { return "2.0"; }

/* Before an instance exists: straight to the host's logger, if any. */
static void early_error(const fmi2CallbackFunctions *f, fmi2String name, const char *msg) {
  if (f && f->logger)
    f->logger(f->componentEnvironment, name ? name : "", fmi2Error, "logStatusError", msg);
}

FMI2_EXPORT fmi2Component fmi2Instantiate(fmi2String instanceName, fmi2Type fmuType,
                                          fmi2String fmuGUID, fmi2String fmuResourceLocation,
                                          const fmi2CallbackFunctions *functions,
                                          fmi2Boolean visible, fmi2Boolean loggingOn) {
  (void)fmuResourceLocation; /* everything is compiled in: no resources */
  (void)visible;
  if (!functions || !functions->allocateMemory || !functions->freeMemory) {
    early_error(functions, instanceName,
                "fmi2Instantiate: allocateMemory and freeMemory callbacks are required");
    return NULL;
  }
  if (!instanceName || !instanceName[0]) {
    early_error(functions, instanceName, "fmi2Instantiate: instanceName is NULL or empty");
    return NULL;
  }
  if (fmuType != fmi2CoSimulation) {
    early_error(functions, instanceName,
                "fmi2Instantiate: this FMU supports co-simulation only (fmuType must be "
                "fmi2CoSimulation)");
    return NULL;
  }
  char guid[40];
  if (!fmuGUID || strcmp(fmuGUID, fmu_guid(guid)) != 0) {
    early_error(functions, instanceName,
                "fmi2Instantiate: fmuGUID does not match this binary's modelDescription.xml");
    return NULL;
  }
  fmu_instance *in = (fmu_instance *)functions->allocateMemory(1, sizeof *in);
  const size_t len = strlen(instanceName) + 1;
  char *name = (char *)functions->allocateMemory(len, 1);
  if (!in || !name) {
    if (in) functions->freeMemory(in);
    if (name) functions->freeMemory(name);
    early_error(functions, instanceName, "fmi2Instantiate: allocateMemory returned NULL");
    return NULL;
  }
  memset(in, 0, sizeof *in);
  memcpy(name, instanceName, len);
  in->tag = FMU_INSTANCE_TAG;
  in->logging_on = loggingOn != fmi2False;
  in->cb = *functions;
  in->name = name;
  fmu_data_start(&in->d);
  fmu_log(in, fmi2OK, "logAll", "instantiated (GUID %s)", guid);
  return in;
}

FMI2_EXPORT void fmi2FreeInstance(fmi2Component c) {
  fmu_instance *in = fmu_cast(c);
  if (!in) return;
  const fmi2CallbackFreeMemory release = in->cb.freeMemory;
  in->tag = 0; /* a second free of the same handle is caught by fmu_cast */
  release(in->name);
  release(in);
}

FMI2_EXPORT fmi2Status fmi2SetDebugLogging(fmi2Component c, fmi2Boolean loggingOn,
                                           size_t nCategories, const fmi2String categories[]) {
  fmu_instance *in = fmu_cast(c);
  if (!in) return fmi2Error;
  if (nCategories > 0 && !categories)
    return fmu_fail(in, fmi2Error, "fmi2SetDebugLogging: categories is NULL");
  /* Categories are not filtered: every message of the enabled level is sent. */
  in->logging_on = loggingOn != fmi2False;
  return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2SetupExperiment(fmi2Component c, fmi2Boolean toleranceDefined,
                                           fmi2Real tolerance, fmi2Real startTime,
                                           fmi2Boolean stopTimeDefined, fmi2Real stopTime) {
  fmu_instance *in = fmu_cast(c);
  if (!in) return fmi2Error;
  if (fmu_require_mode(in, "fmi2SetupExperiment", FMU_MODE_BIT(FMU_INSTANTIATED)) != fmi2OK)
    return fmi2Error;
  (void)toleranceDefined; /* the stepper's own tolerance (RTB_TOL_DEFAULT) applies */
  (void)tolerance;
  if (!isfinite(startTime))
    return fmu_fail(in, fmi2Error, "fmi2SetupExperiment: startTime is not finite");
  if (stopTimeDefined && !(stopTime >= startTime))
    return fmu_fail(in, fmi2Error, "fmi2SetupExperiment: stopTime < startTime");
  in->d.start_time = in->d.time = in->d.last_successful_time = startTime;
  return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2EnterInitializationMode(fmi2Component c) {
  fmu_instance *in = fmu_cast(c);
  if (!in) return fmi2Error;
  if (fmu_require_mode(in, "fmi2EnterInitializationMode", FMU_MODE_BIT(FMU_INSTANTIATED)) !=
      fmi2OK)
    return fmi2Error;
  in->d.mode = FMU_INITIALIZATION;
  return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2ExitInitializationMode(fmi2Component c) {
  fmu_instance *in = fmu_cast(c);
  if (!in) return fmi2Error;
  if (fmu_require_mode(in, "fmi2ExitInitializationMode", FMU_MODE_BIT(FMU_INITIALIZATION)) !=
      fmi2OK)
    return fmi2Error;
  int bad = -1;
  const rtb_status st = rtb_bushing6_init(&in->d.state, &in->d.params, in->d.x, &bad);
  if (st != RTB_OK) return fmu_fail_rtb(in, fmi2Error, "fmi2ExitInitializationMode", st, bad);
  for (int a = 0; a < RTB_AXES; ++a) in->d.f[a] = in->d.state.axis[a].force; /* 0 when off */
  in->d.time = in->d.last_successful_time = in->d.start_time;
  in->d.mode = FMU_STEP_COMPLETE;
  return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2Terminate(fmi2Component c) {
  fmu_instance *in = fmu_cast(c);
  if (!in) return fmi2Error;
  if (fmu_require_mode(in, "fmi2Terminate",
                       FMU_MODE_BIT(FMU_STEP_COMPLETE) | FMU_MODE_BIT(FMU_STEP_FAILED)) != fmi2OK)
    return fmi2Error;
  in->d.mode = FMU_TERMINATED;
  return fmi2OK;
}

/* Back to the state right after fmi2Instantiate: start values, time 0. */
FMI2_EXPORT fmi2Status fmi2Reset(fmi2Component c) {
  fmu_instance *in = fmu_cast(c);
  if (!in) return fmi2Error;
  fmu_data_start(&in->d);
  return fmi2OK;
}
