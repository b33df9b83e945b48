/* fmu_load.h -- what the host test needs from an FMU file: unpack it, read
 * modelDescription.xml, dlopen the binary and resolve every fmi2 function. */
#ifndef RTB_FMU_HOST_FMU_LOAD_H
#define RTB_FMU_HOST_FMU_LOAD_H

#include "fmi2_host.h"

#define MD_MAX_VARS 512

typedef struct md_var {
  char name[64];
  unsigned vr;
  char type[16];         /* "Real", "Integer", "Boolean", "String" */
  char causality[16];    /* default "local" */
  char variability[16];  /* default "continuous" */
  char start[64];        /* "" when absent */
  char unit[32];
} md_var;

typedef struct md_info {
  char fmi_version[16];
  char guid[64];
  char model_identifier[64];
  int can_get_set_state, can_serialize_state, variable_step;  /* CoSimulation flags */
  int n_vars;
  md_var vars[MD_MAX_VARS];
  int n_output_unknowns;               /* ModelStructure/Outputs */
  int output_dependencies_empty;       /* every Outputs/Unknown has dependencies="" */
} md_info;

typedef struct fmu_file {
  char dir[256];    /* unpacked here (removed by fmu_close) */
  void *so;
  md_info md;
  fmi2_api api;
} fmu_file;

/* Unpack with Debian's `unzip` into a fresh temporary directory, parse the
 * XML with libxml2, dlopen binaries/linux64/<modelIdentifier>.so and resolve
 * all 44 fmi2 functions. Prints the reason and returns 0 on failure. */
int fmu_open(const char *fmu_path, fmu_file *f);
void fmu_close(fmu_file *f);
const md_var *md_find(const md_info *md, const char *name);

#endif /* RTB_FMU_HOST_FMU_LOAD_H */
