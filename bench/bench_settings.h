/* bench_settings.h -- the solver settings the step benchmarks run with.
 *
 * RTB_BENCH_TOL: the Newton tolerance (rtb_settings.tol) of every step of
 * BM_Latency, BM_Throughput and BM_VehicleFrame; unset: NULL settings, the
 * library's default. The speed/accuracy trade a host can make
 * (docs/benchmarks.md, session 11). */
#ifndef RTB_BENCH_SETTINGS_H
#define RTB_BENCH_SETTINGS_H

#include <cstdlib>

#include "rt_bushing/rt_bushing.h"

inline const rtb_settings *bench_settings() {
  static rtb_settings set;
  static const rtb_settings *which = [] {
    const char *s = std::getenv("RTB_BENCH_TOL");
    if (!s || !*s) return static_cast<const rtb_settings *>(nullptr);
    rtb_settings_default(&set);
    set.tol = std::strtod(s, nullptr);
    return static_cast<const rtb_settings *>(&set);
  }();
  return which;
}

#endif
