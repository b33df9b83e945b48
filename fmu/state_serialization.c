/* state_serialization.c -- fmi2Get/Set/FreeFMUstate and their serialization
 * (FMI 2.0 sections 2.1.8): canGetAndSetFMUstate and canSerializeFMUstate.
 *
 * A snapshot is a copy of fmu_data (plain data: mode, time, inputs, outputs,
 * parameters and the six-axis element state), in memory from the host's
 * allocateMemory. Its serialized form is a 24-byte header followed by the
 * bytes of fmu_data:
 *   "RTBFMU\0\1" | uint32 format 1 | uint32 sizeof(fmu_data) | uint64 GUID hash
 * so bytes from another build (other layout, other variables or start
 * values) are refused, and the content is checked before it is accepted.
 */
#include <stdint.h>
#include <string.h>

#include "fmu_instance.h"

#define SNAPSHOT_TAG 0x52544253u /* "RTBS" */
#define FORMAT_VERSION 1u

typedef struct snapshot {
  unsigned tag;
  fmu_data d;
} snapshot;

typedef struct header {
  char magic[8];
  uint32_t format;
  uint32_t data_size;
  uint64_t guid_hash;
} header;

static const char kMagic[8] = {'R', 'T', 'B', 'F', 'M', 'U', '\0', '\1'};
static const size_t kSerializedSize = sizeof(header) + sizeof(fmu_data);

static snapshot *cast_snapshot(fmi2FMUstate s) {
  snapshot *p = (snapshot *)s;
  return p && p->tag == SNAPSHOT_TAG ? p : NULL;
}

/* Reuse *slot when it is one of ours (the standard allows overwriting),
 * else allocate a new snapshot from the host. */
static snapshot *snapshot_for(fmu_instance *in, fmi2FMUstate *slot) {
  snapshot *p = cast_snapshot(*slot);
  if (p) return p;
  p = (snapshot *)in->cb.allocateMemory(1, sizeof *p);
  if (p) p->tag = SNAPSHOT_TAG;
  return p;
}

FMI2_EXPORT fmi2Status fmi2GetFMUstate(fmi2Component c, fmi2FMUstate *FMUstate) {
  fmu_instance *in = fmu_cast(c);
  if (!in) return fmi2Error;
  if (!FMUstate) return fmu_fail(in, fmi2Error, "fmi2GetFMUstate: FMUstate is NULL");
  snapshot *p = snapshot_for(in, FMUstate);
  if (!p) return fmu_fail(in, fmi2Error, "fmi2GetFMUstate: allocateMemory returned NULL");
  p->d = in->d;
  *FMUstate = p;
  return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2SetFMUstate(fmi2Component c, fmi2FMUstate FMUstate) {
  fmu_instance *in = fmu_cast(c);
  if (!in) return fmi2Error;
  const snapshot *p = cast_snapshot(FMUstate);
  if (!p)
    return fmu_fail(in, fmi2Error,
                    "fmi2SetFMUstate: FMUstate is NULL or not from fmi2GetFMUstate");
  in->d = p->d;
  return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2FreeFMUstate(fmi2Component c, fmi2FMUstate *FMUstate) {
  fmu_instance *in = fmu_cast(c);
  if (!in) return fmi2Error;
  if (!FMUstate) return fmu_fail(in, fmi2Error, "fmi2FreeFMUstate: FMUstate is NULL");
  if (!*FMUstate) return fmi2OK; /* nothing to free */
  snapshot *p = cast_snapshot(*FMUstate);
  if (!p) return fmu_fail(in, fmi2Error, "fmi2FreeFMUstate: not a state of this FMU");
  p->tag = 0;
  in->cb.freeMemory(p);
  *FMUstate = NULL;
  return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2SerializedFMUstateSize(fmi2Component c, fmi2FMUstate FMUstate,
                                                  size_t *size) {
  fmu_instance *in = fmu_cast(c);
  if (!in) return fmi2Error;
  if (!cast_snapshot(FMUstate) || !size)
    return fmu_fail(in, fmi2Error, "fmi2SerializedFMUstateSize: FMUstate or size is NULL/invalid");
  *size = kSerializedSize;
  return fmi2OK;
}

FMI2_EXPORT fmi2Status fmi2SerializeFMUstate(fmi2Component c, fmi2FMUstate FMUstate,
                                             fmi2Byte serializedState[], size_t size) {
  fmu_instance *in = fmu_cast(c);
  if (!in) return fmi2Error;
  const snapshot *p = cast_snapshot(FMUstate);
  if (!p || !serializedState)
    return fmu_fail(in, fmi2Error, "fmi2SerializeFMUstate: FMUstate or buffer is NULL/invalid");
  if (size < kSerializedSize)
    return fmu_fail(in, fmi2Error, "fmi2SerializeFMUstate: buffer of %zu bytes, %zu needed", size,
                    kSerializedSize);
  header h;
  memcpy(h.magic, kMagic, sizeof kMagic);
  h.format = FORMAT_VERSION;
  h.data_size = (uint32_t)sizeof(fmu_data);
  h.guid_hash = fmu_guid_hash();
  memcpy(serializedState, &h, sizeof h);
  memcpy(serializedState + sizeof h, &p->d, sizeof p->d);
  return fmi2OK;
}

/* Structural consistency of deserialized data; the library checks the
 * numbers themselves at the next step. NULL when acceptable. */
static const char *invalid_data(const fmu_data *d) {
  if (d->mode < FMU_INSTANTIATED || d->mode > FMU_ERROR) return "unknown mode";
  const int stepping = d->mode >= FMU_STEP_COMPLETE && d->mode <= FMU_TERMINATED;
  for (int a = 0; a < RTB_AXES; ++a) {
    const int on = d->params.active[a];
    const rtb_state *s = &d->state.axis[a];
    if (on != 0 && on != 1) return "active flag not 0 or 1";
    if (!stepping) continue;
    if (s->initialised != on) return "axis state does not match its active flag";
    if (on && (s->abi_version != RTB_ABI_VERSION || s->model != d->params.axis[a].model ||
               s->cells != d->params.axis[a].cells || s->cells < 1 || s->cells > RTB_MAX_CELLS))
      return "axis state does not match its parameters";
  }
  return NULL;
}

FMI2_EXPORT fmi2Status fmi2DeSerializeFMUstate(fmi2Component c,
                                               const fmi2Byte serializedState[], size_t size,
                                               fmi2FMUstate *FMUstate) {
  fmu_instance *in = fmu_cast(c);
  if (!in) return fmi2Error;
  const char *f = "fmi2DeSerializeFMUstate";
  if (!serializedState || !FMUstate)
    return fmu_fail(in, fmi2Error, "%s: serializedState or FMUstate is NULL", f);
  if (size != kSerializedSize)
    return fmu_fail(in, fmi2Error, "%s: %zu bytes, this FMU's states have %zu", f, size,
                    kSerializedSize);
  header h;
  memcpy(&h, serializedState, sizeof h);
  if (memcmp(h.magic, kMagic, sizeof kMagic) != 0 || h.format != FORMAT_VERSION ||
      h.data_size != sizeof(fmu_data))
    return fmu_fail(in, fmi2Error, "%s: not a serialized state of this FMU", f);
  if (h.guid_hash != fmu_guid_hash())
    return fmu_fail(in, fmi2Error, "%s: the state is from an FMU with another GUID", f);
  fmu_data d;
  memcpy(&d, serializedState + sizeof h, sizeof d);
  const char *why = invalid_data(&d);
  if (why) return fmu_fail(in, fmi2Error, "%s: inconsistent state: %s", f, why);
  snapshot *p = snapshot_for(in, FMUstate);
  if (!p) return fmu_fail(in, fmi2Error, "%s: allocateMemory returned NULL", f);
  p->d = d;
  *FMUstate = p;
  return fmi2OK;
}
