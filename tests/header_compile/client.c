/* client.c -- compiled by tests/header_test.cpp as strict C99
 * (-std=c99 -pedantic -Wall -Wextra -Werror) against two generated parameter
 * headers, then run over a CSV record:
 *   client INPUT.csv rt|sts
 * prints the selected parameter set (hex floats) on the first line, then the
 * force after rtb_state_init and after every rtb_step, one per line, as %a.
 * The test compares them bit for bit with the offline tool's simulate_force. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_bushing_rt.h"
#include "test_bushing_sts.h"
#include "test_bushing_rt.h" /* twice: the include guard must hold */

#define MAX_ROWS 100000

static double t_in[MAX_ROWS], x_in[MAX_ROWS];

int main(int argc, char **argv) {
  const rtb_params *p;
  FILE *f;
  char line[512];
  int n = 0, header_seen = 0, i;
  rtb_state s;
  rtb_status st;
  double F;

  if (argc != 3) {
    fprintf(stderr, "usage: client INPUT.csv rt|sts\n");
    return 2;
  }
  p = strcmp(argv[2], "sts") == 0 ? &test_bushing_sts : &test_bushing_rt;
  st = rtb_params_validate(p);
  if (st != RTB_OK) {
    fprintf(stderr, "invalid parameters: %s\n", rtb_status_message(st));
    return 1;
  }
  f = fopen(argv[1], "r");
  if (!f) {
    perror(argv[1]);
    return 1;
  }
  while (fgets(line, sizeof line, f)) {
    char *end;
    if (line[0] == '#' || line[0] == '\n') continue;
    if (!header_seen) { /* "time,displacement[,...]" */
      header_seen = 1;
      continue;
    }
    if (n >= MAX_ROWS) break;
    t_in[n] = strtod(line, &end);
    if (*end != ',') {
      fprintf(stderr, "bad row %d\n", n);
      return 1;
    }
    x_in[n] = strtod(end + 1, &end);
    ++n;
  }
  fclose(f);
  if (n < 2) return 1;

  printf("%d %d %d %d", p->abi_version, p->model, p->cells, p->integrator);
  printf(" %a %a %a %a %a %a %a %a %a %a %a %a %a %a\n", p->K0, p->Kpa, p->Kr, p->C0, p->alpha,
         p->Ff, p->k3, p->k_asym, p->maxwell_k, p->maxwell_tau, p->viscous_c, p->mass,
         p->backlash, p->mullins);

  st = rtb_state_init(&s, p, x_in[0]);
  if (st != RTB_OK) {
    fprintf(stderr, "init: %s\n", rtb_status_message(st));
    return 1;
  }
  printf("%a\n", s.force);
  for (i = 1; i < n; ++i) {
    st = rtb_step(&s, p, NULL, x_in[i], t_in[i] - t_in[i - 1], &F);
    if (st < 0) {
      fprintf(stderr, "step %d: %s\n", i, rtb_status_message(st));
      return 1;
    }
    printf("%a\n", F);
  }
  return 0;
}
