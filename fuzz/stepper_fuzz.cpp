// stepper_fuzz.cpp -- the stepper's public promises (rt_bushing.h) under
// random parameters, settings and inputs:
//   * status >= 0: finite force and finite tangent dF/dx;
//   * status < 0: the committed state is unchanged (memcmp) and the outputs
//     are not written;
//   * rtb_evaluate never writes the committed state, and rtb_evaluate +
//     rtb_commit equals rtb_step bit for bit (state, force, status);
//   * rtb_step_info is filled with sane counts on success.
// The bytes choose a parameter set (mostly valid, sometimes one raw field),
// optional settings, then up to kMaxSteps (x, dt) pairs.
#include <cmath>
#include <cstdint>
#include <cstring>

#include "fuzz/fuzz_bytes.h"
#include "rt_bushing/rt_bushing.h"

namespace {

using rtb_fuzz::Bytes;
using rtb_fuzz::fail;

constexpr int kMaxSteps = 48;

rtb_params make_params(Bytes &in) {
  const uint8_t mode = in.u8();
  rtb_params p;
  rtb_params_default(&p, (mode & 1) ? RTB_MODEL_STS : RTB_MODEL_RT);
  p.integrator = (mode & 2) ? RTB_INTEGRATOR_BE : RTB_INTEGRATOR_SDIRK2;
  p.cells = 1 + in.u8() % RTB_MAX_CELLS;
  p.K0 = (mode & 4) ? 0.0 : in.log_uniform(1e-3, 1e6);
  p.Kpa = in.log_uniform(1e-3, 1e6);
  p.Kr = in.log_uniform(1e-3, 1e7);
  p.C0 = in.log_uniform(1e-3, 1e4);
  p.alpha = RTB_ALPHA_MIN + in.unit() * (1.0 - RTB_ALPHA_MIN);
  p.Ff = in.log_uniform(1e-3, 1e4);
  const uint8_t ext = in.u8();  // one bit per extension
  if (ext & 1) p.k3 = (in.unit() * 2.0 - 1.0) * in.log_uniform(1e-6, 1e4);
  if (ext & 2) p.k_asym = (in.unit() * 2.0 - 1.0) * p.K0;
  if (ext & 4) {
    p.maxwell_k = in.log_uniform(1e-3, 1e6);
    p.maxwell_tau = in.log_uniform(1e-6, 1e3);
  }
  if (ext & 8) p.viscous_c = in.log_uniform(1e-6, 1e3);
  if (ext & 16) p.mass = in.log_uniform(1e-9, 1e0);
  if (ext & 32) p.backlash = in.log_uniform(1e-9, 1e1);
  if (ext & 64) p.mullins = in.unit();
  if (ext & 128) {
    p.sat_force = in.log_uniform(1e-3, 1e5);
    p.sat_disp = in.log_uniform(1e-6, 1e2);
  }
  if (mode & 8) p.smoothing = in.log_uniform(1e-3, 1e6);
  const uint8_t ext3 = in.u8();  // the ABI 3 extensions
  if (ext3 & 1) p.slack = 1.0;
  else if (ext3 & 2) p.backlash_held = 1.0;
  if ((ext3 & 4) && p.model == RTB_MODEL_RT) p.fric_asym = in.unit() * 1.98 - 0.99;
  if (ext3 & 16) p.k2 = (in.unit() * 2.0 - 1.0) * in.log_uniform(1e-6, 1e4);  // ABI 6
  if (ext3 & 32) p.mullins_whole = 1.0;                                         // ABI 7
  if (ext3 & 128) p.relax_width = in.log_uniform(1e-6, 1e2);                    // ABI 9
  if ((ext3 & 64) && p.sat_force > 0.0 && p.k_asym == 0.0)  // K0 < 0 under a softening spring
    p.K0 = -in.unit() * (1.0 / (1.0 / p.Kpa + p.cells / p.Kr) + p.sat_force / p.sat_disp);
  if (ext3 & 8) {
    p.spec_k = in.log_uniform(1e-3, 1e5);
    p.spec_exp = in.unit() * 2.0 - 1.0;
    p.spec_tau_min = in.log_uniform(1e-5, 1e1);
    p.spec_tau_max = p.spec_tau_min * in.log_uniform(1.0, 1e8);
  }
  // Rarely, any bits in one field (the validation paths and RTB_ERR_*).
  if ((mode & 0x70) == 0x70) {
    const uint8_t which = in.u8();
    if (which < 4) {
      int32_t v = (int32_t)in.u32();
      std::memcpy(reinterpret_cast<char *>(&p) + which * sizeof(int32_t), &v, sizeof v);
    } else {
      const size_t nd = (sizeof p - 4 * sizeof(int32_t)) / sizeof(rtb_real);
      rtb_real *d = reinterpret_cast<rtb_real *>(reinterpret_cast<char *>(&p) + 4 * sizeof(int32_t));
      d[which % nd] = in.raw_double();
    }
  }
  return p;
}

// NULL (the defaults) or settings from the bytes, sometimes out of range.
const rtb_settings *make_settings(Bytes &in, rtb_settings *set) {
  const uint8_t mode = in.u8();
  if ((mode & 3) != 0) return nullptr;
  rtb_settings_default(set);
  set->tol = in.log_uniform(1e-17, 1e-1);
  set->max_iter = (int32_t)(in.u8() % 110);
  set->max_backtrack = (int32_t)(in.u8() % 70);
  const uint8_t w = in.u8();  // mostly small budgets, sometimes 0 (rejected)
  set->max_work = w < 200 ? (int32_t)w * 8 : (int32_t)(RTB_STEP_WORK + (w - 200) * 1024);
  return set;
}

void next_input(Bytes &in, double amp, double *x, double *dt) {
  const uint8_t kind = in.u8();
  switch (kind & 7) {
    case 0: *x = in.raw_double(); break;                              // any bits
    case 1: *x = (in.unit() < 0.5 ? -1.0 : 1.0) * in.log_uniform(1e-12, 1e12); break;
    case 2: *x += amp * (in.unit() * 2.0 - 1.0) * 0.05; break;       // small move
    default: *x = amp * (in.unit() * 2.0 - 1.0); break;              // jump within amp
  }
  *dt = (kind & 0x80) ? in.raw_double() : in.log_uniform(1e-10, 2e3);
}

bool same(const void *a, const void *b, size_t n) { return std::memcmp(a, b, n) == 0; }

void check_step(const rtb_state &s, const rtb_params &p, const rtb_settings *set, double x,
                double dt) {
  const double kSentinel = -31415.9265;
  // Trial evaluation: s must not move.
  rtb_state committed = s, trial;
  std::memset(&trial, 0x5a, sizeof trial);
  double fe = kSentinel, dfe = kSentinel;
  rtb_step_info info;
  std::memset(&info, 0x5a, sizeof info);
  const rtb_step_info info_before = info;
  const rtb_status se = rtb_evaluate_ex(&committed, &p, set, x, dt, &trial, &fe, &dfe, &info);
  if (!same(&committed, &s, sizeof s)) fail("rtb_evaluate wrote the committed state");

  // The real step on a copy.
  rtb_state stepped = s;
  double fs = kSentinel;
  const rtb_status ss = rtb_step(&stepped, &p, set, x, dt, &fs);
  if (ss != se) fail("rtb_step and rtb_evaluate disagree on the status");
  if (ss < 0) {
    if (!same(&stepped, &s, sizeof s)) fail("rtb_step changed the state on error");
    if (fs != kSentinel || fe != kSentinel || dfe != kSentinel) fail("output written on error");
    if (!same(&info, &info_before, sizeof info)) fail("rtb_step_info written on error");
    return;
  }
  if (!std::isfinite(fs)) fail("non-finite force with status >= 0");
  if (!std::isfinite(dfe)) fail("non-finite tangent dF/dx with status >= 0");
  if (!same(&fs, &fe, sizeof fs)) fail("rtb_evaluate force != rtb_step force");
  if (!same(&trial, &stepped, sizeof trial)) fail("rtb_evaluate trial != rtb_step state");
  if (rtb_commit(&committed, &trial) != RTB_OK) fail("rtb_commit failed");
  if (!same(&committed, &stepped, sizeof committed)) fail("evaluate + commit != step");
  if (!(info.iterations >= 0 && info.backtracks >= 0 && info.clearance_iterations >= 0 &&
        info.stages >= 1 && info.stages <= 2 && info.residual >= 0.0 &&
        info.clearance_residual >= 0.0))
    fail("rtb_step_info out of range");
  rtb_settings defaults;
  rtb_settings_default(&defaults);
  if (ss == RTB_OK && set == nullptr && !(info.residual <= defaults.tol))
    fail("RTB_OK with a stage residual above the default tolerance");
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
  Bytes in(data, size);
  const rtb_params p = make_params(in);
  rtb_settings set_buf;
  const rtb_settings *set = make_settings(in, &set_buf);
  rtb_state s;
  std::memset(&s, 0, sizeof s);
  const double x0 = (in.u8() & 1) ? in.log_uniform(1e-9, 1e3) * (in.unit() - 0.5) : 0.0;
  if (rtb_state_init(&s, &p, x0) != RTB_OK) {
    if (rtb_params_validate(&p) == RTB_OK) fail("valid parameters rejected by rtb_state_init");
    // Still exercise the error paths with a zeroed (uninitialised) state.
  } else if (rtb_params_validate(&p) != RTB_OK) {
    fail("rtb_state_init accepted parameters rtb_params_validate rejects");
  } else if (!std::isfinite(s.force)) {
    fail("non-finite initial force");
  }
  const double amp = in.log_uniform(1e-9, 1e3);
  double x = x0, dt = 1e-3;
  for (int i = 0; i < kMaxSteps && !in.empty(); ++i) {
    next_input(in, amp, &x, &dt);
    check_step(s, p, set, x, dt);
    double f;
    rtb_step(&s, &p, set, x, dt, &f);  // advance (or not, on error) as a host would
  }
  return 0;
}
