/* step_instructions.c -- the fixed stepping driver behind the instruction
 * counts in docs/benchmarks.md (sessions 12 and 18): the benchmark input
 * (section 3.4 element, N = 15, 10 Hz 1 mm sine plus +-17 um uniform noise
 * at 1 kHz), n steps after 2000 warm-up steps; prints the sum of forces and
 * the mean Newton iterations per step. A plain C99 client of the library.
 *
 *   cmake --build build --target rt_bushing
 *   cc -std=c99 -O2 -I. docs/scripts/step_instructions.c build/librt_bushing.a -lm -lstdc++ \
 *      -o /tmp/step_instructions
 *   valgrind --tool=callgrind /tmp/step_instructions 10000      # SDIRK2
 *   valgrind --tool=callgrind /tmp/step_instructions 10000 1    # backward Euler
 * Instructions per step = callgrind's "I refs" / 12000.
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "rt_bushing/rt_bushing.h"

int main(int argc, char **argv) {
  const long n = argc > 1 ? atol(argv[1]) : 10000;
  const int be = argc > 2 ? atoi(argv[2]) : 0;
  const double pi = 3.14159265358979323846;
  rtb_params p;
  rtb_params_default(&p, RTB_MODEL_RT);
  p.cells = 15;
  p.integrator = be ? RTB_INTEGRATOR_BE : RTB_INTEGRATOR_SDIRK2;
  rtb_state s;
  if (rtb_state_init(&s, &p, 0.0) != RTB_OK) return 1;
  double F, sum = 0.0;
  unsigned long long seed = 1;
  long iters = 0;
  for (long i = 0; i < n + 2000; ++i) {
    seed = seed * 6364136223846793005ULL + 1442695040888963407ULL;
    const double u = (double)(seed >> 11) * (1.0 / 9007199254740992.0) - 0.5;
    const double x = sin(2.0 * pi * 10.0 * (i + 1) * 1e-3) + 0.0346 * u;
    if (rtb_step(&s, &p, NULL, x, 1e-3, &F) < 0) return 1;
    sum += F;
    if (i >= 2000) iters += s.last_iterations;
  }
  printf("%.17g %g\n", sum, (double)iters / n);
  return 0;
}
