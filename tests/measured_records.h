// measured_records.h -- every record of ../shared/data (or $RTB_DATA_DIR),
// for the stage-0 detectors' tests that must leave real records alone.
// Returns false (the caller skips) when the data are absent.
#ifndef RTB_TESTS_MEASURED_RECORDS_H
#define RTB_TESTS_MEASURED_RECORDS_H

#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "offline/io/csv.h"

namespace rtb_test {

inline bool measured_records(std::vector<rtb::Record> *recs, std::string *dir) {
  const char *env = std::getenv("RTB_DATA_DIR");
  *dir = env && *env ? env : RTB_SHARED_DATA_DIR;
  if (!std::filesystem::exists(*dir)) return false;
  for (const char *sub : {"friction_damper", "vhb4910"}) {
    if (!std::filesystem::exists(*dir + "/" + sub)) continue;
    for (const auto &e : std::filesystem::directory_iterator(*dir + "/" + sub))
      if (e.path().extension() == ".csv") recs->push_back(rtb::read_record_csv(e.path().string()));
  }
  return true;
}

}  // namespace rtb_test

#endif
