/* client6.c -- compiled by tests/header_test.cpp twice, as strict C99 and
 * (with -x c++) as C++17, both with -pedantic -Wall -Wextra -Werror, against
 * a six-axis header bushing6.h written by `rtb header --axis ...`. Steps the
 * element over a fixed input and prints the six forces of every step as %a;
 * the test compares them bit for bit with rtb_bushing6_step in-process. */
#include <math.h>
#include <stdio.h>

#include "bushing6.h"
#include "bushing6.h" /* twice: the include guard must hold */

int main(void) {
  rtb_bushing6_state s;
  double x[RTB_AXES], F[RTB_AXES];
  int i, a, bad = -1;
  if (rtb_bushing6_init(&s, &bushing6, NULL, &bad) != RTB_OK) return 1;
  for (i = 1; i <= 300; ++i) {
    for (a = 0; a < RTB_AXES; ++a) x[a] = (a < RTB_AXIS_RX ? 0.5 : 0.02) * sin(0.03 * i * (a + 1));
    if (rtb_bushing6_step(&s, &bushing6, NULL, x, 1e-3, F, &bad) < 0) return 1;
    for (a = 0; a < RTB_AXES; ++a) printf("%a%c", F[a], a + 1 < RTB_AXES ? ' ' : '\n');
  }
  return 0;
}
