// sine_tests_page.cpp -- see sine_tests_page.h.
#include "report/sine_tests_page.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>

#include "freq/record_dynstiff.h"
#include "freq/table_fit.h"
#include "identify/identify.h"
#include "identify/sts_init.h"
#include "io/atomic_file.h"
#include "io/number_text.h"
#include "model/parallel_for.h"
#include "preprocess/preprocess.h"
#include "report/dynstiff_figure.h"
#include "report/study.h"

namespace rtb {

namespace {

struct SineSet {
  const char *key, *title, *pattern;  // pattern: printf with %s frequency, %s amplitude
};

const SineSet kSets[] = {
    {"d2_36lb", "dataset-2, 36 lb", "friction_damper/d2_sine_%sHz_%sin_36lb.csv"},
    {"d2_30lb", "dataset-2, 30 lb", "friction_damper/d2_sine_%sHz_%sin_30lb.csv"},
    {"d3_30lb", "dataset-3, 30 lb", "friction_damper/d3_sine_%sHz_%sin.csv"},
};

// The tests that exist (the data README: no 2 Hz at 1 and 1.5 in).
std::vector<std::string> set_files(const SineSet &s) {
  std::vector<std::string> out;
  for (const char *f : {"0.25", "0.5", "1", "2"})
    for (const char *A : {"0.5", "1", "1.5"}) {
      if (std::string(f) == "2" && std::string(A) != "0.5") continue;
      char b[128];
      std::snprintf(b, sizeof b, s.pattern, f, A);
      out.push_back(b);
    }
  return out;
}


DynStiffRow row_of(const RecordDynStiff &r, const ComplexStiffness &k) {
  return DynStiffRow{r.freq, r.amp, k.stiffness, k.loss_angle_deg, 1.0};
}

}  // namespace

void write_sine_tests_page(const std::string &data_dir, const std::string &out_dir, bool quiet) {
  const auto t0 = std::chrono::steady_clock::now();
  // 1. Measured K* of every sine record.
  std::vector<std::vector<Record>> recs(3);
  std::vector<std::vector<RecordDynStiff>> meas(3);
  for (int s = 0; s < 3; ++s) {
    for (const std::string &f : set_files(kSets[s])) recs[s].push_back(read_record_csv(data_dir + "/" + f));
    meas[s].resize(recs[s].size());
    parallel_for(recs[s].size(), default_threads(), [&](size_t k) {
      meas[s][k] = record_dynamic_stiffness(recs[s][k], nullptr);
    });
  }

  // 2. The RT model from the measured 36 lb table (the data-sheet route).
  DynStiffTable table;
  table.path = "friction_damper d2 36 lb sine tests (measured)";
  for (const RecordDynStiff &r : meas[0]) table.rows.push_back(row_of(r, r.measured));
  TableFitOptions to;
  const TableFitResult tab = fit_dynstiff_table(table, table_initial_guess(table, RTB_DEFAULT_CELLS), to);
  const double t_table = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (!quiet) std::fprintf(stderr, "report: sine tests: table fit %.1f s\n", t_table);

  // 3. The RT model from time records: the study's fit records and
  // preprocessing, from the STS start and from the table fit (the misfit has
  // a poor basin near alpha 0.5 on this device); the lower misfit is kept.
  const auto t1 = std::chrono::steady_clock::now();
  const StudySpec spec = friction_damper_study();
  std::vector<Record> fit;
  for (const std::string &f : spec.fit_files) fit.push_back(read_record_csv(data_dir + "/" + f));
  apply_preprocess(spec.pre, fit, true);
  IdentifyOptions io;
  IdentifyResult time_fit = identify(fit, sts_initial_guess(fit, RTB_DEFAULT_CELLS, 0.2, 0.0), io);
  const IdentifyResult from_table = identify(fit, tab.fit.params, io);
  const bool table_start_won = from_table.J < time_fit.J;
  const double sts_error = time_fit.error;
  if (table_start_won) time_fit = from_table;
  const double t_time = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  if (!quiet) std::fprintf(stderr, "report: sine tests: time-record fits %.1f s\n", t_time);

  // Both models driven by every record, analysed over the record's window.
  std::vector<std::vector<ComplexStiffness>> time_pred(3), tab_pred(3);
  for (int s = 0; s < 3; ++s) {
    time_pred[s].resize(recs[s].size());
    tab_pred[s].resize(recs[s].size());
    parallel_for(recs[s].size(), default_threads(), [&](size_t k) {
      time_pred[s][k] = record_dynamic_stiffness(recs[s][k], &time_fit.params).model;
      tab_pred[s][k] = record_dynamic_stiffness(recs[s][k], &tab.fit.params).model;
    });
  }

  // 4. The page.
  std::ostringstream md;
  md << "# Friction damper: sine tests in the frequency domain\n\n"
     << "Dynamic stiffness |K*| = |F1/X1| [kip/in] and loss angle arg(F1/X1) [deg] of each "
        "displacement-controlled sine test (`rtb dynstiff --data`): the fundamental is fitted by "
        "least squares over the whole periods at full amplitude (the three constant-amplitude "
        "cycles of the ramped profile, delimited by zero crossings of x); A is the fundamental's "
        "amplitude |X1| (the 1 Hz, 1.5 in tests peak at 1.45 in, but the actuator clips their "
        "displacement towards a triangle: |X1| = 1.24 in). Next to it, two RT "
        "models (N = 15) driven by the same record and analysed over the same window:\n\n"
     << "* **time fit**: `rtb identify` on the friction-damper study's three fit records "
        "(d2 36 lb: 0.25 Hz 1.5 in, 0.5 Hz 1 in, 1 Hz 0.5 in; 20 Hz low-pass), error sqrt(J/J0) "
     << number_text("%.1f", 100 * time_fit.error) << " %, "
     << (table_start_won ? "started from the table fit (from the STS start it ends at "
                         : "from the STS start (from the table fit it ends at ")
     << number_text("%.1f", 100 * (table_start_won ? sts_error : from_table.error)) << " %);\n"
     << "* **table fit**: `rtb identify --dynstiff` on the 10-row measured table of the d2 36 lb "
        "set (what a user with only a data sheet would do): rms "
     << number_text("%.2f", 100 * tab.rms_stiffness_rel) << " % in stiffness, "
     << number_text("%.2f", tab.rms_loss_deg) << " deg in loss angle over its own rows.\n\n"
     << "A pure friction loop (a force +-Fs switching with the velocity) has F1 = (4/pi) Fs "
        "in phase with the velocity: |K*| = 4 Fs / (pi A), falling as 1/A, and a loss angle of "
        "90 deg; elastic parts and the clearance after each reversal lower the angle. The "
        "clearance of the device (the study's diagnosis) is not in these plain RT models. Both "
        "models come from 36 lb data: on the 30 lb sets they show how the band tension scales "
        "the stiffness (measured 0.6-0.7 x the 36 lb figures at 0.5 in) at a similar loss "
        "angle.\n\n";
  md << "| parameter | time fit | table fit | table fit std. dev. |\n|---|---|---|---|\n";
  for (size_t i = 0; i < to.free.size(); ++i) {
    const ParamId id = to.free[i];
    md << "| " << param_name(id) << " | " << number_text("%.4g", param_get(time_fit.params, id)) << " | "
       << number_text("%.4g", param_get(tab.fit.params, id)) << " | "
       << (tab.fit.uncertainty.valid ? number_text("%.3g", tab.fit.uncertainty.stddev[(Eigen::Index)i]) : "n/a")
       << " |\n";
  }
  md << "\n";
  for (int s = 0; s < 3; ++s) {
    const std::string png = std::string("friction_damper_sine_") + kSets[s].key + ".png";
    md << "## " << kSets[s].title << "\n\n"
       << "| record | f Hz | A in | periods | measured K kip/in | measured deg | time fit K | "
          "time fit deg | table fit K | table fit deg |\n|---|---|---|---|---|---|---|---|---|---|\n";
    std::vector<DynStiffRow> m, tf, tb;
    for (size_t k = 0; k < meas[s].size(); ++k) {
      const RecordDynStiff &r = meas[s][k];
      md << "| " << base_of(r.path) << " | " << number_text("%.3f", r.freq) << " | " << number_text("%.3f", r.amp)
         << " | " << r.periods << " | " << number_text("%.3f", r.measured.stiffness) << " | "
         << number_text("%.1f", r.measured.loss_angle_deg) << " | " << number_text("%.3f", time_pred[s][k].stiffness)
         << " | " << number_text("%.1f", time_pred[s][k].loss_angle_deg) << " | "
         << number_text("%.3f", tab_pred[s][k].stiffness)
         << " | " << number_text("%.1f", tab_pred[s][k].loss_angle_deg) << " |\n";
      m.push_back(row_of(r, r.measured));
      tf.push_back(row_of(r, time_pred[s][k]));
      tb.push_back(row_of(r, tab_pred[s][k]));
    }
    render_dynstiff_png(out_dir + "/" + png,
                        {DynStiffCurves{"measured", m, "points pt 7 ps 1.3"},
                         DynStiffCurves{"time fit", tf, "lines dt 2"},
                         DynStiffCurves{"table fit", tb, "lines"}},
                        "in", "kip", "Hz");
    md << "\n![" << kSets[s].title << "](" << png << ")\n\n";
  }
  md << "Reproduce: `make report` (or `build/rtb report --only friction_damper_sine`); one "
        "record: `build/rtb dynstiff --data ../shared/data/friction_damper/"
        "d2_sine_0.5Hz_1in_36lb.csv --params P.json`.\n";
  write_file_atomic(out_dir + "/friction_damper_sine.md", md.str());
  std::ostringstream tm;
  tm << "# Friction damper sine tests: wall times\n\n| step | s |\n|---|---|\n"
     << "| table identification (10 rows), with the measurement | " << number_text("%.1f", t_table) << " |\n"
     << "| time-record identifications (two starts) | " << number_text("%.1f", t_time) << " |\n"
     << "| whole page | "
     << number_text("%.1f", std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count())
     << " |\n";
  write_file_atomic(out_dir + "/friction_damper_sine_timings.md", tm.str());
}

}  // namespace rtb
