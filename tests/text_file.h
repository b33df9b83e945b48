// text_file.h -- a whole file read into a string, or written from one
// (binary mode: the bytes as they are); shared by the tests that check files.
#ifndef RTB_TESTS_TEXT_FILE_H
#define RTB_TESTS_TEXT_FILE_H

#include <fstream>
#include <sstream>
#include <string>

namespace rtb_test {

inline std::string read_text(const std::string &path) {
  std::ifstream f(path, std::ios::binary);
  std::stringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

inline void write_text(const std::string &path, const std::string &text) {
  std::ofstream f(path, std::ios::binary);
  f << text;
}

}  // namespace rtb_test

#endif
