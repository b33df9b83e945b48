/* host_support.h -- the host side of the test: the callbacks it gives the
 * FMU (a counting allocator and a logger that records messages), the
 * library reference built from modelDescription.xml, and the check macro. */
#ifndef RTB_FMU_HOST_SUPPORT_H
#define RTB_FMU_HOST_SUPPORT_H

#include <stdio.h>

#include "fmi2_host.h"
#include "fmu_load.h"
#include "rt_bushing.h"

extern int g_failures;
#define CHECK(cond, ...)                                                     \
  do {                                                                       \
    if (!(cond)) {                                                           \
      ++g_failures;                                                          \
      fprintf(stderr, "fmu_host: FAIL %s:%d: ", __FILE__, __LINE__);         \
      fprintf(stderr, __VA_ARGS__);                                          \
      fputc('\n', stderr);                                                   \
    }                                                                        \
  } while (0)

/* What the logger saw, per instance (componentEnvironment). */
typedef struct host_log {
  int errors;          /* messages with status fmi2Error */
  int messages;
  char last[512];
} host_log;

/* Callbacks with env as componentEnvironment; allocation counts are global
 * (allocateMemory has no environment argument in FMI 2.0). */
fmi2CallbackFunctions host_callbacks(host_log *env);
long host_live_allocations(void);
long host_total_allocations(void);

/* The library's parameters of every axis, from the start values in the XML
 * (names "x.K0", "ry.cells", ...). Returns 0 and says why on a name it
 * cannot map. */
int reference_params(const md_info *md, rtb_bushing6_params *p);

/* The parameter JSON of `rtb simulate` (offline/io/params_json.cpp format). */
int write_params_json(const char *path, const rtb_params *p);

/* Value reference of a named variable (the test fails when absent). */
fmi2ValueReference vr_of(const md_info *md, const char *name);

#endif
