// gnuplot_figure.h -- line plots as PNG files through gnuplot, reproducibly.
//
// render_png() writes, next to the PNG, the plotted data (NAME.dat) and the
// gnuplot script (NAME.gp) that draws it, then runs gnuplot on them. The
// script is self-contained relative to its directory, so `cd DIR && gnuplot
// NAME.gp` redraws DIR/NAME.png after hand edits. The PNG is produced
// atomically: gnuplot renders to a temporary file in the same directory,
// which is renamed over NAME.png only after gnuplot succeeded; on any failure
// the temporary file is removed (an older NAME.png is left untouched) and
// std::runtime_error says why (gnuplot missing, gnuplot's own error message).
//
// Reproducible: the same data give byte-identical .dat, .gp and .png files
// (no timestamps, no temporary names inside the files; pngcairo writes no
// tIME chunk).
//
// Data are written with %.6g (6 significant digits: finer than a pixel on
// any axis whose range is more than 1e-4 of its values). Non-finite values
// are written as NaN, which gnuplot skips. A series longer than
// kMaxPlotPoints is decimated by a uniform stride (first and last point
// kept) to keep the .dat small; features narrower than the stride may then
// disappear, so decimate smartly yourself (e.g. keep loop tips) if it matters.
#ifndef RTB_OFFLINE_REPORT_GNUPLOT_FIGURE_H
#define RTB_OFFLINE_REPORT_GNUPLOT_FIGURE_H

#include <cstddef>
#include <string>
#include <vector>

namespace rtb {

constexpr std::size_t kMaxPlotPoints = 20000;  // per series, see above

struct Series {
  std::string label;             // legend entry (plain text; "" = no entry)
  std::vector<double> x, y;      // same length, >= 1 point
  std::string style = "lines";   // gnuplot "with" clause, e.g. "lines dt 2 lc 'black'",
                                 // "points pt 7 ps 0.5", "linespoints"
};

struct Figure {  // one panel
  std::string title, xlabel, ylabel;  // plain text, put units in the labels
  bool logx = false, logy = false;
  std::string xrange, yrange;         // gnuplot ranges like "[0:1.1]"; "" = automatic
  std::string key = "top left";       // gnuplot `set key` arguments; "off" hides the legend
  std::vector<Series> series;
};

// Renders the panels side by side (one row) into png_path, 900x600 pixels
// for one panel and 750x600 per panel otherwise (width_px/height_px override
// when > 0). png_path must end in ".png"; its directory must exist. Throws
// std::invalid_argument on bad input (no panel, empty series, size mismatch)
// and std::runtime_error when gnuplot is missing or fails.
void render_png(const std::string &png_path, const std::vector<Figure> &panels,
                int width_px = 0, int height_px = 0);

// True when an executable `gnuplot` is on PATH.
bool gnuplot_available();

}  // namespace rtb

#endif
