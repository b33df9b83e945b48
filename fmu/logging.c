/* logging.c -- messages to the host's logger callback, and the mode checks
 * every fmi2 function starts with. */
#include <stdarg.h>
#include <stdio.h>

#include "fmu_instance.h"

const char *fmu_mode_name(int mode) {
  switch (mode) {
    case FMU_INSTANTIATED: return "instantiated";
    case FMU_INITIALIZATION: return "initializationMode";
    case FMU_STEP_COMPLETE: return "stepComplete";
    case FMU_STEP_FAILED: return "stepFailed";
    case FMU_TERMINATED: return "terminated";
    case FMU_ERROR: return "error";
    default: return "unknown";
  }
}

static const char *category_of(fmi2Status status) {
  switch (status) {
    case fmi2OK: return "logAll";
    case fmi2Warning: return "logStatusWarning";
    case fmi2Discard: return "logStatusDiscard";
    default: return "logStatusError";
  }
}

/* The logger's message is a printf format with '#' variable escapes (FMI 2.0
 * section 2.1.5): double every '%' and '#' so the text arrives verbatim. */
static void escape(const char *in, char *out, size_t cap) {
  size_t n = 0;
  for (; *in && n + 2 < cap; ++in) {
    if (*in == '%' || *in == '#') out[n++] = *in;
    out[n++] = *in;
  }
  out[n] = '\0';
}

static void vlog(fmu_instance *in, fmi2Status status, const char *category, const char *fmt,
                 va_list ap) {
  if (!in || !in->cb.logger) return;
  if (status == fmi2OK && !in->logging_on) return;
  char text[512], escaped[1024];
  vsnprintf(text, sizeof text, fmt, ap);
  escape(text, escaped, sizeof escaped);
  in->cb.logger(in->cb.componentEnvironment, in->name ? in->name : "", status,
                category ? category : category_of(status), escaped);
}

void fmu_log(fmu_instance *in, fmi2Status status, const char *category, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vlog(in, status, category, fmt, ap);
  va_end(ap);
}

fmi2Status fmu_fail(fmu_instance *in, fmi2Status status, const char *fmt, ...) {
  va_list ap;
  va_start(ap, fmt);
  vlog(in, status, NULL, fmt, ap);
  va_end(ap);
  if (in && status == fmi2Error) in->d.mode = FMU_ERROR;
  return status;
}

fmu_instance *fmu_cast(fmi2Component c) {
  fmu_instance *in = (fmu_instance *)c;
  return in && in->tag == FMU_INSTANCE_TAG ? in : NULL;
}

fmi2Status fmu_require_mode(fmu_instance *in, const char *func, unsigned mask) {
  if (mask & FMU_MODE_BIT(in->d.mode)) return fmi2OK;
  return fmu_fail(in, fmi2Error, "%s called in mode %s, where the standard does not allow it",
                  func, fmu_mode_name(in->d.mode));
}

fmi2Status fmu_fail_rtb(fmu_instance *in, fmi2Status status, const char *func, rtb_status st,
                        int bad_axis) {
  const char *axis = rtb_axis_name(bad_axis);
  const char *field = "";
  if (axis && in) rtb_params_check(&in->d.params.axis[bad_axis], &field);
  if (axis && field && field[0])
    return fmu_fail(in, status, "%s: axis %s: parameter %s.%s: %s (rt_bushing status %d)", func,
                    axis, axis, field, rtb_status_message(st), (int)st);
  if (axis)
    return fmu_fail(in, status, "%s: axis %s: %s (rt_bushing status %d)", func, axis,
                    rtb_status_message(st), (int)st);
  return fmu_fail(in, status, "%s: %s (rt_bushing status %d)", func, rtb_status_message(st),
                  (int)st);
}
