// cmd_report.cpp -- `rtb report`: the real-data studies of issue #5 (friction
// damper, VHB 4910) and the paper's figures, written as markdown pages and
// PNGs into docs/results/ (what `make report` runs).
#include <sys/stat.h>

#include <cstdio>
#include <string>

#include "cli/cli.h"
#include "report/paper_figures.h"
#include "report/sine_tests_page.h"
#include "report/study.h"
#include "rtb_offline.h"

namespace rtb {
namespace cli {

int run_report(int argc, char **argv) {
  static const CommandSpec spec{
      "report",
      "Run both real-data studies (friction damper, VHB 4910 strip) and reproduce the\n"
      "paper's Figures 5, 6, 8, 9: markdown pages and PNG figures in --out-dir.",
      {
          {"data-dir", "DIR", "the measured data (default ../shared/data)"},
          {"out-dir", "DIR", "output directory (default docs/results)"},
          {"only", "NAME", "friction_damper, friction_damper_sine, vhb4910 or paper (default: all)"},
          {"quiet", nullptr, "no progress on stderr"},
      },
      "Needs the data folder (see its README for provenance and licenses) and gnuplot.\n"
      "Everything but the *_timings.md pages is reproduced byte for byte by a rerun."};
  Args a;
  if (parse_or_help(spec, argc, argv, a)) return kExitOk;
  const std::string data = a.get("data-dir", "../shared/data");
  const std::string out = a.get("out-dir", "docs/results");
  const std::string only = a.get("only", "");
  const bool quiet = a.has("quiet");
  if (!only.empty() && only != "friction_damper" && only != "friction_damper_sine" &&
      only != "vhb4910" && only != "paper")
    throw UsageError("--only must be friction_damper, friction_damper_sine, vhb4910 or paper");
  struct stat st{};
  if (only != "paper" && (stat(data.c_str(), &st) != 0 || !S_ISDIR(st.st_mode)))
    throw InputError("the measured data folder '" + data +
                     "' is missing: `rtb report` needs it (give --data-dir DIR)");
  mkdir(out.c_str(), 0777);

  if (only.empty() || only == "paper") {
    std::string md;
    write_paper_figures(out, &md);
    write_file_atomic(out + "/paper_figures.md", md);
    if (!quiet) std::fprintf(stderr, "report: paper figures written\n");
  }
  if (only.empty() || only == "friction_damper_sine") {
    write_sine_tests_page(data, out, quiet);
    if (!quiet) std::fprintf(stderr, "report: friction damper sine tests written\n");
  }
  for (const StudySpec &s : {friction_damper_study(), vhb4910_study()}) {
    if (!only.empty() && only != s.name) continue;
    if (!quiet) std::fprintf(stderr, "report: study %s\n", s.name.c_str());
    const StudyResult r = run_study(s, data, quiet);
    write_study_report(s, r, out);
    std::printf("%s: %s\n  validation error %.2f%% (baseline) -> %.2f%% (extended)\n",
                s.name.c_str(), r.diag.verdict.c_str(), 100 * r.err_val_base, 100 * r.err_val_ext);
  }
  return kExitOk;
}

}  // namespace cli
}  // namespace rtb
