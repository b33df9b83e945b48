/* c99_client.c -- the public header and the library from a strict C99 host.
 * Built with -std=c99 -pedantic -Wall -Wextra -Werror (tests/CMakeLists.txt).
 * Returns 0 and prints "c99_client: OK ..." on success, 1 on failure. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "rt_bushing.h"

static int failures = 0;

static void check(int ok, const char *what) {
  if (!ok) {
    printf("c99_client: FAIL: %s\n", what);
    ++failures;
  }
}

/* Drive one state with a sine; returns the peak |force| (or -1 on failure). */
static double run_sine(const rtb_params *p, const char *name) {
  rtb_state s;
  double peak = 0.0;
  const double dt = 1e-3, amp = 0.5, freq = 5.0;
  int i;
  rtb_status st = rtb_state_init(&s, p, 0.0);
  check(st == RTB_OK, name);
  if (st != RTB_OK) return -1.0;
  for (i = 1; i <= 400; ++i) {
    const double x = amp * sin(2.0 * 3.14159265358979323846 * freq * i * dt);
    double f = 0.0;
    st = rtb_step(&s, p, NULL, x, dt, &f);
    if (st < 0 || !isfinite(f)) {
      printf("c99_client: FAIL: %s step %d status %d (%s) force %g\n", name, i, (int)st,
             rtb_status_message(st), f);
      ++failures;
      return -1.0;
    }
    if (fabs(f) > peak) peak = fabs(f);
  }
  check(s.steps == 400, "committed step count");
  return peak;
}

int main(void) {
  rtb_info info;
  rtb_params rt, sts;
  rtb_state s, before;
  double f_rt, f_sts, f = 12345.0;
  rtb_status st;

  memset(&info, 0, sizeof info);
  rtb_get_info(&info);
  check(info.abi_version == RTB_ABI_VERSION, "info.abi_version");
  check(info.max_cells == RTB_MAX_CELLS, "info.max_cells");
  check(info.scalar_bytes == (int)sizeof(rtb_real), "info.scalar_bytes");
  check(info.scalar_bytes == RTB_SCALAR_BYTES, "RTB_SCALAR_BYTES");
  check(info.version != NULL && info.version[0] != '\0', "info.version");
  check(info.scalar != NULL && strcmp(info.scalar, "double") == 0, "info.scalar");
  /* The library's struct sizes match this client's header. */
  check(info.params_bytes == (int32_t)sizeof(rtb_params), "info.params_bytes");
  check(info.state_bytes == (int32_t)sizeof(rtb_state), "info.state_bytes");
  check(info.settings_bytes == (int32_t)sizeof(rtb_settings), "info.settings_bytes");

  check(rtb_params_default(&rt, RTB_MODEL_RT) == RTB_OK, "rtb_params_default RT");
  check(rtb_params_default(&sts, RTB_MODEL_STS) == RTB_OK, "rtb_params_default STS");
  check(rtb_params_validate(&rt) == RTB_OK, "validate RT");
  check(rtb_params_validate(&sts) == RTB_OK, "validate STS");

  f_rt = run_sine(&rt, "RT sine");
  f_sts = run_sine(&sts, "STS sine");
  check(f_rt > 0.0, "RT force nonzero");
  check(f_sts > 0.0, "STS force nonzero");

  /* A NaN displacement is rejected; state and output untouched. */
  check(rtb_state_init(&s, &rt, 0.0) == RTB_OK, "init for NaN check");
  check(rtb_step(&s, &rt, NULL, 0.1, 1e-3, &f) >= 0, "step before NaN check");
  before = s;
  f = 12345.0;
  st = rtb_step(&s, &rt, NULL, NAN, 1e-3, &f);
  check(st == RTB_ERR_INPUT, "NaN input gives RTB_ERR_INPUT");
  check(f == 12345.0, "force untouched after error");
  check(memcmp(&s, &before, sizeof s) == 0, "state untouched after error");
  check(rtb_status_message(st) != NULL && rtb_status_message(st)[0] != '\0',
        "status message");

  /* rtb_step_ex reports the step's cost; trial == s is RTB_ERR_ALIAS. */
  {
    rtb_step_info si;
    rtb_state trial;
    double df = 0.0;
    memset(&si, 0, sizeof si);
    check(rtb_step_ex(&s, &rt, NULL, 0.2, 1e-3, &f, &si) == RTB_OK, "rtb_step_ex");
    rtb_settings defaults;
    rtb_settings_default(&defaults);
    check(si.stages == 2 && si.iterations >= 1 && si.residual <= defaults.tol, "rtb_step_info");
    check(rtb_evaluate_ex(&s, &rt, NULL, 0.2, 1e-3, &trial, &f, &df, NULL) == RTB_OK,
          "rtb_evaluate_ex without info");
    check(rtb_evaluate(&s, &rt, NULL, 0.2, 1e-3, &s, &f, &df) == RTB_ERR_ALIAS, "alias");
  }
  /* The six-axis element from C99: x and rz on, the rest off. */
  {
    rtb_bushing6_params p6;
    rtb_bushing6_state s6;
    double x6[RTB_AXES] = {0.1, 0.0, 0.0, 0.0, 0.0, 0.01}, F6[RTB_AXES];
    int bad = 0, a;
    check(rtb_bushing6_params_default(&p6, RTB_MODEL_RT) == RTB_OK, "bushing6 default");
    for (a = RTB_AXIS_Y; a <= RTB_AXIS_RY; ++a) p6.active[a] = 0;
    check(rtb_bushing6_init(&s6, &p6, NULL, &bad) == RTB_OK && bad == -1, "bushing6 init");
    check(rtb_bushing6_step(&s6, &p6, NULL, x6, 1e-3, F6, &bad) == RTB_OK, "bushing6 step");
    check(F6[RTB_AXIS_X] > 0.0 && F6[RTB_AXIS_RZ] > 0.0 && F6[RTB_AXIS_Y] == 0.0,
          "bushing6 forces");
    check(strcmp(rtb_axis_name(RTB_AXIS_RZ), "rz") == 0, "rtb_axis_name");
  }

  if (failures) {
    printf("c99_client: %d failure(s)\n", failures);
    return 1;
  }
  printf("c99_client: OK (rt_bushing %s, abi %d, peak |F| RT %.3f N, STS %.3f N)\n",
         info.version, info.abi_version, f_rt, f_sts);
  return 0;
}
