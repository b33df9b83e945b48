/* variables.c -- see variables.h. The units are those of the README's table:
 * mm, N, s on the translations; rad and N mm on the rotations. */
#include "variables.h"

#include <stddef.h>
#include <stdio.h>

typedef struct real_field {
  const char *name;
  size_t offset;            /* in rtb_params */
  const char *unit_trans;   /* x y z */
  const char *unit_rot;     /* rx ry rz */
  const char *description;
} real_field;

/* Every physical field and model setting of rtb_params that is a real. A
 * field added to rtb_params later and missing here keeps its compiled-in
 * value (it is not tunable) -- add a row to make it so. */
static const real_field kRealFields[] = {
    {"K0", offsetof(rtb_params, K0), "N/mm", "N.mm/rad", "global elastic stiffness, >= 0"},
    {"Kpa", offsetof(rtb_params, Kpa), "N/mm", "N.mm/rad", "low-amplitude stiffness, > 0"},
    {"Kr", offsetof(rtb_params, Kr), "N/mm", "N.mm/rad", "cell spring stiffness, > 0"},
    {"C0", offsetof(rtb_params, C0), "N.(s/mm)^alpha", "N.mm.(s/rad)^alpha",
     "RT dashpot coefficient, > 0, eq. (1)"},
    {"alpha", offsetof(rtb_params, alpha), NULL, NULL, "RT dashpot exponent in [0.001, 1)"},
    {"Ff", offsetof(rtb_params, Ff), "N", "N.mm", "STS friction threshold, > 0 (STS only)"},
    {"k3", offsetof(rtb_params, k3), "N/mm3", "N.mm/rad3", "cubic spring"},
    {"k_asym", offsetof(rtb_params, k_asym), "N/mm", "N.mm/rad",
     "tension/compression asymmetry, |k_asym| <= K0"},
    {"maxwell_k", offsetof(rtb_params, maxwell_k), "N/mm", "N.mm/rad",
     "Maxwell branch stiffness, >= 0"},
    {"maxwell_tau", offsetof(rtb_params, maxwell_tau), "s", "s", "Maxwell relaxation time"},
    {"viscous_c", offsetof(rtb_params, viscous_c), "N.s/mm", "N.mm.s/rad",
     "parallel linear dashpot, >= 0"},
    {"mass", offsetof(rtb_params, mass), "N.s2/mm", "N.mm.s2/rad", "inertia in the load path"},
    {"backlash", offsetof(rtb_params, backlash), "mm", "rad", "total clearance in series, >= 0"},
    {"mullins", offsetof(rtb_params, mullins), NULL, NULL, "Mullins softening fraction in [0, 1)"},
    {"smoothing", offsetof(rtb_params, smoothing), "s/mm", "s/rad",
     "eq. (14) sigmoid smoothing, 0 = off"},
    {"sat_force", offsetof(rtb_params, sat_force), "N", "N.mm", "softening spring force, >= 0"},
    {"sat_disp", offsetof(rtb_params, sat_disp), "mm", "rad", "softening spring displacement"},
};
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

static void fill(fmu_var *v, const char *axis, const char *name, fmi2ValueReference vr, int type,
                 int role, const char *unit, const char *description, double start) {
  if (axis) snprintf(v->name, sizeof v->name, "%s.%s", axis, name);
  else snprintf(v->name, sizeof v->name, "%s", name);
  v->vr = vr;
  v->type = type;
  v->role = role;
  v->unit = unit;
  v->description = description;
  v->start = start;
}

int fmu_variable(int i, const rtb_bushing6_params *p, fmu_var *v) {
  if (i < 0) return 0;
  if (i < RTB_AXES) {
    fill(v, NULL, rtb_axis_name(i), FMU_VR_INPUT + i, FMU_REAL, FMU_INPUT,
         is_rot(i) ? "rad" : "mm", is_rot(i) ? "rotation" : "displacement", 0.0);
    return 1;
  }
  i -= RTB_AXES;
  if (i < RTB_AXES) {
    fill(v, NULL, kOutputNames[i], FMU_VR_OUTPUT + i, FMU_REAL, FMU_OUTPUT,
         is_rot(i) ? "N.mm" : "N", is_rot(i) ? "moment" : "force", 0.0);
    return 1;
  }
  i -= RTB_AXES;
  const int a = i / PER_AXIS, k = i % PER_AXIS;
  if (a >= RTB_AXES) return 0;
  const char *ax = rtb_axis_name(a);
  const rtb_params *q = &p->axis[a];
  if (k == 0) {
    fill(v, ax, "active", FMU_VR_BOOL_PARAM + a, FMU_BOOLEAN, FMU_FIXED, NULL,
         "axis on; off gives zero force", p->active[a]);
  } else if (k < 4) {
    const int val = k == 1 ? q->model : k == 2 ? q->cells : q->integrator;
    fill(v, ax, kIntNames[k - 1], FMU_VR_INT_PARAM + FMU_AXIS_STRIDE_INT * a + (k - 1),
         FMU_INTEGER, FMU_FIXED, NULL, kIntDescriptions[k - 1], val);
  } else {
    const real_field *f = &kRealFields[k - 4];
    fill(v, ax, f->name, FMU_VR_REAL_PARAM + FMU_AXIS_STRIDE_REAL * a + (k - 4), FMU_REAL,
         FMU_TUNABLE, is_rot(a) ? f->unit_rot : f->unit_trans, f->description,
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
