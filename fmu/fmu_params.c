/* fmu_params.c -- the bushing compiled into this FMU, and its GUID.
 *
 * Default: the paper's section 3.4 set on every axis (rtb_params_default).
 * `make fmu PARAMS=FILE` compiles a generated six-axis header instead: the
 * build defines RTB_FMU_PARAMS_HEADER (its path) and RTB_FMU_PARAMS_NAME (the
 * rtb_bushing6_params constant it declares).
 */
#include <stdio.h>
#include <string.h>

#include "fmu_instance.h"
#include "variables.h"

#ifdef RTB_FMU_PARAMS_HEADER
#include RTB_FMU_PARAMS_HEADER
#endif

void fmu_start_params(rtb_bushing6_params *p) {
#ifdef RTB_FMU_PARAMS_HEADER
  *p = RTB_FMU_PARAMS_NAME;
#else
  rtb_bushing6_params_default(p, RTB_MODEL_RT);
#endif
}

void fmu_data_start(fmu_data *d) {
  memset(d, 0, sizeof *d);
  d->mode = FMU_INSTANTIATED;
  fmu_start_params(&d->params);
}

/* FNV-1a, 64 bit. */
static unsigned long long fnv(unsigned long long h, const void *data, size_t n) {
  const unsigned char *b = (const unsigned char *)data;
  for (size_t i = 0; i < n; ++i) {
    h ^= b[i];
    h *= 1099511628211ull;
  }
  return h;
}

/* Over everything modelDescription.xml says about the variables, so an FMU
 * with other start values or another table has another GUID. */
static unsigned long long table_hash(unsigned long long h) {
  static const char kVersion[] = "rt_bushing FMI 2.0 co-simulation 1";
  rtb_bushing6_params p;
  fmu_start_params(&p);
  const int abi = RTB_ABI_VERSION;
  h = fnv(h, kVersion, sizeof kVersion);
  h = fnv(h, &abi, sizeof abi);
  fmu_var v;
  for (int i = 0; fmu_variable(i, &p, &v); ++i) {
    h = fnv(h, v.name, strlen(v.name) + 1);
    h = fnv(h, &v.vr, sizeof v.vr);
    h = fnv(h, &v.type, sizeof v.type);
    h = fnv(h, &v.role, sizeof v.role);
    h = fnv(h, &v.start, sizeof v.start);
  }
  return h;
}

unsigned long long fmu_guid_hash(void) { return table_hash(14695981039346656037ull); }

const char *fmu_guid(char buf[40]) {
  const unsigned long long a = fmu_guid_hash(), b = table_hash(0x84222325cbf29ce4ull);
  snprintf(buf, 40, "{%08llx-%04llx-%04llx-%04llx-%012llx}", a >> 32, (a >> 16) & 0xffff,
           a & 0xffff, b >> 48, b & 0xffffffffffffull);
  return buf;
}
