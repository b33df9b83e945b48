// client.cpp -- the C++17 twin of client.c (g++ -std=c++17 -pedantic -Wall
// -Wextra -Werror): same output, so the generated header is also valid C++.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "test_bushing_rt.h"
#include "test_bushing_sts.h"
#include "test_bushing_rt.h"  // twice: the include guard must hold

// The constant really is an rtb_params.
static_assert(sizeof(test_bushing_rt) == sizeof(rtb_params), "layout");

int main(int argc, char **argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: client INPUT.csv rt|sts\n");
    return 2;
  }
  const rtb_params *p = std::strcmp(argv[2], "sts") == 0 ? &test_bushing_sts : &test_bushing_rt;
  rtb_status st = rtb_params_validate(p);
  if (st != RTB_OK) {
    std::fprintf(stderr, "invalid parameters: %s\n", rtb_status_message(st));
    return 1;
  }
  std::FILE *f = std::fopen(argv[1], "r");
  if (!f) {
    std::perror(argv[1]);
    return 1;
  }
  std::vector<double> t, x;
  char line[512];
  bool header_seen = false;
  while (std::fgets(line, sizeof line, f)) {
    if (line[0] == '#' || line[0] == '\n') continue;
    if (!header_seen) {
      header_seen = true;
      continue;
    }
    char *end;
    t.push_back(std::strtod(line, &end));
    if (*end != ',') return 1;
    x.push_back(std::strtod(end + 1, &end));
  }
  std::fclose(f);
  if (t.size() < 2) return 1;

  std::printf("%d %d %d %d", p->abi_version, p->model, p->cells, p->integrator);
  std::printf(" %a %a %a %a %a %a %a %a %a %a %a %a %a %a\n", p->K0, p->Kpa, p->Kr, p->C0,
              p->alpha, p->Ff, p->k3, p->k_asym, p->maxwell_k, p->maxwell_tau, p->viscous_c,
              p->mass, p->backlash, p->mullins);
  rtb_state s;
  st = rtb_state_init(&s, p, x[0]);
  if (st != RTB_OK) return 1;
  std::printf("%a\n", s.force);
  for (size_t i = 1; i < t.size(); ++i) {
    double F;
    st = rtb_step(&s, p, nullptr, x[i], t[i] - t[i - 1], &F);
    if (st < 0) {
      std::fprintf(stderr, "step %zu: %s\n", i, rtb_status_message(st));
      return 1;
    }
    std::printf("%a\n", F);
  }
  return 0;
}
