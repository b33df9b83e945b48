/* fmu_instance.h -- one FMU instance: the host's callbacks, and the plain-data
 * part (fmu_data) that an FMU state snapshot copies and serializes whole.
 * No global state: everything an instance needs is in its fmu_instance,
 * allocated by the host's allocateMemory.
 */
#ifndef RTB_FMU_INSTANCE_H
#define RTB_FMU_INSTANCE_H

#include "fmi2_api.h"
#include "rt_bushing.h"

/* The co-simulation state machine of FMI 2.0 section 4.2.4 (stepInProgress
 * and stepCanceled never occur: doStep is synchronous). */
typedef enum {
  FMU_INSTANTIATED = 1,
  FMU_INITIALIZATION = 2,
  FMU_STEP_COMPLETE = 3,
  FMU_STEP_FAILED = 4,   /* after doStep returned fmi2Discard */
  FMU_TERMINATED = 5,
  FMU_ERROR = 6          /* after any fmi2Error: SetFMUstate, Reset or Free */
} fmu_mode;

/* Everything that defines where the simulation is. Plain data. */
typedef struct fmu_data {
  int mode;                      /* fmu_mode */
  int pad_;
  double start_time;             /* fmi2SetupExperiment [s] */
  double time;                   /* current communication point [s] */
  double last_successful_time;   /* fmi2GetRealStatus(fmi2LastSuccessfulTime) [s] */
  double x[RTB_AXES];            /* inputs x y z [mm], rx ry rz [rad] */
  double f[RTB_AXES];            /* outputs fx fy fz [N], mx my mz [N mm] */
  rtb_bushing6_params params;    /* the current (tunable) parameters */
  rtb_bushing6_state state;      /* the element, valid from ExitInitializationMode */
} fmu_data;

#define FMU_INSTANCE_TAG 0x52544246u /* "RTBF": catches a pointer that is not ours */

typedef struct fmu_instance {
  unsigned tag;
  int logging_on;
  fmi2CallbackFunctions cb;      /* copied at instantiation */
  char *name;                    /* instanceName, in host memory */
  fmu_data d;
} fmu_instance;

/* The start parameters (the paper's section 3.4 set on every axis, or the
 * bushing compiled in with `make fmu PARAMS=...`). fmu_params.c */
void fmu_start_params(rtb_bushing6_params *p);
/* The GUID of this build, "{xxxxxxxx-xxxx-xxxx-xxxx-xxxxxxxxxxxx}", a hash of
 * the variable table and start values (fmu_guid.c); also its 64-bit core. */
const char *fmu_guid(char buf[40]);
unsigned long long fmu_guid_hash(void);

/* Reset fmu_data to the start values, mode FMU_INSTANTIATED. */
void fmu_data_start(fmu_data *d);

/* ---- logging (logging.c) ----
 * Errors and warnings always reach the host's logger; fmi2OK messages only
 * when logging is on. fmu_fail logs and, for fmi2Error, enters FMU_ERROR. */
void fmu_log(fmu_instance *in, fmi2Status status, const char *category, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
fmi2Status fmu_fail(fmu_instance *in, fmi2Status status, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
/* A library error: "FUNC: axis A: <rtb_status_message>" through fmu_fail. */
fmi2Status fmu_fail_rtb(fmu_instance *in, fmi2Status status, const char *func, rtb_status st,
                        int bad_axis);

/* The instance behind a handle, or NULL (nothing can be logged then). */
fmu_instance *fmu_cast(fmi2Component c);
/* fmi2OK if the instance is in one of the modes of `mask` (bit 1 << mode),
 * else fmu_fail with "FUNC called in mode M". */
fmi2Status fmu_require_mode(fmu_instance *in, const char *func, unsigned mask);
#define FMU_MODE_BIT(m) (1u << (m))
const char *fmu_mode_name(int mode);

#endif /* RTB_FMU_INSTANCE_H */
