// csv.h -- record CSV reading/writing beyond the declarations in
// rtb_offline.h (read_record_csv(path) and write_record_csv(...)).
#ifndef RTB_OFFLINE_IO_CSV_H
#define RTB_OFFLINE_IO_CSV_H

#include <string>
#include <vector>

#include "rtb_offline.h"

namespace rtb {

struct CsvReadOptions {
  // false: a record without a `force` column is accepted (Record::F is then
  // left empty); used by `rtb simulate`, whose input is a displacement history.
  bool require_force = true;
};

// As read_record_csv(path), with options.
Record read_record_csv(const std::string &path, const CsvReadOptions &opt);

// Parses CSV text already in memory; `path` is used in messages and stored in
// Record::path; Record::sha256 is the hash of `bytes`.
Record parse_record_csv(const std::string &bytes, const std::string &path,
                        const CsvReadOptions &opt = CsvReadOptions());

// Generic column writer: '#'-prefixed comment lines (each given without the
// '#'), then the header line and the rows, numbers with %.17g. All columns
// must have the same length. Written atomically (write_file_atomic).
struct CsvColumn {
  std::string name;
  const std::vector<double> *values;
};
std::string format_csv(const std::vector<std::string> &comments,
                       const std::vector<CsvColumn> &columns);
void write_csv_atomic(const std::string &path, const std::vector<std::string> &comments,
                      const std::vector<CsvColumn> &columns);

// The comment line carrying the units ("units: time=s ..."), "" if units empty.
std::string units_comment(const std::string &units);

}  // namespace rtb

#endif
