// dynstiff_table.h -- dynamic-stiffness tables (a supplier data sheet, or the
// output of `rtb dynstiff`): CSV with '#' comment lines, a header naming
// frequency, amplitude, stiffness, loss_angle_deg (any order; an optional
// `weight` column; other columns ignored), one row per (frequency, amplitude).
// Units are the user's (e.g. Hz, mm, N/mm, deg), consistent with the
// parameters.
#ifndef RTB_OFFLINE_FREQ_DYNSTIFF_TABLE_H
#define RTB_OFFLINE_FREQ_DYNSTIFF_TABLE_H

#include <string>
#include <vector>

namespace rtb {

struct DynStiffRow {
  double freq = 0, amp = 0;        // [1/time], [length] (amplitude, not peak-to-peak)
  double stiffness = 0;            // |K*| [force/length]
  double loss_angle_deg = 0;       // arg K* [deg]
  double weight = 1.0;             // >= 0, multiplies both residuals of the row
  int line = 0;                    // line in the file (messages)
};

struct DynStiffTable {
  std::string path, sha256;
  std::vector<DynStiffRow> rows;
};

// Throws InputError "PATH:LINE: ..." on a missing file or column, a
// non-numeric or non-finite cell, a wrong field count, frequency, amplitude
// or stiffness <= 0, a loss angle outside (-90, 90) deg, a negative weight,
// no rows, or no row of positive weight.
DynStiffTable read_dynstiff_table(const std::string &path);
DynStiffTable parse_dynstiff_table(const std::string &bytes, const std::string &path);

// The CSV text: comments (without '#'), then frequency,amplitude,stiffness,
// loss_angle_deg and the extra columns (same length as rows), %.10g.
struct ExtraColumn {
  std::string name;
  std::vector<double> values;
};
std::string format_dynstiff_table(const std::vector<std::string> &comments,
                                  const std::vector<DynStiffRow> &rows,
                                  const std::vector<ExtraColumn> &extra = {});

}  // namespace rtb

#endif
