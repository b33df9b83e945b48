// io_test.cpp -- offline I/O: record CSV reader/writer (every error case
// names file and line), SHA-256 (FIPS 180-2 vectors), atomic writes, and the
// parameter JSON reader/writer.
#ifdef RTB_HAVE_OFFLINE
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "temp_dir.h"
#include "offline/io/atomic_file.h"
#include "offline/io/csv.h"
#include "offline/io/params_json.h"
#include "offline/io/sha256.h"
#include "offline/rtb_offline.h"
#include "text_file.h"

namespace fs = std::filesystem;

namespace {

using rtb_test::read_text;
using rtb_test::write_text;

class IoTempDir : public rtb_test::TempDir {
 public:
  IoTempDir() : rtb_test::TempDir("rtb_io_test") {}
};

// Rows "t,x,F" for i = 0..n-1.
std::string rows(int n, int first = 0) {
  std::string s;
  for (int i = first; i < first + n; ++i)
    s += std::to_string(0.01 * i) + "," + std::to_string(0.1 * i) + "," + std::to_string(-2.0 * i) +
         "\n";
  return s;
}

// Expects read_record_csv to throw InputError whose message contains every
// needle; returns the message.
std::string expect_input_error(const std::string &path, const std::vector<std::string> &needles,
                               bool require_force = true) {
  rtb::CsvReadOptions opt;
  opt.require_force = require_force;
  try {
    rtb::read_record_csv(path, opt);
  } catch (const rtb::InputError &e) {
    const std::string msg = e.what();
    for (const std::string &n : needles)
      EXPECT_NE(msg.find(n), std::string::npos) << "message \"" << msg << "\" lacks \"" << n << "\"";
    return msg;
  }
  ADD_FAILURE() << "no InputError for " << path;
  return "";
}

const std::string kHeader = "time,displacement,force\n";

}  // namespace

// ------------------------------------------------------------------ CSV errors

TEST(IoCsv, MissingFileNamesPath) {
  IoTempDir d;
  expect_input_error(d.file("nope.csv"), {d.file("nope.csv"), "cannot open"});
}

TEST(IoCsv, DirectoryIsNotARecord) {
  IoTempDir d;
  EXPECT_THROW(rtb::read_record_csv(d.path()), rtb::InputError);
}

TEST(IoCsv, EmptyFileAndCommentsOnlyHaveNoHeader) {
  IoTempDir d;
  write_text(d.file("empty.csv"), "");
  expect_input_error(d.file("empty.csv"), {d.file("empty.csv") + ":1:", "no header"});
  write_text(d.file("comments.csv"), "# a\n# units: time=s\n\n");
  expect_input_error(d.file("comments.csv"), {d.file("comments.csv") + ":3:", "no header"});
}

TEST(IoCsv, DataWithoutHeaderLine) {
  IoTempDir d;
  write_text(d.file("a.csv"), "# c\n" + rows(10));
  expect_input_error(d.file("a.csv"), {d.file("a.csv") + ":2:", "no header"});
}

TEST(IoCsv, MissingColumnIsNamed) {
  IoTempDir d;
  const char *cases[][2] = {{"displacement,force\n", "'time'"},
                            {"time,force\n", "'displacement'"},
                            {"time,displacement\n", "'force'"},
                            {"time,displacment,force\n", "'displacement'"}};
  for (auto &c : cases) {
    const std::string p = d.file("m.csv");
    std::string body;
    for (int i = 0; i < 10; ++i) body += i ? "\n1,2" : "1,2";
    write_text(p, std::string("# comment\n") + c[0] + body + "\n");
    expect_input_error(p, {p + ":2:", "missing column", c[1]});
  }
}

TEST(IoCsv, ColumnNamesWithUnitsAndCommonAliases) {
  IoTempDir d;
  const char *headers[] = {"t,x,F", "Time [s],Disp (mm),Force [N]", "time_s,displacement_mm,force_kN",
                           "load,stroke,time", "sample,T,u,f,temperature"};
  for (const char *h : headers) {
    const std::string p = d.file("h.csv");
    const bool five = std::string(h).rfind("sample", 0) == 0;
    const bool load_first = std::string(h).rfind("load", 0) == 0;
    std::string body;
    for (int i = 0; i < 10; ++i) {
      const double t = 0.01 * i, x = 0.1 * i, F = 100.0 * i;
      char row[160];
      if (five) std::snprintf(row, sizeof row, "%d,%g,%g,%g,20\n", i, t, x, F);
      else if (load_first) std::snprintf(row, sizeof row, "%g,%g,%g\n", F, x, t);
      else std::snprintf(row, sizeof row, "%g,%g,%g\n", t, x, F);
      body += row;
    }
    write_text(p, std::string(h) + "\n" + body);
    const rtb::Record r = rtb::read_record_csv(p);
    ASSERT_EQ(r.t.size(), 10u) << h;
    EXPECT_DOUBLE_EQ(r.t[3], 0.03) << h;
    EXPECT_DOUBLE_EQ(r.x[3], 0.3) << h;
    EXPECT_DOUBLE_EQ(r.F[3], 300.0) << h;
  }
  // Two columns for one role are an error naming both.
  write_text(d.file("a.csv"), "time,x,displacement,force\n" + rows(10));
  expect_input_error(d.file("a.csv"), {"'displacement'", "twice", "\"x\"", "\"displacement\""});
}

TEST(IoCsv, DuplicateColumnRejected) {
  IoTempDir d;
  write_text(d.file("a.csv"), "time,displacement,force,Time\n" + rows(10));
  expect_input_error(d.file("a.csv"), {d.file("a.csv") + ":1:", "'time'", "twice"});
}

TEST(IoCsv, NonNumericCellQuotedWithColumn) {
  IoTempDir d;
  const std::string p = d.file("a.csv");
  write_text(p, kHeader + rows(3) + "0.03,abc,1\n" + rows(10, 4));
  expect_input_error(p, {p + ":5:", "'displacement'", "\"abc\"", "non-numeric"});
  write_text(p, kHeader + rows(5) + "0.05,1,\n" + rows(10, 6));
  expect_input_error(p, {p + ":7:", "'force'", "\"\"", "non-numeric"});
  write_text(p, kHeader + rows(5) + "0.05x,1,2\n" + rows(10, 6));
  expect_input_error(p, {p + ":7:", "'time'", "\"0.05x\""});
}

TEST(IoCsv, NonFiniteCellsRejected) {
  IoTempDir d;
  const std::string p = d.file("a.csv");
  for (const char *bad : {"nan", "NaN", "inf", "-Infinity", "1e999"}) {
    write_text(p, kHeader + rows(3) + "0.03,0.3," + bad + "\n" + rows(10, 4));
    expect_input_error(p, {p + ":5:", "'force'", "non-finite", std::string("\"") + bad + "\""});
  }
}

TEST(IoCsv, RowWithWrongFieldCount) {
  IoTempDir d;
  const std::string p = d.file("a.csv");
  write_text(p, kHeader + rows(4) + "0.04,0.4\n" + rows(10, 5));
  expect_input_error(p, {p + ":6:", "2 fields", "header has 3"});
  write_text(p, kHeader + rows(4) + "0.04,0.4,1,7\n" + rows(10, 5));
  expect_input_error(p, {p + ":6:", "4 fields"});
}

TEST(IoCsv, NonIncreasingTimeGivesBothTimes) {
  IoTempDir d;
  const std::string p = d.file("a.csv");
  write_text(p, kHeader + "0,0,0\n0.5,1,1\n0.5,2,2\n" + rows(10, 10));
  expect_input_error(p, {p + ":4:", "not increasing", "0.5 follows 0.5", "line 3"});
  write_text(p, kHeader + "0,0,0\n0.5,1,1\n0.25,2,2\n" + rows(10, 10));
  expect_input_error(p, {p + ":4:", "0.25 follows 0.5"});
}

TEST(IoCsv, TooFewRows) {
  IoTempDir d;
  const std::string p = d.file("a.csv");
  write_text(p, kHeader + rows(rtb::kMinSamples - 1));
  expect_input_error(p, {p + ":", "only 7 data rows", "at least 8"});
  write_text(p, kHeader + rows(rtb::kMinSamples));
  EXPECT_EQ(rtb::read_record_csv(p).t.size(), (size_t)rtb::kMinSamples);
}

TEST(IoCsv, BlankLineInsideDataRejected) {
  IoTempDir d;
  const std::string p = d.file("a.csv");
  write_text(p, kHeader + rows(4) + "\n" + rows(6, 4));
  expect_input_error(p, {p + ":6:", "blank line"});
}

// ------------------------------------------------------------------ CSV good files

TEST(IoCsv, ReadsCommentsUnitsAndValuesExactly) {
  IoTempDir d;
  const std::string p = d.file("a.csv");
  const std::string text =
      "# source: x\n# units: time=s displacement=in force=kip\n" + kHeader +
      "0,0.0009431094,-0.00961056\n0.0009765625,1e-3,+2.5E2\n" + rows(8, 1);
  write_text(p, text);
  const rtb::Record r = rtb::read_record_csv(p);
  EXPECT_EQ(r.path, p);
  EXPECT_EQ(r.units, "time=s displacement=in force=kip");
  ASSERT_EQ(r.t.size(), 10u);
  EXPECT_EQ(r.x[0], 0.0009431094);
  EXPECT_EQ(r.F[0], -0.00961056);
  EXPECT_EQ(r.t[1], 0.0009765625);
  EXPECT_EQ(r.x[1], 1e-3);
  EXPECT_EQ(r.F[1], 250.0);
  EXPECT_EQ(r.sha256, rtb::sha256_hex(text));
  EXPECT_EQ(r.sha256, rtb::sha256_file(p));
}

TEST(IoCsv, ReorderedExtraColumnsCaseAndBlanks) {
  IoTempDir d;
  const std::string p = d.file("a.csv");
  std::string text = " Force , velocity,TIME,\"Displacement\" ,note\n";
  for (int i = 0; i < 9; ++i)
    text += std::to_string(10 * i) + ",junk," + std::to_string(i) + ", " + std::to_string(2 * i) +
            " ,x\n";
  write_text(p, text);
  const rtb::Record r = rtb::read_record_csv(p);
  ASSERT_EQ(r.t.size(), 9u);
  for (int i = 0; i < 9; ++i) {
    EXPECT_EQ(r.t[i], i);
    EXPECT_EQ(r.x[i], 2 * i);
    EXPECT_EQ(r.F[i], 10 * i);
  }
}

TEST(IoCsv, CrlfBomAndTrailingBlankLines) {
  IoTempDir d;
  const std::string p = d.file("a.csv");
  std::string text = "\xEF\xBB\xBF# units: time=s displacement=mm force=N\r\n" +
                     std::string("time,displacement,force\r\n");
  for (int i = 0; i < 9; ++i) text += std::to_string(i) + ",1.5,2.5\r\n";
  text += "\r\n\r\n  \n";
  write_text(p, text);
  const rtb::Record r = rtb::read_record_csv(p);
  EXPECT_EQ(r.units, "time=s displacement=mm force=N");
  ASSERT_EQ(r.t.size(), 9u);
  EXPECT_EQ(r.t[8], 8.0);
  EXPECT_EQ(r.F[8], 2.5);
}

// European rigs: ';' between fields and a decimal comma; tab-separated
// exports; a malformed row is still named by file and line.
TEST(IoCsv, SemicolonsDecimalCommasAndTabs) {
  IoTempDir d;
  const std::string p = d.file("a.csv");
  std::string text = "Zeit;Weg;Kraft;time [s];stroke [mm];force [N]\n";
  for (int i = 0; i < 9; ++i)
    text += "x;y;z;" + std::to_string(i) + ",5;-1,25;" + std::to_string(3 * i) + "\n";
  write_text(p, text);
  rtb::Record r = rtb::read_record_csv(p);
  ASSERT_EQ(r.t.size(), 9u);
  EXPECT_EQ(r.t[2], 2.5);
  EXPECT_EQ(r.x[2], -1.25);
  EXPECT_EQ(r.F[2], 6.0);
  write_text(p, "t\tx\tF\n0\t0.5\t1e3\n" + std::string("1\t0.25\t2\n2\t0\t3\n3\t1\t4\n") +
                    "4\t1\t4\n5\t1\t4\n6\t1\t4\n7\t1\t4\n8\t1\t4\n");
  r = rtb::read_record_csv(p);
  ASSERT_EQ(r.t.size(), 9u);
  EXPECT_EQ(r.F[0], 1000.0);
  EXPECT_EQ(r.x[1], 0.25);
  write_text(p, "time;disp;force\n0;0;0\n0,1;0,2\n");
  expect_input_error(p, {p + ":3:", "2 fields", "header has 3"});
  write_text(p, "time;disp;force\n0;0;0\n0,1;0,2,5;1\n");  // two decimal commas
  expect_input_error(p, {p + ":3:", "non-numeric", "0,2,5"});
}

TEST(IoCsv, ForceOptionalOnRequest) {
  IoTempDir d;
  const std::string p = d.file("a.csv");
  std::string text = "time,displacement\n";
  for (int i = 0; i < 9; ++i) text += std::to_string(i) + "," + std::to_string(i * i) + "\n";
  write_text(p, text);
  expect_input_error(p, {p + ":1:", "'force'"});  // default: required
  rtb::CsvReadOptions opt;
  opt.require_force = false;
  const rtb::Record r = rtb::read_record_csv(p, opt);
  EXPECT_EQ(r.t.size(), 9u);
  EXPECT_EQ(r.x[3], 9.0);
  EXPECT_TRUE(r.F.empty());
  // ... but displacement still is.
  write_text(p, "time,force\n" + std::string("0,1\n1,1\n2,1\n3,1\n4,1\n5,1\n6,1\n7,1\n8,1\n"));
  expect_input_error(p, {p + ":1:", "'displacement'"}, false);
}

TEST(IoCsv, ThirtyThousandRowsAreFast) {
  IoTempDir d;
  const std::string p = d.file("big.csv");
  std::string text = "# units: time=s displacement=in force=kip\n" + kHeader;
  char buf[128];
  const int n = 30000;
  for (int i = 0; i < n; ++i) {
    std::snprintf(buf, sizeof buf, "%.7g,%.7g,%.7g\n", i / 1024.0, std::sin(0.001 * i),
                  std::cos(0.001 * i));
    text += buf;
  }
  write_text(p, text);
  const auto t0 = std::chrono::steady_clock::now();
  const rtb::Record r = rtb::read_record_csv(p);
  const double secs =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  EXPECT_EQ(r.t.size(), (size_t)n);
  EXPECT_LT(secs, 2.0);  // ~10 ms in practice; generous for sanitizer builds
}

TEST(IoCsv, RealDataFileIfPresent) {
  const std::string p =
      std::string(RTB_SHARED_DATA_DIR) + "/friction_damper/d3_sine_2Hz_0.5in.csv";
  if (!fs::exists(p)) GTEST_SKIP() << "shared data not present: " << p;
  const rtb::Record r = rtb::read_record_csv(p);
  EXPECT_EQ(r.t.size(), 3585u);
  EXPECT_EQ(r.units, "time=s displacement=in force=kip");
  EXPECT_EQ(r.sha256.size(), 64u);
}

TEST(IoCsv, WriteReadRoundTripIsExact) {
  IoTempDir d;
  const std::string p = d.file("w.csv");
  std::vector<double> t, x, F;
  for (int i = 0; i < 50; ++i) {
    t.push_back(i / 3.0);
    x.push_back(std::sin(i * 0.7) * 1e-7);
    F.push_back(std::exp(i * 0.9) * (i % 2 ? -1 : 1));
  }
  rtb::write_record_csv(p, t, x, F, "time=s displacement=mm force=N");
  const rtb::Record r = rtb::read_record_csv(p);
  EXPECT_EQ(r.units, "time=s displacement=mm force=N");
  EXPECT_EQ(r.t, t);
  EXPECT_EQ(r.x, x);
  EXPECT_EQ(r.F, F);
  EXPECT_EQ(d.entries(), std::vector<std::string>{"w.csv"});
  // Mismatched lengths are a programming error, and nothing is written.
  F.pop_back();
  EXPECT_THROW(rtb::write_record_csv(d.file("bad.csv"), t, x, F, ""), std::invalid_argument);
  EXPECT_FALSE(fs::exists(d.file("bad.csv")));
}

// ------------------------------------------------------------------ SHA-256

TEST(IoSha256, StandardVectors) {
  EXPECT_EQ(rtb::sha256_hex(""),
            "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(rtb::sha256_hex("abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(rtb::sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(rtb::sha256_hex("abcdefghbcdefghicdefghijdefghijkefghijklfghijklmghijklmnhijklmno"
                            "ijklmnopjklmnopqklmnopqrlmnopqrsmnopqrstnopqrstu"),
            "cf5b16a778af8380036ce59e7b0492370b249b11e8f07a51afac45037afee9d1");
  EXPECT_EQ(rtb::sha256_hex(std::string(1000000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(IoSha256, PaddingBoundaries) {
  const std::pair<int, const char *> v[] = {
      {55, "9f4390f8d30c2dd92ec9f095b65e2b9ae9b0a925a5258e241c9f1e910f734318"},
      {56, "b35439a4ac6f0948b6d6f9e3c6af0f5f590ce20f1bde7090ef7970686ec6738a"},
      {63, "7d3e74a05d7db15bce4ad9ec0658ea98e3f06eeecf16b4c6fff2da457ddc2f34"},
      {64, "ffe054fe7ae0cb6dc65c3af9b61d5209f439851db43d0ba5997337df154668eb"},
      {65, "635361c48bb9eab14198e76ea8ab7f1a41685d6ad62aa9146d301d4f17eb0ae0"},
      {119, "31eba51c313a5c08226adf18d4a359cfdfd8d2e816b13f4af952f7ea6584dcfb"},
      {120, "2f3d335432c70b580af0e8e1b3674a7c020d683aa5f73aaaedfdc55af904c21c"},
      {128, "6836cf13bac400e9105071cd6af47084dfacad4e5e302c94bfed24e013afb73e"}};
  for (const auto &c : v) EXPECT_EQ(rtb::sha256_hex(std::string(c.first, 'a')), c.second) << c.first;
}

TEST(IoSha256, IncrementalEqualsOneShotAndFile) {
  std::string msg;
  for (int i = 0; i < 5000; ++i) msg += (char)(i * 131 % 251);
  const std::string one = rtb::sha256_hex(msg);
  for (size_t chunk : {1u, 3u, 63u, 64u, 65u, 1000u}) {
    rtb::Sha256 s;
    for (size_t i = 0; i < msg.size(); i += chunk) s.update(msg.data() + i, std::min(chunk, msg.size() - i));
    EXPECT_EQ(s.hex_digest(), one) << "chunk " << chunk;
  }
  IoTempDir d;
  write_text(d.file("m.bin"), msg);
  EXPECT_EQ(rtb::sha256_file(d.file("m.bin")), one);
  EXPECT_THROW(rtb::sha256_file(d.file("none")), rtb::InputError);
}

// ------------------------------------------------------------------ atomic write

TEST(IoAtomic, WritesAndReplacesWithoutLeftovers) {
  IoTempDir d;
  const std::string p = d.file("out.txt");
  rtb::write_file_atomic(p, "first\n");
  EXPECT_EQ(read_text(p), "first\n");
  rtb::write_file_atomic(p, std::string(200000, 'z'));
  EXPECT_EQ(read_text(p), std::string(200000, 'z'));
  rtb::write_file_atomic(p, "");
  EXPECT_EQ(read_text(p), "");
  EXPECT_EQ(d.entries(), std::vector<std::string>{"out.txt"});
}

TEST(IoAtomic, KeepsModeOfExistingFile) {
  IoTempDir d;
  const std::string p = d.file("out.txt");
  write_text(p, "old");
  ASSERT_EQ(::chmod(p.c_str(), 0640), 0);
  rtb::write_file_atomic(p, "new");
  struct stat st;
  ASSERT_EQ(::stat(p.c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0640u);
}

TEST(IoAtomic, FailureAtAnyStageLeavesOldFileAndNoTemp) {
  IoTempDir d;
  const std::string p = d.file("keep.txt");
  write_text(p, "precious");
  for (int stage = 1; stage <= 4; ++stage) {
    rtb::set_atomic_write_fault_for_testing(stage);
    EXPECT_THROW(rtb::write_file_atomic(p, "replacement"), std::runtime_error) << stage;
    EXPECT_EQ(read_text(p), "precious") << "stage " << stage;
    EXPECT_EQ(d.entries(), std::vector<std::string>{"keep.txt"}) << "stage " << stage;
  }
  rtb::set_atomic_write_fault_for_testing(0);
  // A failing write of a new file creates nothing.
  rtb::set_atomic_write_fault_for_testing(2);
  EXPECT_THROW(rtb::write_file_atomic(d.file("new.txt"), "x"), std::runtime_error);
  EXPECT_FALSE(fs::exists(d.file("new.txt")));
  EXPECT_EQ(d.entries(), std::vector<std::string>{"keep.txt"});
}

TEST(IoAtomic, TargetIsDirectoryOrMissingDirectory) {
  IoTempDir d;
  fs::create_directory(d.file("sub"));
  write_text(d.file("sub/inner"), "x");
  EXPECT_THROW(rtb::write_file_atomic(d.file("sub"), "data"), std::runtime_error);
  EXPECT_TRUE(fs::is_directory(d.file("sub")));
  EXPECT_EQ(read_text(d.file("sub/inner")), "x");
  EXPECT_THROW(rtb::write_file_atomic(d.file("nodir/out.txt"), "data"), std::runtime_error);
  EXPECT_EQ(d.entries(), std::vector<std::string>{"sub"});
}

TEST(IoAtomic, UnwritableDirectoryLeavesOldFile) {
  IoTempDir d;
  const std::string p = d.file("keep.txt");
  write_text(p, "precious");
  ASSERT_EQ(::chmod(d.path().c_str(), 0555), 0);
  ASSERT_EQ(::chmod(p.c_str(), 0644), 0);
  // As root, directory permissions do not apply: try the write in a child
  // process running as an unprivileged user.
  const bool privileged = ::access(d.path().c_str(), W_OK) == 0;
  const pid_t pid = ::fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    if (privileged && (::setgid(65534) != 0 || ::setuid(65534) != 0)) ::_exit(3);
    if (::access(d.path().c_str(), W_OK) == 0) ::_exit(3);  // still writable: cannot test
    try {
      rtb::write_file_atomic(p, "replacement");
    } catch (const std::runtime_error &) {
      ::_exit(0);  // expected
    }
    ::_exit(1);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  ::chmod(d.path().c_str(), 0755);
  ASSERT_TRUE(WIFEXITED(status));
  if (WEXITSTATUS(status) == 3) GTEST_SKIP() << "cannot make a directory unwritable here";
  EXPECT_EQ(WEXITSTATUS(status), 0) << "write_file_atomic did not throw";
  EXPECT_EQ(read_text(p), "precious");
  EXPECT_EQ(d.entries(), std::vector<std::string>{"keep.txt"});
}

// ------------------------------------------------------------------ params JSON

namespace {

std::string expect_params_error(const std::string &text, const std::vector<std::string> &needles) {
  try {
    rtb::params_from_json_text(text, "fit.json");
  } catch (const rtb::InputError &e) {
    const std::string msg = e.what();
    EXPECT_EQ(msg.rfind("fit.json", 0), 0u) << msg;
    for (const std::string &n : needles)
      EXPECT_NE(msg.find(n), std::string::npos) << "message \"" << msg << "\" lacks \"" << n << "\"";
    return msg;
  }
  ADD_FAILURE() << "no InputError for " << text;
  return "";
}

std::string rt_json(const std::string &params, const std::string &extra = "") {
  return "{\"model\":\"rt\"" + extra + ",\"params\":{" + params + "}}";
}

const std::string kCore = "\"K0\":1000,\"Kpa\":800,\"Kr\":3000,\"C0\":40,\"alpha\":0.2";

bool same_params(const rtb_params &a, const rtb_params &b) {
  return std::memcmp(&a, &b, sizeof a) == 0;  // no padding: 4 ints then doubles
}

}  // namespace

TEST(IoParams, DefaultsAndValues) {
  const rtb_params p = rtb::params_from_json_text(rt_json(kCore), "fit.json");
  rtb_params ref;
  rtb_params_default(&ref, RTB_MODEL_RT);
  ref.Ff = 0.0;  // not given for an RT set
  EXPECT_EQ(p.cells, 15);
  EXPECT_EQ(p.integrator, RTB_INTEGRATOR_SDIRK2);
  EXPECT_EQ(p.model, RTB_MODEL_RT);
  EXPECT_TRUE(same_params(p, ref));
  const rtb_params q = rtb::params_from_json_text(
      "{\"model\":\"sts\",\"cells\":4,\"integrator\":\"be\",\"params\":{\"K0\":1,\"Kpa\":2,"
      "\"Kr\":3,\"Ff\":4,\"backlash\":0.5}}",
      "f.json");
  EXPECT_EQ(q.model, RTB_MODEL_STS);
  EXPECT_EQ(q.cells, 4);
  EXPECT_EQ(q.integrator, RTB_INTEGRATOR_BE);
  EXPECT_EQ(q.Ff, 4.0);
  EXPECT_EQ(q.backlash, 0.5);
}

TEST(IoParams, MissingKeysNamed) {
  for (const char *key : {"K0", "Kpa", "Kr", "C0", "alpha"}) {
    std::string params;
    const char *all[] = {"K0", "Kpa", "Kr", "C0", "alpha"};
    const char *vals[] = {"1000", "800", "3000", "40", "0.2"};
    for (int i = 0; i < 5; ++i)
      if (std::string(all[i]) != key) params += (params.empty() ? "" : ",") + std::string("\"") + all[i] + "\":" + vals[i];
    expect_params_error(rt_json(params), {"missing key", std::string("params.") + key});
  }
  expect_params_error("{\"model\":\"sts\",\"params\":{\"K0\":1,\"Kpa\":2,\"Kr\":3}}",
                      {"missing key", "params.Ff"});
  expect_params_error("{\"params\":{}}", {"\"model\""});
  expect_params_error("{\"model\":\"rt\"}", {"\"params\""});
}

TEST(IoParams, NegativeAndOutOfRangeNamed) {
  // K0 may be negative down to -chain (= -160 here, no softening spring).
  expect_params_error(rt_json("\"K0\":-161,\"Kpa\":800,\"Kr\":3000,\"C0\":40,\"alpha\":0.2"),
                      {"params.K0", "static stiffness at x = 0 must not be negative"});
  expect_params_error(rt_json("\"K0\":1,\"Kpa\":800,\"Kr\":-3000,\"C0\":40,\"alpha\":0.2"),
                      {"params.Kr", "negative"});
  expect_params_error(rt_json("\"K0\":1,\"Kpa\":800,\"Kr\":3000,\"C0\":-4,\"alpha\":0.2"),
                      {"params.C0", "negative"});
  expect_params_error(rt_json(kCore + ",\"viscous_c\":-1"), {"params.viscous_c", "negative"});
  for (const char *a : {"0", "1", "1.2", "-0.5"})
    expect_params_error(rt_json(std::string("\"K0\":1,\"Kpa\":800,\"Kr\":3000,\"C0\":40,\"alpha\":") + a),
                        {"params.alpha", "outside (0,1)"});
  expect_params_error(rt_json("\"K0\":1,\"Kpa\":800,\"Kr\":3000,\"C0\":40,\"alpha\":1e-4"),
                      {"params.alpha", "RTB_ALPHA_MIN"});
  expect_params_error(rt_json(kCore + ",\"mullins\":1"), {"params.mullins"});
  expect_params_error(rt_json(kCore, ",\"cells\":0"), {"\"cells\"", "outside"});
  expect_params_error(rt_json(kCore, ",\"cells\":33"), {"\"cells\"", "outside"});
  expect_params_error(rt_json(kCore, ",\"cells\":2.5"), {"\"cells\"", "integer"});
  expect_params_error(rt_json(kCore, ",\"integrator\":\"rk4\""), {"integrator", "rk4"});
  expect_params_error("{\"model\":\"maxwell\",\"params\":{}}", {"model", "maxwell"});
  expect_params_error(rt_json("\"K0\":\"big\",\"Kpa\":800,\"Kr\":3000,\"C0\":40,\"alpha\":0.2"),
                      {"params.K0", "number"});
  expect_params_error(rt_json(kCore + ",\"k0\":1"), {"unknown key", "k0"});
}

TEST(IoParams, LibraryValidationBecomesInputError) {
  // Each key is fine alone; the combination is rejected by rtb_params_validate.
  const std::string msg = expect_params_error(
      rt_json("\"K0\":10,\"Kpa\":800,\"Kr\":3000,\"C0\":40,\"alpha\":0.2,\"k_asym\":200"),
      {"invalid parameters", "k_asym"});
  EXPECT_NE(msg.find(rtb_status_message(RTB_ERR_PARAM_RANGE)), std::string::npos) << msg;
  expect_params_error(rt_json(kCore + ",\"maxwell_k\":5"), {"maxwell_tau"});
}

TEST(IoParams, InvalidJsonGivesLine) {
  expect_params_error("{\n\"model\": \"rt\",\n\"params\": {\"K0\": 1,,}\n}", {"fit.json:3:", "invalid JSON"});
  expect_params_error("[1,2]", {"object"});
}

TEST(IoParams, FileErrorsNamePath) {
  IoTempDir d;
  try {
    rtb::read_params_json(d.file("none.json"));
    ADD_FAILURE() << "no error";
  } catch (const rtb::InputError &e) {
    EXPECT_NE(std::string(e.what()).find(d.file("none.json")), std::string::npos);
  }
  write_text(d.file("p.json"), rt_json("\"K0\":1,\"Kpa\":800,\"Kr\":3000,\"C0\":40"));
  try {
    rtb::read_params_json(d.file("p.json"));
    ADD_FAILURE() << "no error";
  } catch (const rtb::InputError &e) {
    EXPECT_NE(std::string(e.what()).find(d.file("p.json") + ": missing key \"params.alpha\""),
              std::string::npos)
        << e.what();
  }
}

TEST(IoParams, RoundTripIsBitExact) {
  rtb_params p;
  rtb_params_default(&p, RTB_MODEL_RT);
  p.cells = 7;
  p.integrator = RTB_INTEGRATOR_BE;
  p.K0 = 1.0 / 3.0;
  p.Kpa = 2.0 / 7.0 * 1e5;
  p.Kr = std::nextafter(3000.0, 1e9);
  p.C0 = 4.9406564584124654e-300;
  p.alpha = 0.1 + 0.2;
  p.Ff = 0.0;
  p.k3 = -1.7976931348623157e300;
  p.k_asym = -0.1;
  p.maxwell_k = 12.5;
  p.maxwell_tau = 1e-3 / 3;
  p.viscous_c = std::sqrt(2.0);
  p.mass = 1e-9;
  p.backlash = 0.01;
  p.mullins = 0.999;
  ASSERT_EQ(rtb_params_validate(&p), RTB_OK);
  const std::string text = rtb::params_to_json_text(p);
  const rtb_params q = rtb::params_from_json_text(text, "round.json");
  EXPECT_TRUE(same_params(p, q)) << text;
  EXPECT_EQ(rtb::params_to_json_text(q), text);

  rtb_params s;
  rtb_params_default(&s, RTB_MODEL_STS);
  s.C0 = 0.0;
  s.alpha = 0.0;
  s.Ff = 1.0 / 7.0;
  const rtb_params s2 = rtb::params_from_json_text(rtb::params_to_json_text(s), "sts.json");
  EXPECT_TRUE(same_params(s, s2)) << rtb::params_to_json_text(s);
}

TEST(IoParams, TopLevelExtraKeysIgnored) {
  const rtb_params p = rtb::params_from_json_text(
      "{\"model\":\"rt\",\"fit\":{\"error\":0.03},\"files\":[],\"params\":{" + kCore + "}}",
      "id.json");
  EXPECT_EQ(p.K0, 1000.0);
}

#endif  // RTB_HAVE_OFFLINE
