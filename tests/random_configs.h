// random_configs.h -- random valid parameter sets over the whole admissible
// range (RT and STS, N 1..RTB_MAX_CELLS, both integrators, stiffnesses and
// dashpot levels over 4-5 decades, alpha down to RTB_ALPHA_MIN, half of
// them with a random subset of the extensions). Shared by the robustness
// test (finite output for every valid configuration) and the worst-case
// step benchmark (bench/worst_case_bench.cpp).
#ifndef RTB_TESTS_RANDOM_CONFIGS_H
#define RTB_TESTS_RANDOM_CONFIGS_H

#include <cmath>
#include <random>

#include "rt_bushing/rt_bushing.h"

namespace rtb_test {

inline double log_uniform(std::mt19937 &g, double lo, double hi) {
  std::uniform_real_distribution<double> u(std::log(lo), std::log(hi));
  return std::exp(u(g));
}

// with_smoothing: the extension subset may also hold the eq. (14) smoothing
// and the softening spring (drawn last, so the sets without them are the
// same sequence).
inline rtb_params random_params(std::mt19937 &g, bool with_smoothing = false) {
  std::uniform_int_distribution<int> cells(1, RTB_MAX_CELLS);
  std::uniform_int_distribution<int> coin(0, 1);
  std::uniform_real_distribution<double> u01(0.0, 1.0);
  rtb_params p;
  rtb_params_default(&p, u01(g) < 0.75 ? RTB_MODEL_RT : RTB_MODEL_STS);
  p.cells = cells(g);
  p.integrator = coin(g) ? RTB_INTEGRATOR_SDIRK2 : RTB_INTEGRATOR_BE;
  p.K0 = u01(g) < 0.1 ? 0.0 : log_uniform(g, 1.0, 1e4);
  p.Kpa = log_uniform(g, 1.0, 1e4);
  p.Kr = log_uniform(g, 1.0, 1e5);
  p.C0 = log_uniform(g, 0.1, 1e3);
  p.alpha = log_uniform(g, RTB_ALPHA_MIN, 0.99);
  p.Ff = log_uniform(g, 0.1, 1e3);
  if (u01(g) < 0.5) {  // random subset of the extensions
    if (coin(g)) p.k3 = log_uniform(g, 1e-3, 1e2);
    if (coin(g)) p.k_asym = (u01(g) * 2.0 - 1.0) * p.K0;
    if (coin(g)) {
      p.maxwell_k = log_uniform(g, 1.0, 1e4);
      p.maxwell_tau = log_uniform(g, 1e-4, 10.0);
    }
    if (coin(g)) p.viscous_c = log_uniform(g, 1e-3, 1e2);
    if (coin(g)) p.mass = log_uniform(g, 1e-6, 1e-2);
    if (coin(g)) p.backlash = log_uniform(g, 1e-6, 1.0);
    if (coin(g)) p.mullins = u01(g) * 0.9;
    if (with_smoothing) {
      if (coin(g)) p.smoothing = log_uniform(g, 1e-2, 1e4);
      if (coin(g)) {
        p.sat_force = log_uniform(g, 1.0, 1e3);
        p.sat_disp = log_uniform(g, 1e-3, 1.0);
      }
    }
  }
  return p;
}

}  // namespace rtb_test

#endif
