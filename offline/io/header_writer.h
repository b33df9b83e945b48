// header_writer.h -- C parameter header for the real-time library: a
// `static const rtb_params NAME = {...};` that compiles as C99 and C++,
// exact to the bit (hex float literals), with its provenance in comments and
// no timestamp (same inputs -> byte-identical header). The caller writes the
// text with write_file_atomic.
#ifndef RTB_OFFLINE_IO_HEADER_WRITER_H
#define RTB_OFFLINE_IO_HEADER_WRITER_H

#include <cstddef>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "rtb_offline.h"

namespace rtb {

struct HeaderDataFile {
  std::string path;             // as given by the user
  std::string sha256;           // hex digest of the file bytes
  std::size_t samples = 0;      // 0 = not shown
  double error = std::numeric_limits<double>::quiet_NaN();  // per-file figure, NaN = not shown
};

struct HeaderInfo {
  std::string name;             // C identifier of the constant (validated)
  std::string tool_version;     // e.g. "rtb 0.1.0"
  std::vector<HeaderDataFile> data_files;
  double error = std::numeric_limits<double>::quiet_NaN();  // NaN = not shown
  std::string error_label = "relative error sqrt(J/J0), eq. (27)";
  std::map<std::string, double> std_devs;   // parameter name (e.g. "K0") -> std. deviation
  std::vector<std::string> provenance;      // free-form lines
};

// True if `name` can name the constant: [A-Za-z_][A-Za-z0-9_]*, not a C or
// C++ keyword, not a reserved identifier (leading "__" or "_" + capital) and
// not an identifier of rt_bushing.h (rtb_params, rtb_step, RTB_OK, ...).
// On false, *why says why.
bool is_valid_header_name(const std::string &name, std::string *why = nullptr);

// The header text. Throws InputError for an invalid name or parameters that
// rtb_params_validate rejects.
std::string emit_parameter_header(const rtb_params &p, const HeaderInfo &info);

// ---- six axes (bushing6_header.cpp)
struct Bushing6HeaderInfo {
  std::string name;                       // C identifier of the constant (validated)
  std::string tool_version;
  std::string sources[RTB_AXES];          // per axis, e.g. "fx.json (sha256 ...)"; "" = off
  std::vector<std::string> provenance;    // free-form lines
};

// `static const rtb_bushing6_params NAME = {...};`, C99 and C++, exact to the
// bit, no timestamp. An axis that is off carries the section 3.4 defaults
// (ignored by the library; a host that switches it on gets a sane bushing).
// Throws InputError for an invalid name or an active axis that does not validate.
std::string emit_bushing6_header(const rtb_bushing6_params &p, const Bushing6HeaderInfo &info);

// ---- building blocks shared by both headers (header_writer.cpp)
// Text safe inside a /* */ comment: no comment delimiters, no trigraphs, no
// control characters.
std::string comment_safe(const std::string &s);
// The typedef-array compile-time checks of ABI, scalar, reserved slots and capacity.
std::string layout_checks(const std::string &name, int max_cells_used);
// "{ ... }" of one rtb_params, every line after the first prefixed by indent.
std::string params_initializer(const rtb_params &p, const std::map<std::string, double> &std_devs,
                               const std::string &indent);

}  // namespace rtb

#endif
