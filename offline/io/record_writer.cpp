// record_writer.cpp -- CSV output of records (time, displacement, force and
// optional extra columns), %.17g so every value reads back bit for bit.
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/csv.h"
#include "rtb_offline.h"

namespace rtb {

std::string units_comment(const std::string &units) {
  if (units.empty()) return "";
  return "units: " + units;
}

std::string format_csv(const std::vector<std::string> &comments,
                       const std::vector<CsvColumn> &columns) {
  if (columns.empty()) throw std::invalid_argument("format_csv: no columns");
  const size_t n = columns[0].values->size();
  for (const CsvColumn &c : columns)
    if (c.values->size() != n)
      throw std::invalid_argument("format_csv: column '" + c.name + "' has " +
                                  std::to_string(c.values->size()) + " values, expected " +
                                  std::to_string(n));
  std::string out;
  out.reserve(64 + n * columns.size() * 24);
  for (const std::string &c : comments) {
    // One '#' line per line of the comment text.
    size_t start = 0;
    for (;;) {
      const size_t nl = c.find('\n', start);
      out += "# ";
      out.append(c, start, nl == std::string::npos ? std::string::npos : nl - start);
      out += '\n';
      if (nl == std::string::npos) break;
      start = nl + 1;
    }
  }
  for (size_t k = 0; k < columns.size(); ++k) {
    if (k) out += ',';
    out += columns[k].name;
  }
  out += '\n';
  char buf[40];
  for (size_t i = 0; i < n; ++i) {
    for (size_t k = 0; k < columns.size(); ++k) {
      if (k) out += ',';
      const int len = std::snprintf(buf, sizeof buf, "%.17g", (*columns[k].values)[i]);
      out.append(buf, (size_t)len);
    }
    out += '\n';
  }
  return out;
}

void write_csv_atomic(const std::string &path, const std::vector<std::string> &comments,
                      const std::vector<CsvColumn> &columns) {
  write_file_atomic(path, format_csv(comments, columns));
}

void write_record_csv(const std::string &path, const std::vector<double> &t,
                      const std::vector<double> &x, const std::vector<double> &F,
                      const std::string &units) {
  std::vector<std::string> comments;
  if (!units.empty()) comments.push_back(units_comment(units));
  write_csv_atomic(path, comments, {{"time", &t}, {"displacement", &x}, {"force", &F}});
}

}  // namespace rtb
