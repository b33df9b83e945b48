// report_test.cpp -- the figure helper (offline/report/gnuplot_figure.h):
// PNG output, byte-identical regeneration, atomicity on failure, clear errors;
// and the physics numbers behind the reproduced Figures 5, 6, 8 and 9 of Puel,
// Bourgeteau & Aubry (2013) (offline/report/paper_figures.h), asserted on
// the very data the figures plot; plus `rtb paper-figures` end to end.
#ifdef RTB_HAVE_OFFLINE
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_path.h"
#include "temp_dir.h"
#include "offline/report/gnuplot_figure.h"
#include "offline/report/paper_figures.h"
#include "rt_bushing/rt_bushing.h"
#include "text_file.h"

namespace fs = std::filesystem;
using namespace rtb;

namespace {

using rtb_test::kRtb;
using rtb_test::read_text;

#define SKIP_WITHOUT_GNUPLOT()                                                         \
  if (!gnuplot_available())                                                            \
  GTEST_SKIP() << "gnuplot is not on PATH (Debian: apt-get install gnuplot-nox); "     \
                  "figure rendering not tested"

class ReportTempDir : public rtb_test::TempDir {
 public:
  ReportTempDir() : rtb_test::TempDir("rtb_report_test") {}
};

bool starts_with_png_signature(const std::string &bytes) {
  return bytes.size() > 8 && bytes.compare(0, 8, std::string("\x89PNG\r\n\x1a\n", 8)) == 0;
}

// Two panels (the second with a log time axis), three series.
std::vector<Figure> sample_panels() {
  Figure loop, decay;
  loop.title = "loop 'quoted' title";
  loop.xlabel = "displacement x [mm]";
  loop.ylabel = "force F [N]";
  Series s;
  s.label = "model";
  for (int i = 0; i <= 200; ++i) {
    const double t = 2.0 * 3.14159265358979 * i / 200.0;
    s.x.push_back(std::sin(t));
    s.y.push_back(1000.0 * std::sin(t) + 150.0 * std::cos(t));
  }
  loop.series.push_back(s);
  decay.title = "decay";
  decay.xlabel = "time t [s]";
  decay.ylabel = "force F [N]";
  decay.logx = true;
  Series d;
  d.label = "excess";
  d.style = "lines dt 2";
  for (int i = 0; i <= 100; ++i) {
    d.x.push_back(std::pow(10.0, -3.0 + 0.06 * i));
    d.y.push_back(1160.0 + 300.0 * std::pow(d.x.back() + 1e-3, -0.25) / 5.6);
  }
  decay.series.push_back(d);
  decay.series.push_back({"", {1e-3, 1e3}, {1160.0, 1160.0}, "lines lc rgb 'black'"});
  return {loop, decay};
}

std::string with_path(const std::string &path_env) {
  const char *old = std::getenv("PATH");
  const std::string saved = old ? old : "";
  ::setenv("PATH", path_env.c_str(), 1);
  return saved;
}

}  // namespace

// ------------------------------------------------------------------ helper

TEST(ReportFigure, WritesPngAndRegeneratesByteIdentical) {
  SKIP_WITHOUT_GNUPLOT();
  ReportTempDir d;
  const std::string png = d.file("panels.png");
  render_png(png, sample_panels());
  const std::string first = read_text(png), dat1 = read_text(d.file("panels.dat")),
                    gp1 = read_text(d.file("panels.gp"));
  EXPECT_TRUE(starts_with_png_signature(first)) << first.size() << " bytes";
  EXPECT_NE(gp1.find("set multiplot layout 1,2"), std::string::npos) << gp1;
  EXPECT_NE(gp1.find("set logscale x"), std::string::npos);
  render_png(png, sample_panels());
  EXPECT_TRUE(read_text(png) == first) << "PNG differs when regenerated";
  EXPECT_EQ(read_text(d.file("panels.dat")), dat1);
  EXPECT_EQ(read_text(d.file("panels.gp")), gp1);
  // Only the three outputs, no temporary left behind.
  EXPECT_EQ(d.entries(), (std::vector<std::string>{"panels.dat", "panels.gp", "panels.png"}));
}

TEST(ReportFigure, FailedRenderLeavesNoPartialPngAndKeepsTheOldOne) {
  SKIP_WITHOUT_GNUPLOT();
  ReportTempDir d;
  std::vector<Figure> bad = sample_panels();
  bad[0].series[0].style = "no_such_plot_style";
  try {
    render_png(d.file("bad.png"), bad);
    FAIL() << "expected a gnuplot failure";
  } catch (const std::runtime_error &e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("gnuplot exited with status"), std::string::npos) << msg;
    EXPECT_NE(msg.find("bad.gp"), std::string::npos) << msg;
  }
  for (const std::string &e : d.entries()) EXPECT_EQ(e.find(".png"), std::string::npos) << e;

  // A failure over an existing figure leaves it intact.
  const std::string png = d.file("keep.png");
  render_png(png, sample_panels());
  const std::string good = read_text(png);
  EXPECT_THROW(render_png(png, bad), std::runtime_error);
  EXPECT_TRUE(read_text(png) == good);
  for (const std::string &e : d.entries()) EXPECT_EQ(e.find(".tmp"), std::string::npos) << e;
}

TEST(ReportFigure, MissingGnuplotIsReportedClearly) {
  ReportTempDir d;
  const std::string saved = with_path(d.path());  // an empty directory
  EXPECT_FALSE(gnuplot_available());
  std::string msg;
  try {
    render_png(d.file("x.png"), sample_panels());
  } catch (const std::runtime_error &e) {
    msg = e.what();
  }
  ::setenv("PATH", saved.c_str(), 1);
  EXPECT_NE(msg.find("gnuplot not found on PATH"), std::string::npos) << msg;
  EXPECT_NE(msg.find("gnuplot-nox"), std::string::npos) << msg;
  EXPECT_TRUE(d.entries().empty());
}

TEST(ReportFigure, RejectsBadInputBeforeWritingAnything) {
  ReportTempDir d;
  std::vector<Figure> p = sample_panels();
  EXPECT_THROW(render_png(d.file("a.png"), {}), std::invalid_argument);
  EXPECT_THROW(render_png(d.file("a.svg"), p), std::invalid_argument);
  p[1].series[0].y.pop_back();
  EXPECT_THROW(render_png(d.file("a.png"), p), std::invalid_argument);
  p = sample_panels();
  p[0].series[0].style = "lines\nset output '/etc/x'";
  EXPECT_THROW(render_png(d.file("a.png"), p), std::invalid_argument);
  p = sample_panels();
  p[0].series.clear();
  EXPECT_THROW(render_png(d.file("a.png"), p), std::invalid_argument);
  EXPECT_TRUE(d.entries().empty());
}

// Series longer than kMaxPlotPoints are decimated by a stride, ends kept.
TEST(ReportFigure, LongSeriesAreDecimated) {
  SKIP_WITHOUT_GNUPLOT();
  ReportTempDir d;
  Figure f;
  f.title = "long";
  Series s;
  s.label = "ramp";
  const int n = 50001;
  for (int i = 0; i < n; ++i) {
    s.x.push_back(i);
    s.y.push_back(0.5 * i);
  }
  f.series.push_back(s);
  render_png(d.file("long.png"), {f});
  std::ifstream in(d.file("long.dat"));
  std::string line, last;
  size_t rows = 0;
  while (std::getline(in, line))
    if (!line.empty() && line[0] != '#') {
      ++rows;
      last = line;
    }
  EXPECT_LE(rows, kMaxPlotPoints);
  EXPECT_GT(rows, kMaxPlotPoints / 2);
  EXPECT_EQ(last, "50000 25000");
}

// ------------------------------------------------------------------ Figure 5

// The rescaled parameter sets give the STS loop the same tip load F* at the
// same amplitude X* for every N (section 5.4 closed form, 2750 N at 2.15 mm),
// including the hand-matched N = 1; and the RT loops drawn in Figure 5
// converge: for N >= 10 the whole cycle is within 1 % of Fmax of N = 15,
// while N = 2 is visibly off (> 3 %), and the gap shrinks from N = 2 to 10.
TEST(ReportPaperFigures, Figure5CellCountLoopsConverge) {
  const CellCountStudy s = cell_count_study();
  ASSERT_EQ(s.cells.size(), s.loops.size());
  EXPECT_NEAR(s.amplitude, 2.15, 1e-12);
  EXPECT_NEAR(s.Fmax, 2750.0, 1e-9);
  for (size_t k = 0; k < s.cells.size(); ++k) {
    const int N = s.cells[k];
    SCOPED_TRACE(testing::Message() << "N = " << N);
    EXPECT_EQ(s.loops[k].not_converged, 0);
    EXPECT_NEAR(s.params[k].K0, 1000.0, 1e-9);
    EXPECT_NEAR(s.params[k].Kpa, 800.0, 1e-9);
    if (N >= 2) {
      EXPECT_NEAR(s.params[k].Kr, 3000.0 * (N - 1) / 14.0, 1e-9);
      EXPECT_NEAR(s.params[k].C0, 600.0 / N, 1e-9);
    }
    // STS with the same scaling: stabilised tip load F* exactly.
    const rtb_params sts = cell_count_params(N, RTB_MODEL_STS);
    rtb_state st;
    ASSERT_EQ(rtb_state_init(&st, &sts, 0.0), RTB_OK);
    const int spc = 400;
    double F = 0.0, F_tip = 0.0;
    for (int i = 1; i <= 3 * spc; ++i) {
      const double u = std::fmod((double)i / spc, 1.0);
      const double x = u < 0.25 ? 4 * u : (u < 0.75 ? 2 - 4 * u : 4 * u - 4);
      ASSERT_GE(rtb_step(&st, &sts, nullptr, s.amplitude * x, 1e-3, &F), 0);
      if (i == 2 * spc + spc / 4) F_tip = F;  // top of the third cycle
    }
    EXPECT_NEAR(F_tip, 2750.0, 1e-6);

    EXPECT_NEAR(s.F_max[k], s.F_max[4], 0.02 * s.Fmax);  // max load within 2 % of N = 15
    if (N >= 10) EXPECT_LT(s.dF_vs_15[k], 0.01 * s.Fmax);
  }
  EXPECT_EQ(s.cells[4], 15);
  EXPECT_GT(s.dF_vs_15[1], 0.03 * s.Fmax);               // N = 2
  EXPECT_GT(s.dF_vs_15[1], s.dF_vs_15[2]);               // N = 2 > N = 5
  EXPECT_GT(s.dF_vs_15[2], 2.0 * s.dF_vs_15[3]);         // N = 5 > 2 x (N = 10)
}

// ------------------------------------------------------------------ Figure 6

// d ln(F - F_static) / d ln(tau) between tau1 and tau2 after the end of the
// rise (nearest samples).
double excess_decay_exponent(const StepStudy &r, double tau1, double tau2) {
  auto excess_at = [&](double tau, double *tau_found) {
    size_t best = 0;
    for (size_t i = 0; i < r.rt.t.size(); ++i)
      if (std::fabs(r.rt.t[i] - r.rise - tau) < std::fabs(r.rt.t[best] - r.rise - tau)) best = i;
    *tau_found = r.rt.t[best] - r.rise;
    return r.rt.F[best] - r.F_static;
  };
  double t1, t2;
  const double e1 = excess_at(tau1, &t1), e2 = excess_at(tau2, &t2);
  return std::log(e2 / e1) / std::log(t2 / t1);
}

// Left: the secant stiffness grows 3-7 % per decade (paper 4 %, 4.5 %).
// Right: after the 10 ms step the load decays monotonically, never below the
// static limit, and ends within 1 % of it after 1e6 s.
TEST(ReportPaperFigures, Figure6StiffeningAndRelaxation) {
  const FrequencyStudy f = frequency_study();
  ASSERT_EQ(f.secant.size(), 3u);
  for (int k = 0; k < 2; ++k) {
    const double inc = f.secant[k + 1] / f.secant[k] - 1.0;
    EXPECT_GT(inc, 0.03) << "decade " << k;
    EXPECT_LT(inc, 0.07) << "decade " << k;
  }
  const StepStudy r = heaviside_relaxation();
  EXPECT_EQ(r.rt.not_converged, 0);
  EXPECT_DOUBLE_EQ(r.F_static, 1160.0);
  EXPECT_GT(r.F_peak, r.F_static + 250.0);
  size_t i = 0;
  while (r.rt.t[i] < r.rise - 1e-12) ++i;
  for (++i; i < r.rt.F.size(); ++i) {
    ASSERT_LE(r.rt.F[i], r.rt.F[i - 1] + 1e-9 * r.F_static) << "t = " << r.rt.t[i];
    ASSERT_GT(r.rt.F[i], r.F_static) << "t = " << r.rt.t[i];
  }
  EXPECT_LT(r.rt.F.back(), 1.01 * r.F_static);
  // Late relaxation is the power law of the dashpot law (eq. (1)): with an
  // excess force e = F - F_static held by springs, e = C0 |v|^alpha and
  // v ~ de/dt give de/dt ~ -e^(1/alpha), so e ~ t^(-alpha/(1-alpha)) =
  // t^-0.25 for alpha = 0.2. Measured over the last two decades.
  const double p = excess_decay_exponent(r, 1e4, 1e6);
  std::printf("[fig6] excess decay exponent over 1e4..1e6 s: %.4f (closed form -0.25)\n", p);
  EXPECT_NEAR(p, -0.25, 0.01);
}

// ------------------------------------------------------------------ Figure 8

TEST(ReportPaperFigures, Figure8StsHoldsRtRelaxes) {
  const StepStudy s = rt_vs_sts_step();
  double rt_max = 0.0, sts_max = 0.0;
  for (double F : s.rt.F) rt_max = std::max(rt_max, F);
  for (double F : s.sts.F) sts_max = std::max(sts_max, F);
  EXPECT_DOUBLE_EQ(rt_max, s.F_peak);  // the maximum is at the end of the rise
  EXPECT_NEAR(s.sts.F.back() / sts_max, 1.0, 1e-12);
  // RT relaxes towards, and never below, the static closed form
  // K0 X + X / (1/Kpa + N/Kr) (all dashpots relaxed).
  const rtb_params p = [] {
    rtb_params q;
    rtb_params_default(&q, RTB_MODEL_RT);
    return q;
  }();
  const double F_static = p.K0 * s.X + s.X / (1.0 / p.Kpa + p.cells / p.Kr);
  EXPECT_GT(s.rt.F.back(), F_static);
  EXPECT_LT(s.rt.F.back(), rt_max);
  // Its excess decays, but not faster than the asymptotic power law t^-0.25
  // (Figure 6 test): after a finite rise the law is ~ (t + t0)^-0.25, whose
  // local exponent in t lies in (-0.25, 0). Measured -0.208 over 1..9.9 s.
  const double p8 = excess_decay_exponent(s, 1.0, 9.9);
  std::printf("[fig8] RT end/peak %.4f, static/peak %.4f, excess decay exponent 1..9.9 s %.4f\n",
              s.rt.F.back() / rt_max, F_static / rt_max, p8);
  EXPECT_LT(p8, 0.0);
  EXPECT_GT(p8, -0.25);
}

// ------------------------------------------------------------------ Figure 9

// Evanescent memory: during the second hold the load relaxes more when the
// second step opposes the first (paper, section 5.5: "the relaxation effect
// is stronger in the second case"; its Figure 9 gives no numbers, so the
// ordering is what is asserted). Measured 8.1 % (same), 61.6 % (back to 0),
// 14.6 % (past 0 to -1 mm).
TEST(ReportPaperFigures, Figure9OppositeSecondStepRelaxesMore) {
  const TwoStepStudy s = two_step_study();
  ASSERT_EQ(s.relaxed.size(), 3u);
  for (const TimeSeries &r : s.runs) EXPECT_EQ(r.not_converged, 0);
  const double same = s.relaxed[0], back = s.relaxed[1], past = s.relaxed[2];
  EXPECT_GT(same, 0.0);   // a hold after a loading step relaxes
  EXPECT_GT(back, same);
  EXPECT_GT(past, same);
  EXPECT_GT(s.F_start[0], 0.0);
  EXPECT_LT(s.F_start[1], 0.0);  // back at 0 mm the load has the opposite sign
  EXPECT_LT(s.F_start[2], 0.0);
}

// ------------------------------------------------------------------ CLI

TEST(ReportPaperFigures, CliWritesFiguresAndMarkdownReproducibly) {
  SKIP_WITHOUT_GNUPLOT();
  ReportTempDir d;
  const std::string out = d.file("a/b");  // created by the command
  const std::string cmd = "'" + kRtb + "' paper-figures --quiet --out-dir '" + out + "'";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  const char *pngs[] = {"fig5_cells.png", "fig6_frequency_step.png", "fig8_step_rt_vs_sts.png",
                        "fig9_two_steps.png"};
  const std::string md = read_text(out + "/paper_figures.md");
  std::vector<std::string> first;
  for (const char *p : pngs) {
    first.push_back(read_text(out + "/" + p));
    EXPECT_TRUE(starts_with_png_signature(first.back())) << p;
    EXPECT_NE(md.find(std::string("](") + p + ")"), std::string::npos) << p;
  }
  // The library call gives the same Markdown and byte-identical PNGs.
  std::string md2;
  write_paper_figures(d.file("again"), &md2);
  EXPECT_EQ(md, md2);
  for (size_t k = 0; k < 4; ++k)
    EXPECT_TRUE(read_text(d.file("again/") + pngs[k]) == first[k]) << pngs[k];

  EXPECT_EQ(std::system(("'" + kRtb + "' paper-figures --help >/dev/null").c_str()), 0);
  EXPECT_NE(std::system(("'" + kRtb + "' paper-figures >/dev/null 2>&1").c_str()), 0);
}

#endif  // RTB_HAVE_OFFLINE
