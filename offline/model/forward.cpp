// forward.cpp -- drive the real-time stepper over a record.
#include "model/forward.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace rtb {

DriveGrid make_drive_grid(const Record &rec, const SimOptions &opt) {
  DriveGrid g;
  const size_t n = rec.x.size();
  double x0 = rec.x[0];
  // The model starts at rest at x = 0 (eq. (3): y(0) = 0). A record that
  // starts elsewhere is preceded by a linear ramp from 0 to x[0] (the paper's
  // first loading, section 5.5). Auto duration: |x0| at the record's median
  // speed, between 10 and 10000 steps of the record's first dt.
  if (x0 != 0.0) {
    const double dt0 = rec.t[1] - rec.t[0];
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
    g.x.push_back(0.0);
    g.dt.push_back(0.0);
    for (int i = 1; i <= m; ++i) {
      g.x.push_back(x0 * i / m);
      g.dt.push_back(T / m);
    }
    g.first_sample = m;
  } else {
    g.x.push_back(x0);
    g.dt.push_back(0.0);
    g.first_sample = 0;
  }
  for (size_t i = 1; i < n; ++i) {
    g.x.push_back(rec.x[i]);
    g.dt.push_back(rec.t[i] - rec.t[i - 1]);
  }
  return g;
}

Trajectory run_forward(const rtb_params &p, const DriveGrid &grid, bool keep_trace, double tol) {
  rtb_settings set;
  rtb_settings_default(&set);
  set.tol = tol;
  set.max_iter = 100;
  Trajectory tr;
  tr.first_sample = grid.first_sample;
  tr.n_stages = rtb_integrator_stages(&p);
  const size_t n = grid.x.size();
  rtb_state s;
  rtb_status st = rtb_state_init(&s, &p, grid.x[0]);
  if (st != RTB_OK) throw std::runtime_error(std::string("rt_bushing: ") + rtb_status_message(st));
  tr.force.resize(n);
  tr.force[0] = s.force;
  if (keep_trace) {
    tr.states.resize(n);
    tr.stages.resize(n * tr.n_stages);
    tr.states[0] = s;
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
    tr.force[i] = F;
    if (keep_trace) {
      tr.states[i] = s;
      for (int k = 0; k < tr.n_stages; ++k) tr.stages[i * tr.n_stages + k] = stg[k];
    }
  }
  return tr;
}

std::vector<double> simulate_force(const rtb_params &p, const Record &rec, const SimOptions &opt) {
  const DriveGrid g = make_drive_grid(rec, opt);
  Trajectory tr = run_forward(p, g, false, opt.tol);
  return std::vector<double>(tr.force.begin() + g.first_sample, tr.force.end());
}

}  // namespace rtb
