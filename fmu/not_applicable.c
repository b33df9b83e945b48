/* not_applicable.c -- the fmi2 functions that do not apply to this
 * co-simulation FMU: model exchange (FMI 2.0 section 3.2) and directional
 * derivatives (providesDirectionalDerivative = false: the outputs have no
 * direct feedthrough from the inputs, see modelDescription.xml). Each returns
 * fmi2Error with a message through the logger. */
#include "fmu_instance.h"

static fmi2Status refuse(fmi2Component c, const char *func, const char *why) {
  fmu_instance *in = fmu_cast(c);
  if (!in) return fmi2Error;
  return fmu_fail(in, fmi2Error, "%s: %s", func, why);
}

static const char kME[] = "model exchange is not supported by this FMU (co-simulation only)";

FMI2_EXPORT fmi2Status fmi2GetDirectionalDerivative(fmi2Component c,
                                                    const fmi2ValueReference vUnknown_ref[],
                                                    size_t nUnknown,
                                                    const fmi2ValueReference vKnown_ref[],
                                                    size_t nKnown, const fmi2Real dvKnown[],
                                                    fmi2Real dvUnknown[]) {
  (void)vUnknown_ref, (void)nUnknown, (void)vKnown_ref, (void)nKnown, (void)dvKnown,
      (void)dvUnknown;
  return refuse(c, "fmi2GetDirectionalDerivative",
                "not provided (providesDirectionalDerivative = false); the tangent dF/dx of a "
                "step is available from rtb_bushing6_evaluate in the C library");
}

FMI2_EXPORT fmi2Status fmi2EnterEventMode(fmi2Component c) {
  return refuse(c, "fmi2EnterEventMode", kME);
}
FMI2_EXPORT fmi2Status fmi2NewDiscreteStates(fmi2Component c, fmi2EventInfo *eventInfo) {
  (void)eventInfo;
  return refuse(c, "fmi2NewDiscreteStates", kME);
}
FMI2_EXPORT fmi2Status fmi2EnterContinuousTimeMode(fmi2Component c) {
  return refuse(c, "fmi2EnterContinuousTimeMode", kME);
}
FMI2_EXPORT fmi2Status fmi2CompletedIntegratorStep(fmi2Component c,
                                                   fmi2Boolean noSetFMUStatePriorToCurrentPoint,
                                                   fmi2Boolean *enterEventMode,
                                                   fmi2Boolean *terminateSimulation) {
  (void)noSetFMUStatePriorToCurrentPoint, (void)enterEventMode, (void)terminateSimulation;
  return refuse(c, "fmi2CompletedIntegratorStep", kME);
}
FMI2_EXPORT fmi2Status fmi2SetTime(fmi2Component c, fmi2Real time) {
  (void)time;
  return refuse(c, "fmi2SetTime", kME);
}
FMI2_EXPORT fmi2Status fmi2SetContinuousStates(fmi2Component c, const fmi2Real x[], size_t nx) {
  (void)x, (void)nx;
  return refuse(c, "fmi2SetContinuousStates", kME);
}
FMI2_EXPORT fmi2Status fmi2GetDerivatives(fmi2Component c, fmi2Real derivatives[], size_t nx) {
  (void)derivatives, (void)nx;
  return refuse(c, "fmi2GetDerivatives", kME);
}
FMI2_EXPORT fmi2Status fmi2GetEventIndicators(fmi2Component c, fmi2Real eventIndicators[],
                                              size_t ni) {
  (void)eventIndicators, (void)ni;
  return refuse(c, "fmi2GetEventIndicators", kME);
}
FMI2_EXPORT fmi2Status fmi2GetContinuousStates(fmi2Component c, fmi2Real x[], size_t nx) {
  (void)x, (void)nx;
  return refuse(c, "fmi2GetContinuousStates", kME);
}
FMI2_EXPORT fmi2Status fmi2GetNominalsOfContinuousStates(fmi2Component c, fmi2Real x_nominal[],
                                                         size_t nx) {
  (void)x_nominal, (void)nx;
  return refuse(c, "fmi2GetNominalsOfContinuousStates", kME);
}
