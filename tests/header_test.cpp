// header_test.cpp -- the generated C parameter header: deterministic
// (byte-identical on re-generation), names validated, and usable: a strict
// C99 program and a C++17 program are compiled against it and the static
// library, run over a CSV record, and must reproduce the offline tool's
// simulate_force bit for bit (same library code, same parameters).
#ifdef RTB_HAVE_OFFLINE
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "cli_path.h"
#include "offline/io/csv.h"
#include "offline/io/header_writer.h"
#include "temp_dir.h"
#include "offline/rtb_offline.h"
#include "test_numbers.h"
#include "text_file.h"

namespace fs = std::filesystem;

namespace {

using rtb_test::read_text;
using rtb_test::shell_quote;

rtb_params header_rt_params() {
  rtb_params p;
  rtb_params_default(&p, RTB_MODEL_RT);
  p.cells = 7;
  p.K0 = 1000.0 / 3.0;
  p.Kpa = 812.345678901234567;
  p.Kr = 2999.0 + 1.0 / 7.0;
  p.C0 = 41.0 / 3.0;
  p.alpha = 0.1 + 0.2;  // not a short decimal
  p.Ff = 0.0;
  p.k3 = -12.5;
  p.k_asym = -std::sqrt(2.0);
  p.maxwell_k = 150.0 / 7.0;
  p.maxwell_tau = 0.0123;
  p.viscous_c = 0.75;
  p.mullins = 0.15;
  return p;
}

rtb_params sts_params() {
  rtb_params p;
  rtb_params_default(&p, RTB_MODEL_STS);
  p.cells = 5;
  p.Ff = 40.0 / 3.0;
  p.C0 = 0.0;
  p.alpha = 0.0;
  p.backlash = 0.02;
  return p;
}

rtb::HeaderInfo info_for(const std::string &name) {
  rtb::HeaderInfo info;
  info.name = name;
  info.tool_version = "rtb 0.1.0";
  info.data_files.push_back({"data/run 1.csv", rtb::sha256_hex("one"), 1234, 0.031});
  info.data_files.push_back({"data/*/x.csv", rtb::sha256_hex("two"), 0,
                             std::numeric_limits<double>::quiet_NaN()});
  info.error = 0.0311;
  info.std_devs = {{"K0", 12.5}, {"alpha", 0.004}};
  // Text that would end the comment, nest one, form a trigraph or splice lines.
  info.provenance = {"identify --data a.csv */ int broken; /*", "line one\nline two ?\?/",
                     "trailing backslash \\"};
  return info;
}

int run_shell(const std::string &cmd, std::string *output = nullptr) {
  std::string full = cmd + " 2>&1";
  FILE *p = ::popen(full.c_str(), "r");
  if (!p) return -1;
  std::string out;
  char buf[4096];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, p)) > 0) out.append(buf, n);
  const int st = ::pclose(p);
  if (output) *output = out;
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

// The configured compiler if it exists, else the first of `fallbacks` on PATH.
std::string find_compiler(const char *configured, std::vector<std::string> fallbacks) {
  if (configured && *configured && ::access(configured, X_OK) == 0) return configured;
  for (const std::string &c : fallbacks) {
    std::string path;
    if (run_shell("command -v " + c, &path) == 0 && !path.empty()) {
      while (!path.empty() && (path.back() == '\n' || path.back() == '\r')) path.pop_back();
      return path;
    }
  }
  return "";
}


}  // namespace

TEST(Header, ByteIdenticalOnRegeneration) {
  const rtb_params p = header_rt_params();
  const std::string a = rtb::emit_parameter_header(p, info_for("test_bushing_rt"));
  const std::string b = rtb::emit_parameter_header(p, info_for("test_bushing_rt"));
  EXPECT_EQ(a, b);
  // ... and depends on its inputs.
  rtb_params q = p;
  q.K0 = std::nextafter(q.K0, 0.0);
  EXPECT_NE(rtb::emit_parameter_header(q, info_for("test_bushing_rt")), a);
  EXPECT_NE(rtb::emit_parameter_header(p, info_for("other_name")), a);
}

TEST(Header, Contents) {
  const std::string h = rtb::emit_parameter_header(header_rt_params(), info_for("test_bushing_rt"));
  EXPECT_NE(h.find("#include \"rt_bushing.h\"\n"), std::string::npos);
  EXPECT_NE(h.find("#ifndef RTB_PARAMS_H_test_bushing_rt\n#define RTB_PARAMS_H_test_bushing_rt\n"),
            std::string::npos);
  EXPECT_NE(h.find("typedef char test_bushing_rt_check_abi[(RTB_ABI_VERSION == " +
                   std::to_string(RTB_ABI_VERSION) + ") ? 1 : -1];"),
            std::string::npos);
  EXPECT_NE(h.find("typedef char test_bushing_rt_check_scalar[(RTB_SCALAR_BYTES == 8) ? 1 : -1];"),
            std::string::npos);
  EXPECT_NE(h.find("[(sizeof(rtb_real) == 8) ? 1 : -1];"), std::string::npos);
  EXPECT_NE(h.find("static const rtb_params test_bushing_rt = {"), std::string::npos);
  EXPECT_NE(h.find("RTB_MODEL_RT, /* model */"), std::string::npos);
  EXPECT_NE(h.find("  7, /* cells */"), std::string::npos);
  EXPECT_NE(h.find("0x1.3333333333334p-2, /* alpha = 0.30000000000000004"), std::string::npos) << h;
  EXPECT_NE(h.find("(sd 12.5)"), std::string::npos);
  EXPECT_NE(h.find(rtb::sha256_hex("one")), std::string::npos);
  EXPECT_NE(h.find("data/run 1.csv"), std::string::npos);
  EXPECT_NE(h.find("rtb 0.1.0"), std::string::npos);
  EXPECT_NE(h.find("3.11 %"), std::string::npos) << h;
  // Comment text is defused: exactly one "*/" per opened comment.
  size_t opens = 0, closes = 0;
  for (size_t i = 0; (i = h.find("/*", i)) != std::string::npos; ++i) ++opens;
  for (size_t i = 0; (i = h.find("*/", i)) != std::string::npos; ++i) ++closes;
  EXPECT_EQ(opens, closes);
  EXPECT_EQ(h.find("??"), std::string::npos);
  // 2 reserved zeros (ABI 2, 3, 6, 7, 8 and 9 took the others), and nothing that looks like a date.
  EXPECT_NE(h.find("reserved[2]"), std::string::npos);
  EXPECT_EQ(h.find("20" "2"), std::string::npos);
}

TEST(Header, NameValidation) {
  const rtb_params p = header_rt_params();
  for (const char *bad : {"", "1abc", "a-b", "a b", "int", "class", "__x", "_Foo", "rtb_params",
                          "rtb_step", "RTB_OK", "na\xc3\xafve"}) {
    EXPECT_FALSE(rtb::is_valid_header_name(bad)) << bad;
    EXPECT_THROW(rtb::emit_parameter_header(p, info_for(bad)), rtb::InputError) << bad;
  }
  for (const char *good : {"a", "_x", "front_left_bushing", "B2", "bushing_rt_v3", "rtb_identified"})
    EXPECT_TRUE(rtb::is_valid_header_name(good)) << good;
  rtb_params bad = p;
  bad.alpha = 1.5;
  EXPECT_THROW(rtb::emit_parameter_header(bad, info_for("x")), rtb::InputError);
}

TEST(Header, CompilesAsC99AndCxx17AndMatchesSimulateBitForBit) {
#if defined(RTB_C_COMPILER)
  const std::string cc = find_compiler(RTB_C_COMPILER, {"cc", "gcc", "clang"});
#else
  const std::string cc = find_compiler(nullptr, {"cc", "gcc", "clang"});
#endif
#if defined(RTB_CXX_COMPILER)
  const std::string cxx = find_compiler(RTB_CXX_COMPILER, {"c++", "g++", "clang++"});
#else
  const std::string cxx = find_compiler(nullptr, {"c++", "g++", "clang++"});
#endif
  if (cc.empty()) GTEST_SKIP() << "no C compiler found; header compile test skipped";
#ifndef RTB_LIB_PATH
  GTEST_SKIP() << "RTB_LIB_PATH not defined by tests/CMakeLists.txt";
#else
  const std::string lib = RTB_LIB_PATH;
  ASSERT_TRUE(fs::exists(lib)) << lib;
#ifdef RTB_TEST_SANITIZE_FLAGS
  const std::string san = std::string(" ") + RTB_TEST_SANITIZE_FLAGS;
#else
  const std::string san;
#endif

  std::string tmpl = (fs::temp_directory_path() / "rtb_header_test_XXXXXX").string();
  std::vector<char> buf(tmpl.begin(), tmpl.end());
  buf.push_back('\0');
  ASSERT_NE(::mkdtemp(buf.data()), nullptr);
  const std::string dir = buf.data();
  struct Cleanup {
    std::string d;
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(d, ec);
    }
  } cleanup{dir};

  // Headers, written the way the tool writes them.
  const rtb_params prt = header_rt_params(), psts = sts_params();
  rtb::write_file_atomic(dir + "/test_bushing_rt.h",
                         rtb::emit_parameter_header(prt, info_for("test_bushing_rt")));
  rtb::write_file_atomic(dir + "/test_bushing_sts.h",
                         rtb::emit_parameter_header(psts, info_for("test_bushing_sts")));

  // Input: starts at rest at 0, non-uniform steps, several amplitudes.
  std::vector<double> t, x;
  double time = 0.0;
  for (int i = 0; i < 1500; ++i) {
    t.push_back(time);
    x.push_back(i == 0 ? 0.0
                       : 0.6 * std::sin(2.0 * M_PI * 0.9 * time) * std::sin(0.7 * time) +
                             0.05 * std::sin(40.0 * time));
    time += 0.003 + 0.001 * (i % 4);
  }
  const std::vector<double> zero(t.size(), 0.0);
  const std::string csv = dir + "/input.csv";
  rtb::write_csv_atomic(csv, {"units: time=s displacement=mm force=N"},
                        {{"time", &t}, {"displacement", &x}});
  rtb::CsvReadOptions ro;
  ro.require_force = false;
  const rtb::Record rec = rtb::read_record_csv(csv, ro);
  ASSERT_EQ(rec.x, x);

  const std::string src = std::string(RTB_SOURCE_DIR) + "/tests/header_compile";
  const std::string inc = " -I" + shell_quote(dir) + " -I" +
                          shell_quote(std::string(RTB_SOURCE_DIR) + "/rt_bushing") + " ";
  struct Program {
    std::string label, compile;
  };
  std::vector<Program> programs;
  programs.push_back({"C99", shell_quote(cc) + " -std=c99 -pedantic -Wall -Wextra -Werror" + san +
                                 inc + shell_quote(src + "/client.c") + " " + shell_quote(lib) +
                                 " -lm -o " + shell_quote(dir + "/client_c")});
  if (!cxx.empty())
    programs.push_back({"C++17", shell_quote(cxx) + " -std=c++17 -pedantic -Wall -Wextra -Werror" +
                                     san + inc + shell_quote(src + "/client.cpp") + " " +
                                     shell_quote(lib) + " -lm -o " +
                                     shell_quote(dir + "/client_cpp")});
  else
    ADD_FAILURE() << "C compiler found but no C++ compiler";

  for (size_t k = 0; k < programs.size(); ++k) {
    const Program &prog = programs[k];
    std::string log;
    ASSERT_EQ(run_shell(prog.compile, &log), 0) << prog.label << " compile failed:\n"
                                          << prog.compile << "\n" << log;
    const std::string exe = dir + (k == 0 ? "/client_c" : "/client_cpp");
    for (const char *model : {"rt", "sts"}) {
      const rtb_params &p = std::string(model) == "rt" ? prt : psts;
      std::string out;
      ASSERT_EQ(run_shell(shell_quote(exe) + " " + shell_quote(csv) + " " + model, &out), 0)
          << prog.label << " " << model << ":\n" << out;
      std::istringstream in(out);
      // Line 1: the parameter set as compiled in.
      int abi, mdl, cells, integ;
      in >> abi >> mdl >> cells >> integ;
      EXPECT_EQ(abi, p.abi_version);
      EXPECT_EQ(mdl, p.model);
      EXPECT_EQ(cells, p.cells);
      EXPECT_EQ(integ, p.integrator);
      const double *fields[] = {&p.K0,        &p.Kpa,         &p.Kr,        &p.C0,   &p.alpha,
                                &p.Ff,        &p.k3,          &p.k_asym,    &p.maxwell_k,
                                &p.maxwell_tau, &p.viscous_c, &p.mass,      &p.backlash,
                                &p.mullins};
      for (const double *f : fields) {
        std::string tok;
        in >> tok;
        const double v = std::strtod(tok.c_str(), nullptr);
        EXPECT_TRUE(same_bits(v, *f)) << prog.label << " " << model << ": field " << tok
                                      << " != " << *f;
      }
      // Then the forces.
      const std::vector<double> ref = rtb::simulate_force(p, rec);
      std::vector<double> got;
      std::string tok;
      while (in >> tok) got.push_back(std::strtod(tok.c_str(), nullptr));
      ASSERT_EQ(got.size(), ref.size()) << prog.label << " " << model;
      size_t mismatches = 0, first = 0;
      for (size_t i = 0; i < ref.size(); ++i)
        if (!same_bits(got[i], ref[i]) && mismatches++ == 0) first = i;
      EXPECT_EQ(mismatches, 0u) << prog.label << " " << model << ": first mismatch at sample "
                                << first << ": program " << got[first] << " vs simulate_force "
                                << ref[first];
      // Not a vacuous comparison.
      double fmax = 0.0;
      for (double v : ref) fmax = std::max(fmax, std::fabs(v));
      EXPECT_GT(fmax, 1.0);
    }
  }
#endif
}

// ---------------------------------------------------------------- six axes
// `rtb header --axis x=fx.json --axis rz=mz.json`: reproducible bytes, the
// same constant from --bushing6, and a program compiled against it as C99
// and as C++17 gives bit for bit what rtb_bushing6_step gives in-process.
namespace {

rtb_bushing6_params two_axis_params() {
  rtb_bushing6_params p;
  rtb_bushing6_params_default(&p, RTB_MODEL_RT);
  for (int a = 0; a < RTB_AXES; ++a) p.active[a] = 0;
  p.active[RTB_AXIS_X] = p.active[RTB_AXIS_RZ] = 1;
  p.axis[RTB_AXIS_X] = header_rt_params();
  p.axis[RTB_AXIS_RZ] = sts_params();
  return p;
}

// What client6.c prints, computed here with the library.
std::string client6_reference(const rtb_bushing6_params &p) {
  rtb_bushing6_state s;
  std::string out;
  if (rtb_bushing6_init(&s, &p, nullptr, nullptr) != RTB_OK) return "init failed";
  for (int i = 1; i <= 300; ++i) {
    double x[RTB_AXES], F[RTB_AXES];
    for (int a = 0; a < RTB_AXES; ++a) x[a] = (a < RTB_AXIS_RX ? 0.5 : 0.02) * std::sin(0.03 * i * (a + 1));
    if (rtb_bushing6_step(&s, &p, nullptr, x, 1e-3, F, nullptr) < 0) return "step failed";
    char buf[64];
    for (int a = 0; a < RTB_AXES; ++a) {
      std::snprintf(buf, sizeof buf, "%a%c", F[a], a + 1 < RTB_AXES ? ' ' : '\n');
      out += buf;
    }
  }
  return out;
}

std::string constant_part(const std::string &h) { return h.substr(h.find("static const")); }

}  // namespace

TEST(Header6, CliHeaderIsReproducibleAndCompilesAsC99AndCxx17) {
  const std::string cc = find_compiler(nullptr, {"cc", "gcc", "clang"});
  const std::string cxx = find_compiler(nullptr, {"c++", "g++", "clang++"});
  if (cc.empty() || cxx.empty()) GTEST_SKIP() << "no C/C++ compiler found";
#ifndef RTB_LIB_PATH
  GTEST_SKIP() << "RTB_LIB_PATH not defined by tests/CMakeLists.txt";
#else
#ifdef RTB_TEST_SANITIZE_FLAGS
  const std::string san = std::string(" ") + RTB_TEST_SANITIZE_FLAGS;
#else
  const std::string san;
#endif
  rtb_test::TempDir d("rtb_header6");
  const rtb_bushing6_params p = two_axis_params();
  rtb::write_file_atomic(d.file("fx.json"), rtb::params_to_json_text(p.axis[RTB_AXIS_X]));
  rtb::write_file_atomic(d.file("mz.json"), rtb::params_to_json_text(p.axis[RTB_AXIS_RZ]));
  const std::string rtb = shell_quote(rtb_test::kRtb);
  const std::string axes = " --axis x=" + shell_quote(d.file("fx.json")) + " --axis rz=" +
                           shell_quote(d.file("mz.json"));
  std::string log;
  ASSERT_EQ(run_shell(rtb + " header" + axes + " --out " + shell_quote(d.file("bushing6.h")), &log), 0)
      << log;
  ASSERT_EQ(run_shell(rtb + " header" + axes + " --name bushing6 --quiet --out " +
                    shell_quote(d.file("again.h")), &log), 0) << log;
  const std::string h = read_text(d.file("bushing6.h"));
  EXPECT_EQ(read_text(d.file("again.h")), h);
  EXPECT_NE(h.find("static const rtb_bushing6_params bushing6 = {"), std::string::npos) << h;
  EXPECT_NE(h.find("{ 1, 0, 0, 0, 0, 1 }, /* active"), std::string::npos) << h;
  EXPECT_NE(h.find(rtb::sha256_file(d.file("mz.json"))), std::string::npos);
  // The six-axis JSON gives the same constant.
  rtb::write_file_atomic(d.file("b6.json"), "{\"x\": " + read_text(d.file("fx.json")) +
                                                 ", \"rz\": " + read_text(d.file("mz.json")) + "}");
  ASSERT_EQ(run_shell(rtb + " header --bushing6 " + shell_quote(d.file("b6.json")) +
                    " --name bushing6 --out " + shell_quote(d.file("b6.h")), &log), 0) << log;
  EXPECT_EQ(constant_part(read_text(d.file("b6.h"))), constant_part(h));

  const std::string src = std::string(RTB_SOURCE_DIR) + "/tests/header_compile/client6.c";
  const std::string inc = " -I" + shell_quote(d.path()) + " -I" +
                          shell_quote(std::string(RTB_SOURCE_DIR) + "/rt_bushing") + " ";
  const std::string libs = " " + shell_quote(RTB_LIB_PATH) + " -lm -o ";
  const std::string ref = client6_reference(p);
  const struct {
    const char *label;
    std::string compile, exe;
  } programs[] = {
      {"C99", shell_quote(cc) + " -std=c99 -pedantic -Wall -Wextra -Werror" + san + inc +
                  shell_quote(src) + libs + shell_quote(d.file("c6")), d.file("c6")},
      {"C++17", shell_quote(cxx) + " -x c++ -std=c++17 -pedantic -Wall -Wextra -Werror" + san +
                    inc + shell_quote(src) + " -x none" + libs + shell_quote(d.file("cpp6")),
       d.file("cpp6")},
  };
  for (const auto &prog : programs) {
    ASSERT_EQ(run_shell(prog.compile, &log), 0) << prog.label << ":\n" << prog.compile << "\n" << log;
    std::string out;
    ASSERT_EQ(run_shell(shell_quote(prog.exe), &out), 0) << prog.label << out;
    EXPECT_EQ(out, ref) << prog.label << ": differs from rtb_bushing6_step";
  }
  EXPECT_EQ(std::count(ref.begin(), ref.end(), '\n'), 300);
  EXPECT_EQ(ref.find("0x0p+0 0x0p+0 0x0p+0 0x0p+0 0x0p+0 0x0p+0"), std::string::npos);
#endif
}

TEST(Header6, CliRefusesBadAxesAndWritesNothing) {
  rtb_test::TempDir d("rtb_header6_bad");
  rtb::write_file_atomic(d.file("fx.json"), rtb::params_to_json_text(header_rt_params()));
  const std::string rtb = shell_quote(rtb_test::kRtb), fx = shell_quote(d.file("fx.json"));
  const std::string out = " --out " + shell_quote(d.file("h.h"));
  std::string log;
  EXPECT_EQ(run_shell(rtb + " header --axis q=" + fx + out, &log), 2) << log;
  EXPECT_NE(log.find("x y z rx ry rz"), std::string::npos) << log;
  EXPECT_EQ(run_shell(rtb + " header --axis x=" + fx + " --axis x=" + fx + out, &log), 2) << log;
  EXPECT_EQ(run_shell(rtb + " header --axis x=" + fx + " --params " + fx + out, &log), 2) << log;
  EXPECT_EQ(run_shell(rtb + " header --axis x=" + fx + " --out " + shell_quote(d.file("int.h")), &log), 2)
      << log;  // the constant would be named "int"
  rtb::write_file_atomic(d.file("b6.json"), "{\"x\": {\"model\": \"rt\"}}");
  EXPECT_EQ(run_shell(rtb + " header --bushing6 " + shell_quote(d.file("b6.json")) + out, &log), 2);
  EXPECT_NE(log.find("axis x"), std::string::npos) << log;
  EXPECT_EQ(d.entries(), (std::vector<std::string>{"b6.json", "fx.json"}));
}

#endif  // RTB_HAVE_OFFLINE
