// number_text.h -- one number printed with a printf format, as a string:
// the report pages and the generated C header write their numbers this way.
#ifndef RTB_OFFLINE_IO_NUMBER_TEXT_H
#define RTB_OFFLINE_IO_NUMBER_TEXT_H

#include <cstdio>
#include <string>

namespace rtb {

// printf_format takes exactly one double (e.g. "%.4g", "%a"); 64 characters
// hold any double in any of the formats used.
inline std::string number_text(const char *printf_format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, printf_format, v);
  return buf;
}

}  // namespace rtb

#endif
