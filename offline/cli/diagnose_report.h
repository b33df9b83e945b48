// diagnose_report.h -- what `rtb diagnose` prints and writes: the verdict,
// the JSON report, the extended model's C header and the plot files.
#ifndef RTB_OFFLINE_CLI_DIAGNOSE_REPORT_H
#define RTB_OFFLINE_CLI_DIAGNOSE_REPORT_H

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "diagnose/diagnose.h"

namespace rtb {
namespace cli {

void print_diagnosis(const DiagnoseResult &R);
nlohmann::ordered_json diagnosis_json(const DiagnoseResult &R, const std::vector<Record> &fit,
                                      const std::vector<Record> &hold);
// Header of the extended model (artefacts are corrected data, not physics:
// they appear in comments only).
std::string diagnosis_header(const DiagnoseResult &R, const std::vector<Record> &fit,
                             const std::string &name);
// Per record: time, x, measured, baseline and extended force (CSV) and, when
// gnuplot is installed, PNG loops and residuals.
void write_diagnosis_plots(const DiagnoseResult &R, const std::vector<Record> &fit,
                           const std::vector<Record> &hold, const std::string &dir);

}  // namespace cli
}  // namespace rtb

#endif
