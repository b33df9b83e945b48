/* single_client.c -- the single-precision library (rt_bushing_float,
 * RTB_SINGLE) on the standard input of tests/single_precision_test.cpp:
 * rtb_params_default (N = 15, SDIRK2), virgin state, dt = 1 ms, 300 steps of
 * x = 1 mm sin(2 pi 10 Hz t) + 0.3 mm sin(2 pi 37 Hz t), x rounded to float.
 * Prints "scalar <name> <bytes>", then per step "<x> <F> <status>" with 9
 * significant digits (float round-trips). */
#include <math.h>
#include <stdio.h>

#include "rt_bushing.h"

int main(void) {
  rtb_params p;
  rtb_state s;
  rtb_info info;
  rtb_get_info(&info);
  printf("scalar %s %d\n", info.scalar, info.scalar_bytes);
  if (rtb_params_default(&p, RTB_MODEL_RT) != RTB_OK || rtb_state_init(&s, &p, 0.0f) != RTB_OK)
    return 1;
  for (int i = 1; i <= 300; ++i) {
    const double two_pi = 6.283185307179586476925, t = i * 1e-3;
    const rtb_real x = (rtb_real)(sin(two_pi * 10.0 * t) + 0.3 * sin(two_pi * 37.0 * t));
    rtb_real F = 0;
    const rtb_status st = rtb_step(&s, &p, NULL, x, (rtb_real)1e-3, &F);
    printf("%.9g %.9g %d\n", (double)x, (double)F, (int)st);
  }
  return 0;
}
