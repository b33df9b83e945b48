/* host_support.c -- see host_support.h. */
#include "host_support.h"

#include <stdarg.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

int g_failures = 0;
static long g_live = 0, g_total = 0;

static void *allocate(size_t nobj, size_t size) {
  void *p = calloc(nobj, size);
  if (p) {
    ++g_live;
    ++g_total;
  }
  return p;
}

static void release(void *p) {
  if (!p) return;
  --g_live;
  free(p);
}

static void logger(fmi2ComponentEnvironment env, fmi2String instance, fmi2Status status,
                   fmi2String category, fmi2String message, ...) {
  host_log *log = (host_log *)env;
  char text[512];
  va_list ap;
  va_start(ap, message);
  vsnprintf(text, sizeof text, message, ap);  /* the message is a printf format */
  va_end(ap);
  if (getenv("FMU_HOST_VERBOSE"))
    fprintf(stderr, "  [%s %d %s] %s\n", instance, (int)status, category, text);
  if (!log) return;
  ++log->messages;
  if (status == fmi2Error) ++log->errors;
  snprintf(log->last, sizeof log->last, "%s", text);
}

fmi2CallbackFunctions host_callbacks(host_log *env) {
  fmi2CallbackFunctions cb;
  cb.logger = logger;
  cb.allocateMemory = allocate;
  cb.freeMemory = release;
  cb.stepFinished = NULL;
  cb.componentEnvironment = env;
  return cb;
}

long host_live_allocations(void) { return g_live; }
long host_total_allocations(void) { return g_total; }

fmi2ValueReference vr_of(const md_info *md, const char *name) {
  const md_var *v = md_find(md, name);
  CHECK(v != NULL, "modelDescription.xml has no variable %s", name);
  return v ? v->vr : 0xFFFFFFFFu;
}

/* The real fields of rtb_params by their names, from the library's public
 * list (rt_bushing.h, RTB_PARAM_FIELDS): the reference the FMU is checked
 * against, not the FMU's own table. */
#define HOST_FIELD(name, rule, kind, unit, text) {#name, offsetof(rtb_params, name)},
static const struct {
  const char *name;
  size_t offset;
} kFields[] = {RTB_PARAM_FIELDS(HOST_FIELD)};
#undef HOST_FIELD
#define N_FIELDS ((int)(sizeof kFields / sizeof kFields[0]))

static int set_field(rtb_params *q, int *active, const md_var *v, const char *field) {
  if (strcmp(field, "active") == 0) {
    *active = strcmp(v->start, "true") == 0;
    return 1;
  }
  if (strcmp(field, "model") == 0) return q->model = atoi(v->start), 1;
  if (strcmp(field, "cells") == 0) return q->cells = atoi(v->start), 1;
  if (strcmp(field, "integrator") == 0) return q->integrator = atoi(v->start), 1;
  for (int k = 0; k < N_FIELDS; ++k)
    if (strcmp(field, kFields[k].name) == 0) {
      *(double *)((char *)q + kFields[k].offset) = strtod(v->start, NULL);
      return 1;
    }
  return 0;
}

int reference_params(const md_info *md, rtb_bushing6_params *p) {
  memset(p, 0, sizeof *p);
  for (int a = 0; a < RTB_AXES; ++a) p->axis[a].abi_version = RTB_ABI_VERSION;
  int n = 0;
  for (int i = 0; i < md->n_vars; ++i) {
    const md_var *v = &md->vars[i];
    if (strcmp(v->causality, "parameter") != 0) continue;
    const char *dot = strchr(v->name, '.');
    int a = 0;
    while (a < RTB_AXES && (!dot || strncmp(v->name, rtb_axis_name(a), (size_t)(dot - v->name)) != 0 ||
                            strlen(rtb_axis_name(a)) != (size_t)(dot - v->name)))
      ++a;
    if (a == RTB_AXES || !set_field(&p->axis[a], &p->active[a], v, dot + 1)) {
      fprintf(stderr, "fmu_host: parameter %s maps to no rtb_params field\n", v->name);
      return 0;
    }
    ++n;
  }
  CHECK(n == RTB_AXES * (4 + N_FIELDS), "%d parameters, expected 6 x %d", n, 4 + N_FIELDS);
  return 1;
}

int write_params_json(const char *path, const rtb_params *p) {
  FILE *f = fopen(path, "w");
  if (!f) return 0;
  fprintf(f, "{\"model\": \"%s\", \"cells\": %d, \"integrator\": \"%s\", \"smoothing\": %.17g,\n",
          p->model == RTB_MODEL_STS ? "sts" : "rt", p->cells,
          p->integrator == RTB_INTEGRATOR_BE ? "be" : "sdirk2", p->smoothing);
  fprintf(f, " \"params\": {");
  int first = 1;
  for (int k = 0; k < N_FIELDS; ++k) {
    if (strcmp(kFields[k].name, "smoothing") == 0) continue; /* a top-level key */
    fprintf(f, "%s\"%s\": %.17g", first ? "" : ", ", kFields[k].name,
            *(const double *)((const char *)p + kFields[k].offset));
    first = 0;
  }
  fprintf(f, "}}\n");
  return fclose(f) == 0;
}
