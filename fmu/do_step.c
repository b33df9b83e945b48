/* do_step.c -- the communication step and the co-simulation status queries
 * (FMI 2.0 section 4.2.2-4.2.3).
 *
 * fmi2DoStep(t, h) advances every axis by exactly ONE rtb step of length
 * dt = h to the inputs set for the end of the step (the library interpolates
 * linearly from the previous inputs inside the step). So a host that drives
 * the FMU with the time grid of a record gets, bit for bit, what
 * rtb_bushing6_step (and rtb_step per axis) gives for the same dt sequence.
 * The step size is the host's accuracy knob: h is bounded only by the
 * library's [RTB_DT_MIN, RTB_DT_MAX] = [1e-9, 1e3] s; README gives the
 * error per step size.
 */
#include <math.h>

#include "fmu_instance.h"

/* Communication points are compared with this relative slack, so a host
 * that accumulates time differently (t0 + n h vs sums of h) is not refused. */
#define FMU_TIME_SLACK 1e-9

static fmi2Status check_step_call(fmu_instance *in, fmi2Real t, fmi2Real h) {
  if (fmu_require_mode(in, "fmi2DoStep", FMU_MODE_BIT(FMU_STEP_COMPLETE)) != fmi2OK)
    return fmi2Error;
  if (!isfinite(h) || !(h > 0.0))
    return fmu_fail(in, fmi2Error, "fmi2DoStep: communicationStepSize = %g must be > 0", h);
  if (!isfinite(t) || fabs(t - in->d.time) > FMU_TIME_SLACK * fmax(1.0, fabs(in->d.time)))
    return fmu_fail(in, fmi2Error,
                    "fmi2DoStep: currentCommunicationPoint = %.17g is not the FMU's time %.17g",
                    t, in->d.time);
  return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2DoStep(fmi2Component c, fmi2Real currentCommunicationPoint,
                                  fmi2Real communicationStepSize,
                                  fmi2Boolean noSetFMUStatePriorToCurrentPoint) {
  (void)noSetFMUStatePriorToCurrentPoint; /* nothing is buffered for rollback */
  fmu_instance *in = fmu_cast(c);
  if (!in) return fmi2Error;
  const double t = currentCommunicationPoint, h = communicationStepSize;
  if (check_step_call(in, t, h) != fmi2OK) return fmi2Error;

  int bad = -1;
  double F[RTB_AXES];
  const rtb_status st = rtb_bushing6_step(&in->d.state, &in->d.params, NULL, in->d.x, h, F, &bad);
  if (st == RTB_ERR_OVERFLOW) {
    /* The step cannot be taken from here with this h; the state is the one
     * at t, so the host may retry with a smaller step or roll back. */
    in->d.mode = FMU_STEP_FAILED;
    in->d.last_successful_time = in->d.time;
    return fmu_fail_rtb(in, fmi2Discard, "fmi2DoStep", st, bad);
  }
  if (st < 0) return fmu_fail_rtb(in, fmi2Error, "fmi2DoStep", st, bad);
  for (int a = 0; a < RTB_AXES; ++a) in->d.f[a] = F[a];
  in->d.time = t + h;
  in->d.last_successful_time = in->d.time;
  if (st == RTB_NOT_CONVERGED)
    return fmu_fail_rtb(in, fmi2Warning, "fmi2DoStep (step committed)", st, bad);
  return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2CancelStep(fmi2Component c) {
  fmu_instance *in = fmu_cast(c);
  if (!in) return fmi2Error;
  return fmu_fail(in, fmi2Error,
                  "fmi2CancelStep: no step is pending (fmi2DoStep is synchronous, "
                  "canRunAsynchronuously = false)");
}

FMI2_EXPORT fmi2Status fmi2SetRealInputDerivatives(fmi2Component c,
                                                   const fmi2ValueReference vr[], size_t nvr,
                                                   const fmi2Integer order[],
                                                   const fmi2Real value[]) {
  (void)vr, (void)nvr, (void)order, (void)value;
  fmu_instance *in = fmu_cast(c);
  if (!in) return fmi2Error;
  return fmu_fail(in, fmi2Error,
                  "fmi2SetRealInputDerivatives: not supported (canInterpolateInputs = false; "
                  "inputs are interpolated linearly between communication points)");
}

FMI2_EXPORT fmi2Status fmi2GetRealOutputDerivatives(fmi2Component c,
                                                    const fmi2ValueReference vr[], size_t nvr,
                                                    const fmi2Integer order[], fmi2Real value[]) {
  (void)vr, (void)nvr, (void)order, (void)value;
  fmu_instance *in = fmu_cast(c);
  if (!in) return fmi2Error;
  return fmu_fail(in, fmi2Error,
                  "fmi2GetRealOutputDerivatives: not supported (maxOutputDerivativeOrder = 0)");
}

#define STATUS_MODES                                                        \
  (FMU_MODE_BIT(FMU_STEP_COMPLETE) | FMU_MODE_BIT(FMU_STEP_FAILED) |        \
   FMU_MODE_BIT(FMU_TERMINATED))

static fmi2Status check_status_call(fmu_instance *in, const char *func, const void *value) {
  if (fmu_require_mode(in, func, STATUS_MODES) != fmi2OK) return fmi2Error;
  if (!value) return fmu_fail(in, fmi2Error, "%s: value is NULL", func);
  return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2GetStatus(fmi2Component c, const fmi2StatusKind s, fmi2Status *value) {
  fmu_instance *in = fmu_cast(c);
  if (!in) return fmi2Error;
  if (check_status_call(in, "fmi2GetStatus", value) != fmi2OK) return fmi2Error;
  return fmu_fail(in, fmi2Discard,
                  "fmi2GetStatus(%d): no asynchronous step exists (fmi2DoStepStatus and "
                  "fmi2PendingStatus apply only after fmi2Pending)",
                  (int)s);
}

FMI2_EXPORT fmi2Status fmi2GetRealStatus(fmi2Component c, const fmi2StatusKind s,
                                         fmi2Real *value) {
  fmu_instance *in = fmu_cast(c);
  if (!in) return fmi2Error;
  if (check_status_call(in, "fmi2GetRealStatus", value) != fmi2OK) return fmi2Error;
  if (s != fmi2LastSuccessfulTime)
    return fmu_fail(in, fmi2Discard, "fmi2GetRealStatus: only fmi2LastSuccessfulTime is a Real");
  *value = in->d.last_successful_time;
  return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2GetIntegerStatus(fmi2Component c, const fmi2StatusKind s,
                                            fmi2Integer *value) {
  fmu_instance *in = fmu_cast(c);
  if (!in) return fmi2Error;
  if (check_status_call(in, "fmi2GetIntegerStatus", value) != fmi2OK) return fmi2Error;
  return fmu_fail(in, fmi2Discard, "fmi2GetIntegerStatus(%d): FMI 2.0 defines no Integer status",
                  (int)s);
}

FMI2_EXPORT fmi2Status fmi2GetBooleanStatus(fmi2Component c, const fmi2StatusKind s,
                                            fmi2Boolean *value) {
  fmu_instance *in = fmu_cast(c);
  if (!in) return fmi2Error;
  if (check_status_call(in, "fmi2GetBooleanStatus", value) != fmi2OK) return fmi2Error;
  if (s != fmi2Terminated)
    return fmu_fail(in, fmi2Discard, "fmi2GetBooleanStatus: only fmi2Terminated is a Boolean");
  *value = fmi2False; /* the element never asks to end the simulation */
  return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2GetStringStatus(fmi2Component c, const fmi2StatusKind s,
                                           fmi2String *value) {
  fmu_instance *in = fmu_cast(c);
  if (!in) return fmi2Error;
  if (check_status_call(in, "fmi2GetStringStatus", value) != fmi2OK) return fmi2Error;
  return fmu_fail(in, fmi2Discard,
                  "fmi2GetStringStatus(%d): no asynchronous step is pending", (int)s);
}
