// paper_figures.h -- Figures 5, 6, 8 and 9 of Puel, Bourgeteau & Aubry (2013)
// (sections 3.4 and 3.5) reproduced with the real-time stepper (rtb_step),
// as PNG files plus a Markdown description with the measured numbers.
//
// Units: displacement mm, force N, time s (stiffnesses N/mm, C0 N (s/mm)^alpha).
// Parameters: the section 3.4 example set (K0 = 1000, Kpa = 800, Kr = 3000
// N/mm, C0 = 40 N (s/mm)^0.2, alpha = 0.2, N = 15; STS: Ff = 40 N), rescaled
// with N for Figure 5. Everything is deterministic: no randomness, fixed
// time grids, so regenerating gives byte-identical files.
//
// The study functions return the data behind each figure (and the numbers
// quoted in the Markdown) so that tests/report_test.cpp asserts exactly what
// the figures show.
#ifndef RTB_OFFLINE_REPORT_PAPER_FIGURES_H
#define RTB_OFFLINE_REPORT_PAPER_FIGURES_H

#include <string>
#include <vector>

#include "rt_bushing/rt_bushing.h"

namespace rtb {

struct TimeSeries {
  std::vector<double> t, x, F;  // time [s], displacement [mm], force [N]
  int not_converged = 0;        // steps that returned RTB_NOT_CONVERGED
};

// Figure 5: stabilised loops under a quasi-static triangle for several N,
// with cell parameters rescaled so the STS loops have the same features.
struct CellCountStudy {
  double amplitude = 0, freq = 0;     // triangle amplitude [mm], frequency [Hz]
  double Tg1 = 0, Tg2 = 0, Fmax = 0;  // target STS features, eq. (17)-(19) [N/mm, N]
  std::vector<int> cells;
  std::vector<rtb_params> params;
  std::vector<TimeSeries> loops;      // the last (third) cycle
  std::vector<double> F_max;          // max load over the loop [N]
  std::vector<double> secant;         // F_max / amplitude [N/mm] (section 3.4)
  std::vector<double> dF_vs_15;       // max |F_N - F_15| over the cycle [N]
};
// The Figure 5 parameter set for N cells (model RTB_MODEL_RT or _STS).
rtb_params cell_count_params(int cells, int model);
CellCountStudy cell_count_study();

// Figure 6 left: loops under 1 mm sines at 1, 10, 100 Hz (N = 15).
struct FrequencyStudy {
  double amplitude = 0;               // [mm]
  std::vector<double> freq;           // [Hz]
  std::vector<TimeSeries> loops;      // the last of 4 cycles
  std::vector<double> secant;         // max load / max displacement [N/mm]
};
FrequencyStudy frequency_study();

// Figure 6 right and Figure 8: a 1 mm step with a linear rise.
struct StepStudy {
  double X = 0, rise = 0;             // [mm], [s]
  TimeSeries rt, sts;                 // sts is empty for Figure 6
  double F_peak = 0;                  // RT load at the end of the rise [N]
  double F_static = 0;                // rtb_static_force [N]
  double sts_peak = 0;                // STS load at the end of the rise [N]
};
// Figure 6 right: 10 ms rise, hold up to 1e6 s on a geometric time grid.
StepStudy heaviside_relaxation();
// Figure 8: 0.1 s rise, hold up to 10 s, RT and STS.
StepStudy rt_vs_sts_step();

// Figure 9: two successive 0.1 s-rise steps, the second at t2.
struct TwoStepStudy {
  double X1 = 0, rise = 0, t2 = 0, hold = 0;  // [mm], [s], [s], [s]
  std::vector<std::string> names;
  std::vector<double> X2;             // second step [mm]
  std::vector<TimeSeries> runs;
  std::vector<double> F_start;        // load at the end of the 2nd rise [N]
  std::vector<double> F_end;          // load `hold` seconds later [N]
  std::vector<double> relaxed;        // 1 - F_end / F_start
};
TwoStepStudy two_step_study();

// Runs the four studies, writes fig5_cells.png, fig6_frequency_step.png,
// fig8_step_rt_vs_sts.png and fig9_two_steps.png (with their .dat and .gp)
// into out_dir (created if missing) and, if markdown is not null, returns a
// Markdown section describing them with relative image links. Throws
// std::runtime_error (gnuplot missing or failing, stepper error).
void write_paper_figures(const std::string &out_dir, std::string *markdown);

}  // namespace rtb

#endif
