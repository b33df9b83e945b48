// cmd_paper_figures.cpp -- `rtb paper-figures`: Figures 5, 6, 8 and 9 of Puel,
// Bourgeteau & Aubry (2013) reproduced with the real-time stepper
// (offline/report/paper_figures.h), as PNGs plus a Markdown description.
#include <cstdio>
#include <string>

#include "cli/cli.h"
#include "report/paper_figures.h"
#include "rtb_offline.h"

namespace rtb {
namespace cli {

int run_paper_figures(int argc, char **argv) {
  static const CommandSpec spec{
      "paper-figures",
      "Reproduce the paper's Figures 5, 6, 8 and 9 (sections 3.4-3.5) with the real-time\n"
      "stepper: PNGs drawn by gnuplot, plus DIR/paper_figures.md describing them with the\n"
      "measured numbers.",
      {
          {"out-dir", "DIR", "output directory (created if missing)", true},
          {"quiet", nullptr, "print nothing on success"},
      },
      "Writes fig5_cells.png, fig6_frequency_step.png, fig8_step_rt_vs_sts.png and\n"
      "fig9_two_steps.png, each with its data (.dat) and gnuplot script (.gp), and\n"
      "paper_figures.md. Deterministic: a rerun gives byte-identical files. Needs\n"
      "gnuplot (Debian package gnuplot-nox)."};
  Args a;
  if (parse_or_help(spec, argc, argv, a)) return kExitOk;
  const std::string dir = a.get("out-dir");
  if (dir.empty()) throw UsageError("--out-dir must not be empty");

  std::string md;
  write_paper_figures(dir, &md);
  const std::string md_path = dir + "/paper_figures.md";
  write_file_atomic(md_path, md);
  if (!a.has("quiet")) std::printf("wrote %s and 4 figures in %s\n", md_path.c_str(), dir.c_str());
  return kExitOk;
}

}  // namespace cli
}  // namespace rtb
