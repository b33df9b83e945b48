// dynstiff_figure.h -- the dynamic-stiffness chart of a data sheet: |K*| and
// the loss angle against frequency (log axis), one curve per amplitude, as a
// gnuplot PNG (gnuplot_figure.h: reproducible, atomic).
#ifndef RTB_OFFLINE_REPORT_DYNSTIFF_FIGURE_H
#define RTB_OFFLINE_REPORT_DYNSTIFF_FIGURE_H

#include <string>
#include <vector>

#include "freq/dynstiff_table.h"

namespace rtb {

struct DynStiffCurves {
  std::string label;               // prefix of the legend entries, e.g. "model"
  std::vector<DynStiffRow> rows;   // grouped by amplitude (within 3%), sorted by frequency
  std::string style = "linespoints pt 7 ps 0.8";
};

// Units are for the axis labels ("" = none given).
void render_dynstiff_png(const std::string &png_path, const std::vector<DynStiffCurves> &sets,
                         const std::string &length_unit, const std::string &force_unit,
                         const std::string &freq_unit);

}  // namespace rtb

#endif
