/* variables.h -- the FMU's variable table: names, value references, units,
 * causality and where each value lives in fmu_data.
 *
 * Value references (unique over all types):
 *   Real     0..5    inputs  x y z [mm], rx ry rz [rad]
 *            6..11   outputs fx fy fz [N], mx my mz [N mm]
 *            100 + 50 a + k   tunable parameter k of axis a: the k-th field of
 *                             RTB_PARAM_FIELDS (rt_bushing.h), all of them
 *   Integer  1000 + 10 a + k  fixed: a.model (1 RT, 2 STS), a.cells, a.integrator
 *   Boolean  2000 + a         fixed: a.active
 * with a = 0..5 for x y z rx ry rz.
 */
#ifndef RTB_FMU_VARIABLES_H
#define RTB_FMU_VARIABLES_H

#include "fmu_instance.h"

typedef enum { FMU_REAL = 1, FMU_INTEGER = 2, FMU_BOOLEAN = 3 } fmu_type;
typedef enum {
  FMU_INPUT = 1,      /* causality input, continuous */
  FMU_OUTPUT = 2,     /* causality output, continuous, no direct feedthrough */
  FMU_TUNABLE = 3,    /* causality parameter, variability tunable */
  FMU_FIXED = 4       /* causality parameter, variability fixed */
} fmu_role;

#define FMU_VR_INPUT 0u
#define FMU_VR_OUTPUT 6u
#define FMU_VR_REAL_PARAM 100u
#define FMU_VR_INT_PARAM 1000u
#define FMU_VR_BOOL_PARAM 2000u
#define FMU_AXIS_STRIDE_REAL 50u
#define FMU_AXIS_STRIDE_INT 10u

typedef struct fmu_var {
  char name[40];
  fmi2ValueReference vr;
  int type;                   /* fmu_type */
  int role;                   /* fmu_role */
  char unit[40];              /* "": dimensionless */
  const char *description;
  double start;               /* start value (Integer/Boolean too, exactly) */
} fmu_var;

/* The index-th variable of the table (0 ..), with its start value from
 * `start`; returns 0 past the end. Order: inputs, outputs, then per axis
 * active, model, cells, integrator and the real parameters. */
int fmu_variable(int index, const rtb_bushing6_params *start, fmu_var *out);

/* Where a value lives, or NULL for an unknown reference of that type. The
 * role goes to *role. */
double *fmu_real_slot(fmu_data *d, fmi2ValueReference vr, int *role);
int *fmu_int_slot(fmu_data *d, fmi2ValueReference vr, int *role);
int *fmu_bool_slot(fmu_data *d, fmi2ValueReference vr, int *role);

#endif /* RTB_FMU_VARIABLES_H */
