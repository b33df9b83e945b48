// paper_figures.cpp -- see paper_figures.h. The studies drive rtb_step
// directly (the code a host runs), on fixed time grids.
#include "report/paper_figures.h"

#include <sys/stat.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <cstring>
#include <functional>
#include <stdexcept>

#include "identify/sts_init.h"
#include "report/gnuplot_figure.h"

namespace rtb {
namespace {


// ------------------------------------------------------------------ driving

rtb_params paper_set(int model, int cells = RTB_DEFAULT_CELLS) {
  rtb_params p;
  rtb_params_default(&p, model);  // the section 3.4 example
  p.cells = cells;
  return p;
}

using Input = std::function<double(double)>;  // displacement [mm] at time [s]

std::vector<double> uniform_grid(double T, long steps) {
  std::vector<double> g((size_t)steps + 1);
  for (long i = 0; i <= steps; ++i) g[(size_t)i] = T * (double)i / (double)steps;
  return g;
}

// Runs the stepper from rest (virgin bushing, x = 0) over the grid.
TimeSeries run(const rtb_params &p, const Input &x_of_t, const std::vector<double> &grid) {
  TimeSeries ts;
  rtb_state s;
  rtb_status st = rtb_state_init(&s, &p, 0.0);
  if (st < 0) throw std::runtime_error(std::string("paper figures: ") + rtb_status_message(st));
  ts.t.push_back(grid[0]);
  ts.x.push_back(0.0);
  ts.F.push_back(s.force);
  for (size_t i = 1; i < grid.size(); ++i) {
    const double x = x_of_t(grid[i]);
    double F = 0.0;
    st = rtb_step(&s, &p, nullptr, x, grid[i] - grid[i - 1], &F);
    if (st < 0) {
      char at[64];
      std::snprintf(at, sizeof at, " at t = %g s", grid[i]);
      throw std::runtime_error(std::string("paper figures: rtb_step: ") + rtb_status_message(st) + at);
    }
    if (st == RTB_NOT_CONVERGED) ++ts.not_converged;
    ts.t.push_back(grid[i]);
    ts.x.push_back(x);
    ts.F.push_back(F);
  }
  return ts;
}

// The last n + 1 samples (one cycle of n steps).
TimeSeries tail(const TimeSeries &ts, size_t n) {
  TimeSeries r;
  const size_t a = ts.t.size() - 1 - n;
  r.t.assign(ts.t.begin() + (long)a, ts.t.end());
  r.x.assign(ts.x.begin() + (long)a, ts.x.end());
  r.F.assign(ts.F.begin() + (long)a, ts.F.end());
  r.not_converged = ts.not_converged;
  return r;
}

double max_of(const std::vector<double> &v) { return *std::max_element(v.begin(), v.end()); }

double max_abs(const std::vector<double> &v) {
  double m = 0.0;
  for (double e : v) m = std::max(m, std::fabs(e));
  return m;
}

// Linear interpolation of F at time t (clamped to the series).
double force_at(const TimeSeries &ts, double t) {
  auto it = std::lower_bound(ts.t.begin(), ts.t.end(), t);
  if (it == ts.t.begin()) return ts.F.front();
  if (it == ts.t.end()) return ts.F.back();
  const size_t j = (size_t)(it - ts.t.begin()), i = j - 1;
  const double w = (t - ts.t[i]) / (ts.t[j] - ts.t[i]);
  return (1.0 - w) * ts.F[i] + w * ts.F[j];
}

// Triangle of amplitude A [mm], frequency f [Hz]: 0 -> A -> -A -> 0.
Input triangle(double A, double f) {
  return [A, f](double t) {
    double s = t * f;
    s -= std::floor(s);
    if (s < 0.25) return 4.0 * A * s;
    if (s < 0.75) return A * (2.0 - 4.0 * s);
    return A * (4.0 * s - 4.0);
  };
}

// The paper's "Heaviside step, not truly discontinuous" (section 3.5): a
// linear rise of `rise` seconds from 0 to X starting at t0, then hold.
double ramp_hold(double X, double rise, double t0, double t) {
  if (t <= t0) return 0.0;
  if (t >= t0 + rise) return X;
  return X * (t - t0) / rise;
}

// ------------------------------------------------------------------ Figure 5

// STS loop features of the section 3.4 example (N = 15, Ff = 40 N) at the
// amplitude where exactly N-1 cells are loaded (section 5.4): tangents after
// and before a cusp, eq. (18)-(19), and the tip (X*, F*) with
// X* = N Ff/Kpa + N(N-1) Ff/(2 Kr), F* = K0 X* + N Ff = Ksec X*, eq. (17)
// (derivation in tests/physics_helpers.h).
struct TargetFeatures {
  double Tg1, Tg2, X, F;
};

TargetFeatures target_features() {
  const rtb_params p = paper_set(RTB_MODEL_STS);
  const double N = p.cells;
  TargetFeatures f;
  f.Tg1 = p.K0 + p.Kpa;
  f.Tg2 = p.K0 + p.Kpa * p.Kr / ((N - 1.0) * p.Kpa + p.Kr);
  f.X = N * p.Ff / p.Kpa + N * (N - 1.0) * p.Ff / (2.0 * p.Kr);
  f.F = p.K0 * f.X + N * p.Ff;
  return f;
}

}  // namespace

// Figure 5 asks for "the same maximum load, secant stiffness and tangents
// before and after cusps" for every N. For N >= 2 the STS inversion
// eq. (21)-(24) of those features gives K0 and Kpa independent of N,
// Kr proportional to N-1 and Ff to 1/N; the RT dashpot follows the friction
// threshold, C0 = Ff / V0^alpha (eq. (26)) at the same mean velocity V0.
// For N = 1 eq. (19) degenerates (Tg2 = Tg1: no cell slips before the cusp),
// so the single cell is matched directly: its slipping tangent
// K0 + Kpa Kr/(Kpa + Kr) equals Tg2, and at the loop tip the friction
// element slips at +Ff with P = Kpa (X* - y) = Kr y + Ff, P = F* - K0 X*.
rtb_params cell_count_params(int cells, int model) {
  if (cells < 1 || cells > RTB_MAX_CELLS)
    throw std::invalid_argument("cell_count_params: cells outside 1.." +
                                std::to_string(RTB_MAX_CELLS));
  const rtb_params p15 = paper_set(RTB_MODEL_STS), r15 = paper_set(RTB_MODEL_RT);
  const TargetFeatures f = target_features();
  StsParams s;
  if (cells >= 2) {
    LoopFeatures lf;
    lf.Tg1 = f.Tg1;
    lf.Tg2 = f.Tg2;
    lf.Fmax = f.F;
    lf.Xmax = f.X;
    s = invert_sts(lf, cells);
  } else {
    s.K0 = p15.K0;
    s.Kpa = p15.Kpa;
    s.Kr = 1.0 / (1.0 / (f.Tg2 - s.K0) - 1.0 / s.Kpa);
    const double P = f.F - s.K0 * f.X;
    s.Ff = P - s.Kr * (f.X - P / s.Kpa);
  }
  rtb_params p = paper_set(model, cells);
  p.K0 = s.K0;
  p.Kpa = s.Kpa;
  p.Kr = s.Kr;
  if (model == RTB_MODEL_STS) p.Ff = s.Ff;
  else p.C0 = r15.C0 * s.Ff / p15.Ff;
  return p;
}

CellCountStudy cell_count_study() {
  const TargetFeatures tf = target_features();
  CellCountStudy r;
  r.amplitude = tf.X;  // 2.15 mm: the design point of the features
  r.freq = 0.1;        // quasi-static: 0.86 mm/s
  r.Tg1 = tf.Tg1;
  r.Tg2 = tf.Tg2;
  r.Fmax = tf.F;
  r.cells = {1, 2, 5, 10, 15, 30};
  const long spc = 4000;  // divisible by 4: the tips are samples
  const std::vector<double> grid = uniform_grid(3.0 / r.freq, 3 * spc);
  for (int N : r.cells) {
    r.params.push_back(cell_count_params(N, RTB_MODEL_RT));
    r.loops.push_back(tail(run(r.params.back(), triangle(r.amplitude, r.freq), grid), spc));
    r.F_max.push_back(max_of(r.loops.back().F));
    r.secant.push_back(r.F_max.back() / r.amplitude);
  }
  const TimeSeries &ref = r.loops[(size_t)(std::find(r.cells.begin(), r.cells.end(), 15) -
                                           r.cells.begin())];
  for (const TimeSeries &l : r.loops) {
    double d = 0.0;
    for (size_t i = 0; i < l.F.size(); ++i) d = std::max(d, std::fabs(l.F[i] - ref.F[i]));
    r.dF_vs_15.push_back(d);
  }
  return r;
}

// ------------------------------------------------------------------ Figure 6

FrequencyStudy frequency_study() {
  FrequencyStudy r;
  r.amplitude = 1.0;
  r.freq = {1.0, 10.0, 100.0};
  const rtb_params p = paper_set(RTB_MODEL_RT);
  const long spc = 2000;  // converged to 1e-5 in Ksec (tests/physics_test.cpp)
  for (double f : r.freq) {
    const double A = r.amplitude;
    const Input sine = [A, f](double t) { return A * std::sin(2.0 * M_PI * f * t); };
    r.loops.push_back(tail(run(p, sine, uniform_grid(4.0 / f, 4 * spc)), spc));
    // Section 3.4: secant stiffness = maximum load / maximum displacement.
    r.secant.push_back(max_of(r.loops.back().F) / max_of(r.loops.back().x));
  }
  return r;
}

StepStudy heaviside_relaxation() {
  StepStudy r;
  r.X = 1.0;
  r.rise = 0.01;
  const rtb_params p = paper_set(RTB_MODEL_RT);
  // 100 steps on the rise, then steps of 2 % of the elapsed hold (at most
  // 500 s): the relaxation is a power law (t^-1/4 for alpha = 0.2), so a
  // geometric grid resolves it evenly on the log time axis.
  std::vector<double> grid;
  const int n_rise = 100;
  for (int i = 0; i <= n_rise; ++i) grid.push_back(r.rise * i / n_rise);
  const double t_end = 1e6;
  while (grid.back() < t_end) {
    const double t = grid.back();
    grid.push_back(std::min(t + std::min(std::max(1e-4, 0.02 * (t - r.rise)), 500.0), t_end));
  }
  const double X = r.X, rise = r.rise;
  r.rt = run(p, [X, rise](double t) { return ramp_hold(X, rise, 0.0, t); }, grid);
  r.F_peak = r.rt.F[(size_t)n_rise];
  r.F_static = rtb_static_force(&p, r.X);
  return r;
}

// ------------------------------------------------------------------ Figure 8

StepStudy rt_vs_sts_step() {
  StepStudy r;
  r.X = 1.0;
  r.rise = 0.1;  // section 5.5
  const double dt = 1e-3, T = 10.0;
  const std::vector<double> grid = uniform_grid(T, std::lround(T / dt));
  const double X = r.X, rise = r.rise;
  const Input in = [X, rise](double t) { return ramp_hold(X, rise, 0.0, t); };
  const rtb_params rt = paper_set(RTB_MODEL_RT), sts = paper_set(RTB_MODEL_STS);
  r.rt = run(rt, in, grid);
  r.sts = run(sts, in, grid);
  const size_t i_rise = (size_t)std::lround(rise / dt);
  r.F_peak = r.rt.F[i_rise];
  r.sts_peak = r.sts.F[i_rise];
  r.F_static = rtb_static_force(&rt, r.X);
  return r;
}

// ------------------------------------------------------------------ Figure 9

TwoStepStudy two_step_study() {
  TwoStepStudy r;
  r.X1 = 1.0;
  r.rise = 0.1;
  r.t2 = 2.0;
  r.hold = 4.0;
  r.names = {"same direction: 0 -> 1 -> 2 mm", "opposite, back: 0 -> 1 -> 0 mm",
             "opposite, past 0: 0 -> 1 -> -1 mm"};
  r.X2 = {1.0, -1.0, -2.0};
  const double dt = 1e-3, T = r.t2 + r.rise + r.hold;
  const std::vector<double> grid = uniform_grid(T, std::lround(T / dt));
  const rtb_params p = paper_set(RTB_MODEL_RT);
  const size_t i_start = (size_t)std::lround((r.t2 + r.rise) / dt);
  for (double X2 : r.X2) {
    const double X1 = r.X1, rise = r.rise, t2 = r.t2;
    r.runs.push_back(run(p, [=](double t) {
      return ramp_hold(X1, rise, 0.0, t) + ramp_hold(X2, rise, t2, t);
    }, grid));
    r.F_start.push_back(r.runs.back().F[i_start]);
    r.F_end.push_back(r.runs.back().F.back());
    r.relaxed.push_back(1.0 - r.F_end.back() / r.F_start.back());
  }
  return r;
}

// ------------------------------------------------------------------ output

namespace {

std::string fmt(const char *f, ...) {
  char buf[1024];
  va_list ap;
  va_start(ap, f);
  std::vsnprintf(buf, sizeof buf, f, ap);
  va_end(ap);
  return buf;
}

// mkdir -p.
void make_directories(const std::string &dir) {
  for (size_t pos = 1; pos <= dir.size(); ++pos) {
    if (pos < dir.size() && dir[pos] != '/') continue;
    const std::string part = dir.substr(0, pos);
    struct stat st;
    if (::stat(part.c_str(), &st) == 0) {
      if (!S_ISDIR(st.st_mode)) throw std::runtime_error("cannot create " + dir + ": " + part + " is not a directory");
      continue;
    }
    if (::mkdir(part.c_str(), 0755) != 0 && errno != EEXIST)
      throw std::runtime_error("cannot create " + dir + ": " + std::strerror(errno));
  }
}

Series series(const std::string &label, std::vector<double> x, std::vector<double> y,
              const std::string &style = "lines") {
  Series s;
  s.label = label;
  s.x = std::move(x);
  s.y = std::move(y);
  s.style = style;
  return s;
}

std::vector<double> scaled(const std::vector<double> &v, double k, double shift = 0.0) {
  std::vector<double> r(v.size());
  for (size_t i = 0; i < v.size(); ++i) r[i] = (v[i] + shift) * k;
  return r;
}

int total_not_converged(const std::vector<TimeSeries> &v) {
  int n = 0;
  for (const TimeSeries &t : v) n += t.not_converged;
  return n;
}

const char *kRed = "lines lc rgb '#d62728'", *kBlack = "lines lc rgb 'black'",
           *kBlue = "lines lc rgb '#1f77b4'", *kPink = "lines lc rgb '#e377c2'",
           *kPurple = "lines lc rgb '#9467bd' dt 2";

std::string figure5(const std::string &dir, int &nc) {
  const CellCountStudy s = cell_count_study();
  nc += total_not_converged(s.loops);
  // Right panel: the load carried by the cell chain, F - K0 x = Kpa (x - y1)
  // (eq. (2)); without the global spring K0 the loops' shapes are visible.
  Figure f, g;
  f.title = fmt("Figure 5: loops for N cells: triangle %.2f mm, %.1f Hz (quasi-static)", s.amplitude, s.freq);
  f.xlabel = "displacement x [mm]";
  f.ylabel = "force F [N]";
  g.title = "same loops without the global spring: F - K0 x";
  g.xlabel = "displacement x [mm]";
  g.ylabel = "load in the cell chain F - K0 x [N]";
  for (size_t k = 0; k < s.cells.size(); ++k) {
    const TimeSeries &l = s.loops[k];
    std::vector<double> chain(l.F.size());
    for (size_t i = 0; i < l.F.size(); ++i) chain[i] = l.F[i] - s.params[k].K0 * l.x[i];
    f.series.push_back(series(fmt("N = %d", s.cells[k]), l.x, l.F));
    g.series.push_back(series(fmt("N = %d", s.cells[k]), l.x, chain));
  }
  render_png(dir + "/fig5_cells.png", {f, g});

  std::string md = "### Figure 5: number of cells\n\n";
  md += fmt("Stabilised loops (third cycle) under a %.2f mm, %.1f Hz triangle for N = 1 to 30. "
            "The cell parameters are rescaled with N so that the STS loops have the features "
            "of the N = 15 example at this amplitude (tangents Tg1 = %.0f and Tg2 = %.1f N/mm "
            "after and before a cusp, Fmax = %.0f N, eq. (17)-(19)): eq. (21)-(24) give K0 and "
            "Kpa independent of N, Kr = 3000 (N-1)/14 N/mm and Ff = 600/N N; the RT dashpot "
            "scales like the threshold (eq. (26) at the same mean velocity), C0 = 600/N "
            "N (s/mm)^0.2, alpha = 0.2. N = 1, where eq. (19) degenerates, "
            "is matched directly (slipping tangent = Tg2, same tip load), which happens to give "
            "the N = 2 values. The right panel removes the global spring K0 x to show the loop "
            "shapes: few cells give visible corners, and the loops for N >= 10 coincide, as in "
            "the paper. The largest gap to N = 15 over the cycle is given below.\n\n",
            s.amplitude, s.freq, s.Tg1, s.Tg2, s.Fmax);
  md += "| N | Kr [N/mm] | C0 [N (s/mm)^0.2] | max load [N] | secant [N/mm] | max abs(F - F(N=15)) [N] |\n";
  md += "|---|---|---|---|---|---|\n";
  for (size_t k = 0; k < s.cells.size(); ++k)
    md += fmt("| %d | %.1f | %.2f | %.1f | %.1f | %.1f (%.2f %%) |\n", s.cells[k],
              s.params[k].Kr, s.params[k].C0, s.F_max[k], s.secant[k], s.dF_vs_15[k],
              100.0 * s.dF_vs_15[k] / s.Fmax);
  md += "\n![Figure 5: loops for N = 1, 2, 5, 10, 15, 30 cells](fig5_cells.png)\n\n";
  return md;
}

std::string figure6(const std::string &dir, int &nc) {
  const FrequencyStudy fs = frequency_study();
  const StepStudy st = heaviside_relaxation();
  nc += total_not_converged(fs.loops) + st.rt.not_converged;
  Figure left;
  left.title = "Figure 6: sines x = 1 mm sin(2 pi f t), N = 15";
  left.xlabel = "displacement x [mm]";
  left.ylabel = "force F [N]";
  for (size_t k = 0; k < fs.freq.size(); ++k)
    left.series.push_back(series(fmt("%g Hz (secant %.0f N/mm)", fs.freq[k], fs.secant[k]),
                                 fs.loops[k].x, fs.loops[k].F));
  Figure right;
  right.title = fmt("Heaviside step to %g mm (%g ms rise), then hold; N = 15", st.X, 1e3 * st.rise);
  right.xlabel = "time since the end of the rise [s] (log scale)";
  right.ylabel = "force F [N]";
  right.logx = true;
  right.xrange = "[1e-4:1e6]";
  right.key = "top right";
  // The hold only: a log axis cannot show the rise, which starts at t = 0.
  const size_t i0 = (size_t)(std::lower_bound(st.rt.t.begin(), st.rt.t.end(), st.rise - 1e-12) -
                             st.rt.t.begin()) + 1;
  std::vector<double> t(st.rt.t.begin() + (long)i0, st.rt.t.end()),
      F(st.rt.F.begin() + (long)i0, st.rt.F.end());
  right.series.push_back(series("RT model", scaled(t, 1.0, -st.rise), F, kRed));
  right.series.push_back(series(fmt("static limit K0 x + x/(1/Kpa + N/Kr) = %.0f N", st.F_static),
                                {1e-4, 1e6}, {st.F_static, st.F_static}, "lines dt 2 lc rgb 'black'"));
  render_png(dir + "/fig6_frequency_step.png", {left, right});

  const double inc1 = fs.secant[1] / fs.secant[0] - 1.0, inc2 = fs.secant[2] / fs.secant[1] - 1.0;
  std::string md = "### Figure 6: frequency and step response\n\n";
  md += fmt("Left: stabilised loops (4th cycle) of the section 3.4 example (K0 = 1000, Kpa = 800, "
            "Kr = 3000 N/mm, C0 = 40 N (s/mm)^0.2, alpha = 0.2, N = 15) under 1 mm sines. The "
            "secant stiffness (max load / max displacement) is %.1f, %.1f and %.1f N/mm at 1, 10 "
            "and 100 Hz: +%.1f %% from 1 to 10 Hz and +%.1f %% from 10 to 100 Hz (paper: +4 %% "
            "and +4.5 %%).\n\n",
            fs.secant[0], fs.secant[1], fs.secant[2], 100 * inc1, 100 * inc2);
  md += fmt("Right: a 1 mm step with a %g ms rise, then held. The load peaks at %.0f N, relaxes "
            "to %.0f N after 1 s, %.0f N after 100 s and %.1f N after 10^6 s, toward the static "
            "limit %.0f N (dashed; rtb_static_force), %.2f %% above it at the end. The decay is "
            "a power law (t^-1/4 for alpha = 0.2), hence the log time axis.\n\n",
            1e3 * st.rise, st.F_peak, force_at(st.rt, 1.0), force_at(st.rt, 100.0), st.rt.F.back(),
            st.F_static, 100.0 * (st.rt.F.back() / st.F_static - 1.0));
  md += "![Figure 6: loops at 1, 10, 100 Hz (left); relaxation after a step (right)]"
        "(fig6_frequency_step.png)\n\n";
  return md;
}

std::string figure8(const std::string &dir, int &nc) {
  const StepStudy s = rt_vs_sts_step();
  nc += s.rt.not_converged + s.sts.not_converged;
  const double mr = max_abs(s.rt.F), ms = max_abs(s.sts.F);
  Figure f;
  f.title = fmt("Figure 8: %g mm step (%g s rise), loads normalised by their maxima", s.X, s.rise);
  f.xlabel = "time t [s]";
  f.ylabel = "normalised load F / max F [-]";
  f.yrange = "[0:1.1]";
  f.key = "bottom right";
  f.series.push_back(series(fmt("RT model (max %.0f N)", mr), s.rt.t, scaled(s.rt.F, 1.0 / mr), kRed));
  f.series.push_back(series(fmt("STS model (max %.0f N)", ms), s.sts.t, scaled(s.sts.F, 1.0 / ms), kBlack));
  render_png(dir + "/fig8_step_rt_vs_sts.png", {f});

  std::string md = "### Figure 8: step response, RT vs STS\n\n";
  md += fmt("A 1 mm displacement with a %g s rise, then held 10 s, for the section 3.4 example "
            "(RT: C0 = 40 N (s/mm)^0.2, alpha = 0.2; STS: Ff = 40 N; N = 15), each load "
            "normalised by its own maximum as in the paper. The RT load falls from %.0f N to "
            "%.3f of its maximum at 10 s; the STS load (%.0f N) stays at %.3f: friction "
            "elements do not relax.\n\n",
            s.rise, mr, s.rt.F.back() / mr, ms, s.sts.F.back() / ms);
  md += "![Figure 8: normalised load after a step, RT vs STS](fig8_step_rt_vs_sts.png)\n\n";
  return md;
}

std::string figure9(const std::string &dir, int &nc) {
  const TwoStepStudy s = two_step_study();
  nc += total_not_converged(s.runs);
  const char *styles[] = {kBlue, kPink, kPurple};
  Figure left, right;
  left.title = "Figure 9: inputs, two successive steps";
  left.xlabel = "time t [s]";
  left.ylabel = "displacement x [mm]";
  left.xrange = fmt("[0:%g]", s.t2 + s.rise + s.hold);
  left.yrange = "[-2.4:2.4]";
  left.key = "bottom right";
  right.title = "load during the second step";
  right.xlabel = "time since the end of the second rise [s]";
  right.ylabel = "normalised load F / F(start of hold) [-]";
  right.yrange = "[0:1.05]";
  right.key = "bottom left";
  const double t0 = s.t2 + s.rise;
  for (size_t k = 0; k < s.runs.size(); ++k) {
    const TimeSeries &r = s.runs[k];
    left.series.push_back(series(s.names[k], r.t, r.x, styles[k]));
    const size_t a = (size_t)(std::lower_bound(r.t.begin(), r.t.end(), t0 - 1e-9) - r.t.begin());
    std::vector<double> t(r.t.begin() + (long)a, r.t.end()), F(r.F.begin() + (long)a, r.F.end());
    right.series.push_back(series(fmt("%s (%.0f N at start)", s.names[k].c_str(), s.F_start[k]),
                                  scaled(t, 1.0, -t0), scaled(F, 1.0 / s.F_start[k]), styles[k]));
  }
  render_png(dir + "/fig9_two_steps.png", {left, right});

  std::string md = "### Figure 9: evanescent memory, two successive steps\n\n";
  md += fmt("A first step 0 -> %g mm at t = 0 and a second one at t = %g s (both with a %g s "
            "rise), N = 15 section 3.4 example. Right: the load during the %g s hold after the "
            "second rise, normalised by its value at the start of that hold. It loses %.1f %% "
            "when the second step goes the same way, but %.1f %% when it comes back to 0 and "
            "%.1f %% when it goes past 0 to -1 mm: the relaxation is stronger for opposite "
            "steps, as in the paper (the first step leaves a fading memory in the cells).\n\n",
            s.X1, s.t2, s.rise, s.hold, 100 * s.relaxed[0], 100 * s.relaxed[1], 100 * s.relaxed[2]);
  md += "![Figure 9: inputs (left) and normalised load during the second step (right)]"
        "(fig9_two_steps.png)\n\n";
  return md;
}

}  // namespace

void write_paper_figures(const std::string &out_dir, std::string *markdown) {
  if (!gnuplot_available())
    throw std::runtime_error("paper figures: gnuplot not found on PATH (Debian: sudo apt-get "
                             "install -y gnuplot-nox)");
  const std::string dir = out_dir.empty() ? std::string(".") : out_dir;
  make_directories(dir);
  int nc = 0;
  std::string md =
      "## Figures 5, 6, 8 and 9 of Puel, Bourgeteau & Aubry (2013), reproduced\n\n"
      "Simulated with the real-time stepper (rtb_step, SDIRK2) from a virgin bushing at rest. "
      "Units: displacement mm, force N, time s. Regenerate with `rtb paper-figures --out-dir "
      "DIR` (deterministic: the PNG, .dat and .gp files are byte-identical on the same "
      "machine); each PNG has its data (.dat) and gnuplot script (.gp) next to it.\n\n";
  md += figure5(dir, nc);
  md += figure6(dir, nc);
  md += figure8(dir, nc);
  md += figure9(dir, nc);
  if (nc > 0) md += fmt("Note: %d step(s) did not reach the Newton tolerance.\n\n", nc);
  if (markdown) *markdown = md;
}

}  // namespace rtb
