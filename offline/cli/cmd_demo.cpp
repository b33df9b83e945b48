// cmd_demo.cpp -- `rtb demo`: the whole pipeline on built-in generated data.
//   1. the element itself: a hysteresis loop and a relaxation (section 3.4);
//   2. records with a hidden effect the tool is not told about;
//   3. identify -> diagnose -> extend -> emit header, with the verdict.
#include <cmath>
#include <cstdio>
#include <sys/stat.h>

#include "cli/cli.h"
#include "cli/diagnose_report.h"
#include "diagnose/diagnose.h"
#include "io/csv.h"
#include "synth/synthetic_records.h"

namespace rtb {
namespace cli {

namespace {

void element_table() {
  rtb_params p;
  rtb_params_default(&p, RTB_MODEL_RT);
  std::printf("== 1. The RT element (N=15, K0=1000, Kpa=800, Kr=3000 N/mm, C0=40, alpha=0.2)\n");
  std::printf("%-28s %10s %12s\n", "input", "x [mm]", "force [N]");
  const double pi = 3.14159265358979323846;
  for (double f : {1.0, 10.0, 100.0}) {  // stabilized 1 mm sine: secant stiffness
    rtb_state s;
    rtb_state_init(&s, &p, 0.0);
    const double dt = 1.0 / (f * 2000.0);
    double F = 0, Fmax = 0;
    for (int i = 1; i <= 6000; ++i) {
      rtb_step(&s, &p, nullptr, std::sin(2 * pi * f * i * dt), dt, &F);
      if (i > 4000) Fmax = std::fmax(Fmax, F);
    }
    std::printf("sine %5.0f Hz, peak of cycle  %10.3f %12.2f   (secant %.1f N/mm)\n", f, 1.0, Fmax, Fmax);
  }
  rtb_state s;
  rtb_state_init(&s, &p, 0.0);
  double F = 0, t = 0;
  const double dt = 1e-3;
  for (double hold : {0.1, 0.2, 1.0, 10.0, 100.0}) {
    while (t < hold - 1e-12) {
      t += dt;
      rtb_step(&s, &p, nullptr, std::fmin(1.0, t / 0.1), dt, &F);
    }
    std::printf("step 1 mm (0.1 s rise), t=%5.1f s %7.3f %12.2f\n", hold, 1.0, F);
  }
  std::printf("static limit K0 x + x/(1/Kpa + N/Kr) %16.2f\n\n", rtb_static_force(&p, 1.0));
}

}  // namespace

int run_demo(int argc, char **argv) {
  static const CommandSpec spec{
      "demo",
      "Built-in example: the element's loop and relaxation, then generated records\n"
      "with a hidden effect, identified and diagnosed without being told the effect.",
      {{"effect", "NAME", "hidden effect (default backlash; any vocabulary word, backlash_held or none)"},
       {"seed", "N", "random parameters seed (default 3)"},
       {"duration", "S", "length of each generated record in seconds (default 8)"},
       {"out-dir", "DIR", "where the records, report and header go (default build/demo)"}}};
  Args a;
  if (parse_or_help(spec, argc, argv, a)) return kExitOk;
  const std::string effect = a.get("effect", "backlash");
  const std::string dir = a.get("out-dir", "build/demo");
  const double duration = a.get_double("duration", 8.0);
  if (!(duration >= 2.0 && duration <= 600.0))
    throw InputError("--duration must be between 2 and 600 s");

  for (size_t k = dir.find('/', 1); ; k = dir.find('/', k + 1)) {  // mkdir -p
    ::mkdir(dir.substr(0, k).c_str(), 0755);
    if (k == std::string::npos) break;
  }
  element_table();

  std::printf("== 2. Generated test-rig records, 0.5%% force noise, one hidden effect\n");
  const Scenario sc = hidden_effect_scenario(effect, (unsigned)a.get_int("seed", 3), 0.005, duration);
  std::vector<Record> fit, hold;
  for (const std::vector<Record> *set : {&sc.fit, &sc.holdout})
    for (const Record &r : *set) {
      const std::string path = dir + "/" + r.path + ".csv";
      write_record_csv(path, r.t, r.x, r.F, r.units);
      (set == &sc.fit ? fit : hold).push_back(read_record_csv(path));
      std::printf("  %s  (%s)\n", path.c_str(), set == &sc.fit ? "fit" : "holdout");
    }

  std::printf("\n== 3. identify -> diagnose -> extend -> header\n");
  DiagnoseOptions o;
  o.quiet = true;
  const DiagnoseResult R = diagnose(fit, hold, o);
  print_diagnosis(R);
  write_file_atomic(dir + "/report.json", diagnosis_json(R, fit, hold).dump(2) + "\n");
  write_file_atomic(dir + "/rtb_demo_params.h", diagnosis_header(R, fit, "rtb_demo_params"));
  std::printf("\nhidden effect: %s -> named: %s\n", effect.c_str(), R.cause.c_str());
  std::printf("wrote %s/report.json and %s/rtb_demo_params.h\n", dir.c_str(), dir.c_str());
  return kExitOk;
}

}  // namespace cli
}  // namespace rtb
