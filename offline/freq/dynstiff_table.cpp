// dynstiff_table.cpp -- see dynstiff_table.h.
#include "freq/dynstiff_table.h"

#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <sstream>

#include "io/atomic_file.h"
#include "rtb_offline.h"

namespace rtb {

namespace {

std::string clean(std::string s) {
  while (!s.empty() && (s.back() == '\r' || s.back() == ' ' || s.back() == '\t')) s.pop_back();
  size_t b = 0;
  while (b < s.size() && (s[b] == ' ' || s[b] == '\t')) ++b;
  s = s.substr(b);
  if (s.size() >= 2 && s.front() == '"' && s.back() == '"') s = s.substr(1, s.size() - 2);
  for (char &c : s) c = (char)std::tolower((unsigned char)c);
  return s;
}

std::vector<std::string> split(const std::string &line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) out.push_back(clean(cell));
  if (!line.empty() && line.back() == ',') out.push_back("");
  return out;
}

// Column index of the first name matching, -1 if none.
int column(const std::vector<std::string> &hdr, std::initializer_list<const char *> names) {
  for (size_t i = 0; i < hdr.size(); ++i)
    for (const char *n : names)
      if (hdr[i] == n) return (int)i;
  return -1;
}

}  // namespace

DynStiffTable parse_dynstiff_table(const std::string &bytes, const std::string &path) {
  DynStiffTable t;
  t.path = path;
  t.sha256 = sha256_hex(bytes);
  std::stringstream in(bytes);
  std::string line;
  int lineno = 0, col[5] = {-1, -1, -1, -1, -1};
  size_t nfields = 0;
  bool have_header = false;
  auto fail = [&](const std::string &why) {
    throw InputError(path + ":" + std::to_string(lineno) + ": " + why);
  };
  while (std::getline(in, line)) {
    ++lineno;
    const std::string c = clean(line);
    if (c.empty() || c[0] == '#') continue;
    const std::vector<std::string> f = split(line);
    if (!have_header) {
      col[0] = column(f, {"frequency", "freq", "f", "frequency_hz", "frequency [hz]"});
      col[1] = column(f, {"amplitude", "amp", "a", "amplitude_mm", "amplitude [mm]"});
      col[2] = column(f, {"stiffness", "dynamic_stiffness", "k", "kdyn"});
      col[3] = column(f, {"loss_angle_deg", "loss_angle", "delta_deg", "phase_deg"});
      col[4] = column(f, {"weight", "w"});
      const char *need[4] = {"frequency", "amplitude", "stiffness", "loss_angle_deg"};
      for (int k = 0; k < 4; ++k)
        if (col[k] < 0) fail(std::string("missing column '") + need[k] + "' in the header");
      nfields = f.size();
      have_header = true;
      continue;
    }
    if (f.size() != nfields)
      fail("expected " + std::to_string(nfields) + " fields, got " + std::to_string(f.size()));
    double v[5] = {0, 0, 0, 0, 1.0};
    for (int k = 0; k < 5; ++k) {
      if (col[k] < 0) continue;
      const std::string &s = f[(size_t)col[k]];
      char *end = nullptr;
      v[k] = std::strtod(s.c_str(), &end);
      if (s.empty() || *end != '\0' || !std::isfinite(v[k]))
        fail("column " + std::to_string(col[k] + 1) + ": not a finite number: '" + s + "'");
    }
    if (!(v[0] > 0.0)) fail("frequency must be > 0");
    if (!(v[1] > 0.0)) fail("amplitude must be > 0");
    if (!(v[2] > 0.0)) fail("stiffness must be > 0");
    if (!(v[3] > -90.0 && v[3] < 90.0)) fail("loss angle must be in (-90, 90) deg");
    if (!(v[4] >= 0.0)) fail("weight must be >= 0");
    t.rows.push_back(DynStiffRow{v[0], v[1], v[2], v[3], v[4], lineno});
  }
  if (!have_header) throw InputError(path + ":" + std::to_string(lineno) + ": no header line");
  if (t.rows.empty()) throw InputError(path + ":" + std::to_string(lineno) + ": no data rows");
  bool any = false;
  for (const DynStiffRow &r : t.rows) any = any || r.weight > 0.0;
  if (!any) throw InputError(path + ":" + std::to_string(lineno) + ": every row has weight 0");
  return t;
}

DynStiffTable read_dynstiff_table(const std::string &path) {
  return parse_dynstiff_table(read_file_bytes(path), path);
}

std::string format_dynstiff_table(const std::vector<std::string> &comments,
                                  const std::vector<DynStiffRow> &rows,
                                  const std::vector<ExtraColumn> &extra) {
  std::string s;
  for (const std::string &c : comments) s += "# " + c + "\n";
  s += "frequency,amplitude,stiffness,loss_angle_deg";
  for (const ExtraColumn &e : extra) s += "," + e.name;
  s += "\n";
  char b[128];
  for (size_t i = 0; i < rows.size(); ++i) {
    const DynStiffRow &r = rows[i];
    std::snprintf(b, sizeof b, "%.10g,%.10g,%.10g,%.10g", r.freq, r.amp, r.stiffness,
                  r.loss_angle_deg);
    s += b;
    for (const ExtraColumn &e : extra) {
      std::snprintf(b, sizeof b, ",%.10g", e.values[i]);
      s += b;
    }
    s += "\n";
  }
  return s;
}

}  // namespace rtb
