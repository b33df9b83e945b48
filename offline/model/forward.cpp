// forward.cpp -- drive the real-time stepper over a record.
#include "model/forward.h"

#include "rt_bushing/src/bushing_force.h"

#include <thread>

#include "model/parallel_for.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace rtb {

const char *start_mode_name(StartMode m) {
  return m == StartMode::ramp ? "ramp" : m == StartMode::hold ? "hold" : "auto";
}

bool holds_start(const Record &rec, const SimOptions &opt) {
  if (opt.start != StartMode::automatic) return opt.start == StartMode::hold;
  // A start within 5% of the record's reach is the rig's zero plus noise: the
  // ramp (tiny) and the hold give the same force. Beyond it the record starts
  // from a preload, which a rig reaches and holds before it records.
  double reach = 0.0;
  for (double x : rec.x) reach = std::max(reach, std::fabs(x));
  return std::fabs(rec.x[0]) > 0.05 * reach;
}

namespace {

// The ramp 0 -> x0 (the paper's first loading, section 5.5). Auto duration:
// |x0| at the record's median speed, between 10 and 10000 steps of the
// record's first dt.
void append_ramp(const Record &rec, const SimOptions &opt, DriveGrid &g) {
  const size_t n = rec.x.size();
  const double x0 = rec.x[0], dt0 = rec.t[1] - rec.t[0];
  double T = opt.ramp_time;
  if (T <= 0.0) {
    std::vector<double> speed;
    for (size_t i = 1; i < n; ++i)
      speed.push_back(std::fabs(rec.x[i] - rec.x[i - 1]) / (rec.t[i] - rec.t[i - 1]));
    std::nth_element(speed.begin(), speed.begin() + speed.size() / 2, speed.end());
    const double v = speed[speed.size() / 2];
    T = v > 0.0 ? std::fabs(x0) / v : 10.0 * dt0;
    T = std::min(std::max(T, 10.0 * dt0), 10000.0 * dt0);
  }
  const int m = std::max(1, (int)std::ceil(T / dt0));
  for (int i = 1; i <= m; ++i) {
    g.x.push_back(x0 * i / m);
    g.dt.push_back(T / m);
  }
}

// x0 held for ~1e5 s: steps growing 2x from the record's dt to the
// library's largest (RTB_DT_MAX), then 100 of those. Every dashpot, Maxwell
// branch and spectrum branch relaxes as the stepper integrates it (a power-law
// dashpot keeps ~C0 (C0 / (Kr t))^(alpha/(1-alpha)) of its force, e.g. 0.2%
// of a 1000 N load at alpha 0.15); a friction-like one (alpha -> 0) keeps its
// locked-in force, as the real device does. Being ordinary steps, the hold is
// inside the exact adjoint.
void append_hold(const Record &rec, DriveGrid &g) {
  const double x0 = rec.x[0];
  double h = rec.t[1] - rec.t[0];
  for (; h < RTB_DT_MAX; h *= 2.0) {
    g.x.push_back(x0);
    g.dt.push_back(h);
  }
  for (int i = 0; i < 100; ++i) {
    g.x.push_back(x0);
    g.dt.push_back(RTB_DT_MAX);
  }
  g.held = true;
}

}  // namespace

DriveGrid make_drive_grid(const Record &rec, const SimOptions &opt) {
  DriveGrid g;
  // The model starts at rest at x = 0 (eq. (3): y(0) = 0). A record that
  // starts elsewhere is preceded by a ramp from 0 to x[0], and, when the
  // start is held (StartMode), by a long hold there.
  g.x.push_back(0.0);
  g.dt.push_back(0.0);
  if (rec.x[0] != 0.0) {
    append_ramp(rec, opt, g);
    if (holds_start(rec, opt)) append_hold(rec, g);
  }
  g.first_sample = (int)g.x.size() - 1;
  for (size_t i = 1; i < rec.x.size(); ++i) {
    g.x.push_back(rec.x[i]);
    g.dt.push_back(rec.t[i] - rec.t[i - 1]);
  }
  return g;
}

namespace {
// Record layout per step: xb, ax (the inertia term's acceleration), z,
// xb_max, contact, z_spec[M], y[n], then per stage h f[n] v[n] y[n].
void store(const rtb_state &s, const rtb_stage *stg, int ns, int n, int M, double *d) {
  d[0] = s.xb;
  d[1] = s.ax;
  d[2] = s.z_maxwell;
  d[3] = s.xb_max;
  d[4] = s.contact;
  std::copy(s.z_spec, s.z_spec + M, d + 5);
  std::copy(s.y, s.y + n, d + 5 + M);
  d += 5 + M + n;
  for (int k = 0; k < ns; ++k) {
    if (stg) {
      d[0] = stg[k].h;
      std::copy(stg[k].f, stg[k].f + n, d + 1);
      std::copy(stg[k].v, stg[k].v + n, d + 1 + n);
      std::copy(stg[k].y, stg[k].y + n, d + 1 + 2 * n);
    } else {
      std::fill(d, d + 1 + 3 * n, 0.0);
    }
    d += 1 + 3 * n;
  }
}
}  // namespace

StepView Trajectory::step(const rtb_params &p, const DriveGrid &g, size_t i) const {
  const size_t S = stride();
  const double *a = &data[(i - 1) * S], *b = &data[i * S];
  StepView v;
  v.p = &p;
  v.dt = g.dt[i];
  v.xb_old = a[0];
  v.z_old = a[2];
  v.xbmax_old = a[3];
  v.zs_old = a + 5;
  v.xb_new = b[0];
  v.ax_new = b[1];
  v.z_new = b[2];
  v.contact = (int)b[4];
  v.zs_new = b + 5;
  v.y_new = b + 5 + branches;
  v.x_new = g.x[i];
  const double *q = v.y_new + cells;
  for (int k = 0; k < n_stages; ++k, q += 1 + 3 * cells)
    v.st[k] = StageView{q[0], q + 1, q + 1 + cells, q + 1 + 2 * cells, nullptr};
  return v;
}

Trajectory run_forward(const rtb_params &p, const DriveGrid &grid, bool keep_trace, double tol) {
  rtb_settings set;
  rtb_settings_default(&set);
  if (tol > 0.0) set.tol = tol;
  Trajectory tr;
  tr.first_sample = grid.first_sample;
  tr.n_stages = rtb_integrator_stages(&p);
  tr.cells = p.cells;
  tr.branches = rtb_spectrum_branches(&p);
  const size_t n = grid.x.size();
  rtb_state s;
  rtb_status st = rtb_state_init(&s, &p, grid.x[0]);
  if (st != RTB_OK) throw std::runtime_error(std::string("rt_bushing: ") + rtb_status_message(st));
  // A record that starts at x = 0 already moving (a sine from t = 0) did not
  // start with a velocity jump: start the input-velocity memory (inertia
  // term) at the record's initial velocity, not at rest, so that m a has no
  // spurious impulse m v0/dt at the first sample.
  // The same for a record that starts from a hold. The acceleration is then
  // not extrapolated from before the reset (ax_age = 0), and v0's step is the
  // record's, not the hold's. The input's motion is not a function of the
  // parameters, so resetting it leaves the adjoint exact.
  const size_t first = (size_t)grid.first_sample;
  const bool reset_vx = (first == 0 || grid.held) && first + 1 < n;
  const double v0 = reset_vx ? (grid.x[first + 1] - grid.x[first]) / grid.dt[first + 1] : 0.0;
  const double h0 = reset_vx ? grid.dt[first + 1] : 0.0;  // the step v0 is taken over
  if (reset_vx && first == 0) s.vx = v0, s.x_dt = h0, s.ax_age = 0.0;
  tr.force.resize(n);
  tr.force[0] = s.force;
  const size_t S = tr.stride();
  if (keep_trace) {
    tr.data.resize(n * S);
    store(s, nullptr, tr.n_stages, p.cells, tr.branches, &tr.data[0]);
  }
  rtb_stage stg[2];
  for (size_t i = 1; i < n; ++i) {
    rtb_state next;
    double F;
    st = rtb_step_detailed(&s, &p, &set, grid.x[i], grid.dt[i], &next, &F, nullptr,
                           keep_trace ? stg : nullptr);
    if (st < 0)
      throw std::runtime_error("rt_bushing step " + std::to_string(i) + ": " +
                               rtb_status_message(st));
    if (st == RTB_NOT_CONVERGED) ++tr.not_converged;
    tr.newton_iterations += next.last_iterations;
    s = next;
    if (reset_vx && i == first) s.vx = v0, s.x_dt = h0, s.ax_age = 0.0;
    tr.force[i] = F;
    if (keep_trace) store(s, stg, tr.n_stages, p.cells, tr.branches, &tr.data[i * S]);
  }
  return tr;
}

std::vector<double> simulate_force(const rtb_params &p, const Record &rec, const SimOptions &opt) {
  const DriveGrid g = make_drive_grid(rec, opt);
  Trajectory tr = run_forward(p, g, false, opt.tol);
  return std::vector<double>(tr.force.begin() + g.first_sample, tr.force.end());
}

}  // namespace rtb

namespace rtb {
int default_threads() {
  const unsigned h = std::thread::hardware_concurrency();
  return h == 0 ? 1 : (int)std::min(8u, h);
}
}  // namespace rtb
