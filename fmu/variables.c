/* variables.c -- see variables.h. The units are those of the README's table:
 * mm, N, s on the translations; rad and N mm on the rotations. */
#include "variables.h"

#include <stddef.h>
#include <stdio.h>
#include <string.h>

typedef struct real_field {
  const char *name;
  size_t offset;       /* in rtb_params */
  const char *unit;    /* generic: "force/length", "-", ... (RTB_PARAM_FIELDS) */
  const char *description;
} real_field;

/* Every real field of rtb_params, from the library's own list, so a field
 * added there is a tunable parameter here without a change. */
#define FMU_REAL_FIELD(name, rule, kind, unit, text) {#name, offsetof(rtb_params, name), unit, text},
static const real_field kRealFields[] = {RTB_PARAM_FIELDS(FMU_REAL_FIELD)};
#undef FMU_REAL_FIELD
#define N_REAL_FIELDS ((int)(sizeof kRealFields / sizeof kRealFields[0]))
typedef char check_stride[(N_REAL_FIELDS <= (int)FMU_AXIS_STRIDE_REAL) ? 1 : -1];

static const char *const kOutputNames[RTB_AXES] = {"fx", "fy", "fz", "mx", "my", "mz"};
static const char *const kIntNames[3] = {"model", "cells", "integrator"};
static const char *const kIntDescriptions[3] = {
    "1 = RT (eq. (2)), 2 = STS (section 3.1); fixed at initialization",
    "number of cells N, 1..32; fixed at initialization",
    "0 = SDIRK2, 1 = backward Euler; fixed at initialization"};
#define PER_AXIS (4 + N_REAL_FIELDS)

static int is_rot(int a) { return a >= RTB_AXIS_RX; }

/* A generic unit of RTB_PARAM_FIELDS in the FMU's units: force -> N or N.mm,
 * length -> mm or rad, time -> s, a blank -> '.'; "-" -> "" (none). E.g.
 * "force (time/length)^alpha" -> "N.(s/mm)^alpha" on x, "N.mm.(s/rad)^alpha" on rx. */
static void concrete_unit(const char *generic, int rot, char *out, size_t cap) {
  size_t n = 0;
  out[0] = '\0';
  if (!generic || strcmp(generic, "-") == 0) return;
  for (const char *c = generic; *c && n + 6 < cap;) {
    const char *word = NULL;
    size_t skip = 1;
    if (strncmp(c, "force", 5) == 0) word = rot ? "N.mm" : "N", skip = 5;
    else if (strncmp(c, "length", 6) == 0) word = rot ? "rad" : "mm", skip = 6;
    else if (strncmp(c, "time", 4) == 0) word = "s", skip = 4;
    else if (*c == ' ') word = ".";
    if (word) n += (size_t)snprintf(out + n, cap - n, "%s", word);
    else out[n++] = *c, out[n] = '\0';
    c += skip;
  }
}

static void fill(fmu_var *v, const char *axis, const char *name, fmi2ValueReference vr, int type,
                 int role, const char *unit, int rot, const char *description, double start) {
  if (axis) snprintf(v->name, sizeof v->name, "%s.%s", axis, name);
  else snprintf(v->name, sizeof v->name, "%s", name);
  v->vr = vr;
  v->type = type;
  v->role = role;
  concrete_unit(unit, rot, v->unit, sizeof v->unit);
  v->description = description;
  v->start = start;
}

int fmu_variable(int i, const rtb_bushing6_params *p, fmu_var *v) {
  if (i < 0) return 0;
  if (i < RTB_AXES) {
    fill(v, NULL, rtb_axis_name(i), FMU_VR_INPUT + i, FMU_REAL, FMU_INPUT, "length", is_rot(i),
         is_rot(i) ? "rotation" : "displacement", 0.0);
    return 1;
  }
  i -= RTB_AXES;
  if (i < RTB_AXES) {
    fill(v, NULL, kOutputNames[i], FMU_VR_OUTPUT + i, FMU_REAL, FMU_OUTPUT, "force", is_rot(i),
         is_rot(i) ? "moment" : "force", 0.0);
    return 1;
  }
  i -= RTB_AXES;
  const int a = i / PER_AXIS, k = i % PER_AXIS;
  if (a >= RTB_AXES) return 0;
  const char *ax = rtb_axis_name(a);
  const rtb_params *q = &p->axis[a];
  if (k == 0) {
    fill(v, ax, "active", FMU_VR_BOOL_PARAM + a, FMU_BOOLEAN, FMU_FIXED, NULL, 0,
         "axis on; off gives zero force", p->active[a]);
  } else if (k < 4) {
    const int val = k == 1 ? q->model : k == 2 ? q->cells : q->integrator;
    fill(v, ax, kIntNames[k - 1], FMU_VR_INT_PARAM + FMU_AXIS_STRIDE_INT * a + (k - 1),
         FMU_INTEGER, FMU_FIXED, NULL, 0, kIntDescriptions[k - 1], val);
  } else {
    const real_field *f = &kRealFields[k - 4];
    fill(v, ax, f->name, FMU_VR_REAL_PARAM + FMU_AXIS_STRIDE_REAL * a + (k - 4), FMU_REAL,
         FMU_TUNABLE, f->unit, is_rot(a), f->description,
         *(const double *)((const char *)q + f->offset));
  }
  return 1;
}

double *fmu_real_slot(fmu_data *d, fmi2ValueReference vr, int *role) {
  if (vr < FMU_VR_OUTPUT) {
    *role = FMU_INPUT;
    return &d->x[vr - FMU_VR_INPUT];
  }
  if (vr < FMU_VR_OUTPUT + RTB_AXES) {
    *role = FMU_OUTPUT;
    return &d->f[vr - FMU_VR_OUTPUT];
  }
  if (vr < FMU_VR_REAL_PARAM) return NULL;
  const unsigned a = (vr - FMU_VR_REAL_PARAM) / FMU_AXIS_STRIDE_REAL;
  const unsigned k = (vr - FMU_VR_REAL_PARAM) % FMU_AXIS_STRIDE_REAL;
  if (a >= RTB_AXES || k >= (unsigned)N_REAL_FIELDS) return NULL;
  *role = FMU_TUNABLE;
  return (double *)((char *)&d->params.axis[a] + kRealFields[k].offset);
}

int *fmu_int_slot(fmu_data *d, fmi2ValueReference vr, int *role) {
  if (vr < FMU_VR_INT_PARAM) return NULL;
  const unsigned a = (vr - FMU_VR_INT_PARAM) / FMU_AXIS_STRIDE_INT;
  const unsigned k = (vr - FMU_VR_INT_PARAM) % FMU_AXIS_STRIDE_INT;
  if (a >= RTB_AXES || k >= 3) return NULL;
  *role = FMU_FIXED;
  rtb_params *q = &d->params.axis[a];
  return k == 0 ? &q->model : k == 1 ? &q->cells : &q->integrator;
}

int *fmu_bool_slot(fmu_data *d, fmi2ValueReference vr, int *role) {
  if (vr < FMU_VR_BOOL_PARAM || vr >= FMU_VR_BOOL_PARAM + RTB_AXES) return NULL;
  *role = FMU_FIXED;
  return &d->params.active[vr - FMU_VR_BOOL_PARAM];
}
