// csv_reader.cpp -- measured records from CSV (see rtb_offline.h / io/csv.h).
//
// Format: optional '#' comment lines (one may be "# units: ..."), one header
// line naming the columns (time, displacement, force; any order, case and
// surrounding blanks ignored, extra columns ignored), then numeric rows with
// as many fields as the header. Fields are separated by ',' or, as the
// header shows, by ';' or tabs, where numbers may have a decimal comma. CRLF line ends and trailing blank lines are
// accepted. Every error names the file and line (and the column).
//
// Test rigs name their channels in many ways; a column is recognized by its
// name with a unit suffix removed ("force [N]", "time (s)", "disp_mm"):
//   time: time, t;  displacement: displacement, disp, x, u, stroke, position;
//   force: force, f, load.
#include <cctype>
#include <charconv>
#include <cmath>
#include <string>
#include <string_view>
#include <system_error>
#include <vector>

#include "io/atomic_file.h"
#include "io/csv.h"
#include "rtb_offline.h"

namespace rtb {
namespace {

std::string_view trim(std::string_view s) {
  size_t b = 0, e = s.size();
  while (b < e && (s[b] == ' ' || s[b] == '\t')) ++b;
  while (e > b && (s[e - 1] == ' ' || s[e - 1] == '\t')) --e;
  return s.substr(b, e - b);
}

// Trimmed, one pair of surrounding double quotes removed.
std::string_view clean_cell(std::string_view s) {
  s = trim(s);
  if (s.size() >= 2 && s.front() == '"' && s.back() == '"') s = trim(s.substr(1, s.size() - 2));
  return s;
}

std::string lower(std::string_view s) {
  std::string out(s);
  for (char &c : out) c = (char)std::tolower((unsigned char)c);
  return out;
}

bool istarts_with(std::string_view s, std::string_view prefix) {
  if (s.size() < prefix.size()) return false;
  for (size_t i = 0; i < prefix.size(); ++i)
    if (std::tolower((unsigned char)s[i]) != std::tolower((unsigned char)prefix[i])) return false;
  return true;
}

// The field separator, from the header line: the most frequent of ',', ';'
// and tab (a ';' or tab file may write decimal commas, as European rigs do).
char separator_of(std::string_view header) {
  size_t n[3] = {0, 0, 0};
  const char seps[3] = {',', ';', '\t'};
  for (char c : header)
    for (int k = 0; k < 3; ++k) n[k] += c == seps[k];
  int best = 0;
  for (int k = 1; k < 3; ++k)
    if (n[k] > n[best]) best = k;
  return seps[best];
}

void split(std::string_view line, char sep, std::vector<std::string_view> &out) {
  out.clear();
  size_t start = 0;
  for (;;) {
    const size_t comma = line.find(sep, start);
    if (comma == std::string_view::npos) {
      out.push_back(line.substr(start));
      return;
    }
    out.push_back(line.substr(start, comma - start));
    start = comma + 1;
  }
}

// Which of time (0), displacement (1), force (2) a header cell names, or -1.
int column_role(std::string name) {
  // A unit in brackets or parentheses: "force [kN]", "time (s)".
  const size_t br = name.find_first_of("[(");
  if (br != std::string::npos) name = name.substr(0, br);
  name = std::string(trim(name));
  static const std::vector<std::string> kAliases[3] = {
      {"time", "t"},
      {"displacement", "disp", "x", "u", "stroke", "position"},
      {"force", "f", "load"}};
  auto match = [&](const std::string &n) {
    for (int k = 0; k < 3; ++k)
      for (const std::string &a : kAliases[k])
        if (n == a) return k;
    return -1;
  };
  const int whole = match(name);
  if (whole >= 0) return whole;
  // A unit after an underscore or a blank: "time_s", "force_kN", "disp mm".
  const size_t sep = name.find_first_of("_ ");
  return sep == std::string::npos ? -1 : match(name.substr(0, sep));
}

enum class NumStatus { ok, not_a_number, out_of_range };

NumStatus parse_double(std::string_view s, double &v, char sep = ',') {
  s = clean_cell(s);
  std::string dotted;
  if (sep != ',' && s.find(',') != std::string_view::npos && s.find('.') == std::string_view::npos) {
    dotted.assign(s);  // a decimal comma: "0,125"
    dotted[dotted.find(',')] = '.';
    s = dotted;
  }
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);
  if (s.empty()) return NumStatus::not_a_number;
  const char *b = s.data(), *e = s.data() + s.size();
  const auto r = std::from_chars(b, e, v, std::chars_format::general);
  if (r.ptr != e) return NumStatus::not_a_number;
  if (r.ec == std::errc::result_out_of_range) return NumStatus::out_of_range;
  if (r.ec != std::errc()) return NumStatus::not_a_number;
  return NumStatus::ok;
}

struct Ctx {
  const std::string &path;
  [[noreturn]] void fail(size_t line, const std::string &what) const {
    throw InputError(path + ":" + std::to_string(line) + ": " + what);
  }
};

std::string in_quotes(std::string_view s) { return "\"" + std::string(s) + "\""; }

}  // namespace

Record parse_record_csv(const std::string &bytes, const std::string &path,
                        const CsvReadOptions &opt) {
  const Ctx ctx{path};
  Record rec;
  rec.path = path;
  rec.sha256 = sha256_hex(bytes);

  std::string_view text(bytes);
  if (text.size() >= 3 && (unsigned char)text[0] == 0xEF && (unsigned char)text[1] == 0xBB &&
      (unsigned char)text[2] == 0xBF)
    text.remove_prefix(3);  // UTF-8 byte order mark

  static const char *const kNames[3] = {"time", "displacement", "force"};
  int col[3] = {-1, -1, -1};
  size_t n_fields = 0;
  char sep = ',';
  size_t header_line = 0;
  size_t first_blank_after_header = 0;
  size_t line_no = 0;
  size_t prev_time_line = 0;
  std::string prev_time_text;
  std::vector<std::string_view> fields;
  std::vector<std::string> header_names;

  size_t pos = 0;
  while (pos < text.size()) {
    size_t nl = text.find('\n', pos);
    if (nl == std::string_view::npos) nl = text.size();
    std::string_view line = text.substr(pos, nl - pos);
    pos = nl + 1;
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    const std::string_view t = trim(line);

    if (t.empty()) {
      if (header_line != 0 && first_blank_after_header == 0) first_blank_after_header = line_no;
      continue;
    }
    if (t.front() == '#') {
      std::string_view c = trim(t.substr(1));
      if (istarts_with(c, "units:") && rec.units.empty()) rec.units = std::string(trim(c.substr(6)));
      continue;
    }

    if (header_line == 0) {  // ---- header
      header_line = line_no;
      sep = separator_of(t);
      split(t, sep, fields);
      n_fields = fields.size();
      bool all_numeric = true;
      for (size_t i = 0; i < fields.size(); ++i) {
        const std::string name = lower(clean_cell(fields[i]));
        double dummy;
        if (parse_double(fields[i], dummy, sep) != NumStatus::ok) all_numeric = false;
        const int k = column_role(name);
        if (k >= 0) {
          if (col[k] >= 0)
            ctx.fail(line_no, std::string("column '") + kNames[k] + "' appears twice in the header (" +
                                  in_quotes(header_names[(size_t)col[k]]) + " and " +
                                  in_quotes(clean_cell(fields[i])) + ")");
          col[k] = (int)i;
        }
        header_names.push_back(std::string(clean_cell(fields[i])));
      }
      if (all_numeric)
        ctx.fail(line_no,
                 "no header line: expected column names (time,displacement,force) before the "
                 "data, found \"" + std::string(t) + "\"");
      for (int k = 0; k < 3; ++k) {
        if (col[k] >= 0 || (k == 2 && !opt.require_force)) continue;
        std::string have;
        for (const auto &h : header_names) have += (have.empty() ? "" : ", ") + in_quotes(h);
        ctx.fail(line_no, std::string("missing column '") + kNames[k] + "' in header (columns: " +
                              have + ")");
      }
      continue;
    }

    // ---- data row
    if (first_blank_after_header != 0)
      ctx.fail(first_blank_after_header, "blank line inside the data (only trailing blank lines "
                                         "are allowed)");
    split(t, sep, fields);
    if (fields.size() != n_fields)
      ctx.fail(line_no, std::to_string(fields.size()) + " field" +
                            (fields.size() == 1 ? "" : "s") + ", but the header has " +
                            std::to_string(n_fields));
    double v[3] = {0.0, 0.0, 0.0};
    for (int k = 0; k < 3; ++k) {
      if (col[k] < 0) continue;
      const std::string_view cell = fields[(size_t)col[k]];
      const NumStatus s = parse_double(cell, v[k], sep);
      if (s == NumStatus::not_a_number)
        ctx.fail(line_no, std::string("column '") + kNames[k] + "': non-numeric value " +
                              in_quotes(clean_cell(cell)));
      if (s == NumStatus::out_of_range || !std::isfinite(v[k]))
        ctx.fail(line_no, std::string("column '") + kNames[k] + "': non-finite value " +
                              in_quotes(clean_cell(cell)));
    }
    if (!rec.t.empty() && !(v[0] > rec.t.back()))
      ctx.fail(line_no, "time is not increasing: " + std::string(clean_cell(fields[(size_t)col[0]])) +
                            " follows " + prev_time_text + " (line " +
                            std::to_string(prev_time_line) + ")");
    prev_time_text = std::string(clean_cell(fields[(size_t)col[0]]));
    prev_time_line = line_no;
    rec.t.push_back(v[0]);
    rec.x.push_back(v[1]);
    if (col[2] >= 0) rec.F.push_back(v[2]);
  }

  if (header_line == 0)
    ctx.fail(line_no > 0 ? line_no : 1,
             "no header line (expected column names time,displacement,force)");
  if (rec.t.size() < (size_t)kMinSamples)
    ctx.fail(line_no, "only " + std::to_string(rec.t.size()) + " data row" +
                          (rec.t.size() == 1 ? "" : "s") + " after the header (line " +
                          std::to_string(header_line) + "), at least " +
                          std::to_string(kMinSamples) + " are needed");
  return rec;
}

Record read_record_csv(const std::string &path, const CsvReadOptions &opt) {
  return parse_record_csv(read_file_bytes(path), path, opt);
}

Record read_record_csv(const std::string &path) { return read_record_csv(path, CsvReadOptions()); }

}  // namespace rtb
