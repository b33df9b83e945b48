/* six_axis.cpp -- six independent channels x, y, z, rx, ry, rz, each a
 * complete single-axis element (rt_bushing.h, "Six-axis bushing").
 *
 * Everything is delegated to the single-axis calls with each axis's own
 * rtb_params, embedded by value, so fields added to rtb_params need no change
 * here. All-or-nothing: every axis is evaluated into a trial before anything
 * is committed, so an error on the last axis leaves the first five untouched.
 */
#include <string.h>

#include "rtb_internal.h"
#include "no_heap.h"

static const char *const kAxisNames[RTB_AXES] = {"x", "y", "z", "rx", "ry", "rz"};

static void set_bad(int *bad_axis, int axis) {
  if (bad_axis) *bad_axis = axis;
}

extern "C" const char *rtb_axis_name(int axis) {
  return axis >= 0 && axis < RTB_AXES ? kAxisNames[axis] : NULL;
}

extern "C" rtb_status rtb_bushing6_params_default(rtb_bushing6_params *p, int model) {
  if (!p) return RTB_ERR_NULL;
  rtb_params one;
  const rtb_status st = rtb_params_default(&one, model);
  if (st != RTB_OK) return st;
  memset(p, 0, sizeof *p);
  for (int a = 0; a < RTB_AXES; ++a) {
    p->active[a] = 1;
    p->axis[a] = one;
  }
  return RTB_OK;
}

extern "C" rtb_status rtb_bushing6_validate(const rtb_bushing6_params *p, int *bad_axis) {
  set_bad(bad_axis, -1);
  if (!p) return RTB_ERR_NULL;
  for (int a = 0; a < RTB_AXES; ++a) {
    if (p->active[a] != 0 && p->active[a] != 1) {
      set_bad(bad_axis, a);
      return RTB_ERR_MODEL;
    }
    if (!p->active[a]) continue;
    const rtb_status st = rtb_params_validate(&p->axis[a]);
    if (st != RTB_OK) {
      set_bad(bad_axis, a);
      return st;
    }
  }
  return RTB_OK;
}

extern "C" rtb_status rtb_bushing6_init(rtb_bushing6_state *s, const rtb_bushing6_params *p,
                                        const rtb_real x0[RTB_AXES], int *bad_axis) {
  set_bad(bad_axis, -1);
  if (!s || !p) return RTB_ERR_NULL;
  rtb_status st = rtb_bushing6_validate(p, bad_axis);
  if (st != RTB_OK) return st;
  rtb_bushing6_state t;
  memset(&t, 0, sizeof t);
  for (int a = 0; a < RTB_AXES; ++a) {
    if (!p->active[a]) continue;
    st = rtb_state_init(&t.axis[a], &p->axis[a], x0 ? x0[a] : 0.0);
    if (st != RTB_OK) {
      set_bad(bad_axis, a);
      return st;
    }
  }
  *s = t;
  return RTB_OK;
}

/* An off axis must hold an uninitialised (zero) state and an on axis an
 * initialised one: a state from other parameters is RTB_ERR_STATE. */
static rtb_status check_activity(const rtb_bushing6_state *s, const rtb_bushing6_params *p,
                                 int *bad_axis) {
  for (int a = 0; a < RTB_AXES; ++a)
    if ((p->active[a] != 0) != (s->axis[a].initialised != 0)) {
      set_bad(bad_axis, a);
      return RTB_ERR_STATE;
    }
  return RTB_OK;
}

extern "C" rtb_status rtb_bushing6_evaluate(const rtb_bushing6_state *s,
                                            const rtb_bushing6_params *p,
                                            const rtb_settings *set, const rtb_real x[RTB_AXES],
                                            rtb_real dt, rtb_bushing6_state *trial,
                                            rtb_real force[RTB_AXES],
                                            rtb_real dforce_dx[RTB_AXES], int *bad_axis) {
  set_bad(bad_axis, -1);
  if (!s || !p || !x || !trial || !force) return RTB_ERR_NULL;
  if (trial == s) return RTB_ERR_NULL;
  rtb_status st = rtb_bushing6_validate(p, bad_axis);
  if (st != RTB_OK) return st;
  st = check_activity(s, p, bad_axis);
  if (st != RTB_OK) return st;
  if (!(dt >= RTB_DT_MIN && dt <= RTB_DT_MAX)) return RTB_ERR_DT; /* also when all are off */

  rtb_real F[RTB_AXES] = {0.0}, K[RTB_AXES] = {0.0};
  rtb_status worst = RTB_OK;
  for (int a = 0; a < RTB_AXES; ++a) {
    if (!p->active[a]) {
      memset(&trial->axis[a], 0, sizeof trial->axis[a]);
      continue;
    }
    st = rtb_evaluate(&s->axis[a], &p->axis[a], set, x[a], dt, &trial->axis[a], &F[a],
                      dforce_dx ? &K[a] : NULL);
    if (st < 0) {
      set_bad(bad_axis, a);
      return st;
    }
    if (st == RTB_NOT_CONVERGED && worst == RTB_OK) {
      worst = st;
      set_bad(bad_axis, a);
    }
  }
  memcpy(force, F, sizeof F);
  if (dforce_dx) memcpy(dforce_dx, K, sizeof K);
  return worst;
}

extern "C" rtb_status rtb_bushing6_commit(rtb_bushing6_state *s,
                                          const rtb_bushing6_state *trial) {
  if (!s || !trial) return RTB_ERR_NULL;
  if (s != trial) *s = *trial;
  return RTB_OK;
}

extern "C" rtb_status rtb_bushing6_step(rtb_bushing6_state *s, const rtb_bushing6_params *p,
                                        const rtb_settings *set, const rtb_real x[RTB_AXES],
                                        rtb_real dt, rtb_real force[RTB_AXES], int *bad_axis) {
  set_bad(bad_axis, -1);
  if (!s || !force) return RTB_ERR_NULL;
  rtb_bushing6_state next;
  rtb_real F[RTB_AXES];
  const rtb_status st = rtb_bushing6_evaluate(s, p, set, x, dt, &next, F, NULL, bad_axis);
  if (st < 0) return st;
  *s = next;
  memcpy(force, F, sizeof F);
  return st;
}
