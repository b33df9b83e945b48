// study.h -- one real-data study of `rtb report`: identify and diagnose on a
// set of fit records, validate on held-out records, then tabulate and plot
// what the baseline and the extended model get right and wrong.
#ifndef RTB_OFFLINE_REPORT_STUDY_H
#define RTB_OFFLINE_REPORT_STUDY_H

#include <string>
#include <vector>

#include "diagnose/diagnose.h"
#include "preprocess/preprocess.h"

namespace rtb {

struct StudySpec {
  std::string name;                     // file stem in the output directory
  std::string title;                    // page heading
  std::string intro;                    // markdown: the device, the choice of records, why
  std::string length_unit, force_unit;  // as in the data files
  std::vector<std::string> fit_files, validation_files;  // relative to the data dir
  Preprocess pre;
  DiagnoseOptions diag;
  bool log_time_validation = false;     // relaxation records: log time axis
  std::vector<std::string> second_stage;  // candidates tried on top of the chosen cause
  double validation_bound = 0.0;        // documented bound on the extended validation error
};

struct FileFigures {
  std::string path;
  bool validation = false;
  double err_base = 0, err_ext = 0;      // sqrt(J/J0), eq. (27)
  double nrmse_base = 0, nrmse_ext = 0;  // % of the measured force range
};

struct SecondStage {
  std::string name;
  double error_fit = 0, error_validation = 0;
  std::string effect;
};

struct StudyResult {
  std::vector<Record> fit, validation;  // as fitted: after preprocessing
  DiagnoseResult diag;
  std::vector<FileFigures> files;
  double err_fit_base = 0, err_fit_ext = 0, err_val_base = 0, err_val_ext = 0;
  std::vector<SecondStage> second;
  double wall_seconds = 0;
};

// Runs the study on the files under data_dir. Throws InputError on bad data.
StudyResult run_study(const StudySpec &spec, const std::string &data_dir, bool quiet);

// Writes out_dir/NAME.md and its PNG figures; wall times go to
// out_dir/NAME_timings.md (they differ from run to run; everything else is
// reproduced byte for byte).
void write_study_report(const StudySpec &spec, const StudyResult &r, const std::string &out_dir);

// The two studies of issue #5 (friction damper, VHB 4910).
StudySpec friction_damper_study();
StudySpec vhb4910_study();

}  // namespace rtb

#endif
