// cli_test.cpp -- the `rtb` executable end to end: help, exit codes,
// simulate (force column, row count, same numbers as simulate_force),
// validate (self-consistent record -> error ~ 0; JSON output), and that bad
// input exits with status 2 without creating the output file.
#ifdef RTB_HAVE_OFFLINE
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli_path.h"
#include "offline/io/csv.h"
#include "offline/io/params_json.h"
#include "offline/model/misfit_norms.h"
#include "offline/rtb_offline.h"
#include "text_file.h"

namespace fs = std::filesystem;

namespace {

using rtb_test::read_text;
using rtb_test::shell_quote;
using rtb_test::write_text;

using rtb_test::kRtb;

struct CmdResult {
  int code = -1;
  std::string out, err;
};

class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!fs::exists(kRtb)) GTEST_SKIP() << "rtb executable not built: " << kRtb;
    std::string tmpl = (fs::temp_directory_path() / "rtb_cli_test_XXXXXX").string();
    std::vector<char> buf(tmpl.begin(), tmpl.end());
    buf.push_back('\0');
    ASSERT_NE(::mkdtemp(buf.data()), nullptr);
    dir_ = buf.data();
  }
  void TearDown() override {
    std::error_code ec;
    if (!dir_.empty()) fs::remove_all(dir_, ec);
  }
  std::string file(const std::string &name) const { return dir_ + "/" + name; }

  // Runs `rtb ARGS` (ARGS already quoted), capturing stdout/stderr.
  CmdResult rtb(const std::string &args) const {
    CmdResult r;
    const std::string o = file(".stdout"), e = file(".stderr");
    const std::string cmd = shell_quote(kRtb) + " " + args + " >" + shell_quote(o) + " 2>" +
                            shell_quote(e);
    const int st = std::system(cmd.c_str());
    r.code = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
    r.out = read_text(o);
    r.err = read_text(e);
    fs::remove(o);
    fs::remove(e);
    return r;
  }

  // Displacement-only input: non-uniform grid, starts at rest at x = 0.
  std::string make_input(const std::string &name, int n, bool with_force = false) const {
    std::string s = "# test input\n# units: time=s displacement=mm force=N\n";
    s += with_force ? "time,displacement,force\n" : "time,displacement\n";
    char buf[128];
    double t = 0.0;
    for (int i = 0; i < n; ++i) {
      const double x = i == 0 ? 0.0 : 0.8 * std::sin(2.0 * M_PI * 1.3 * t) * (1.0 - std::exp(-t));
      if (with_force)
        std::snprintf(buf, sizeof buf, "%.17g,%.17g,%.17g\n", t, x, 900.0 * x + 3.0 * std::cos(t));
      else
        std::snprintf(buf, sizeof buf, "%.17g,%.17g\n", t, x);
      s += buf;
      t += 0.004 + 0.002 * ((i * 7) % 3);
    }
    write_text(file(name), s);
    return file(name);
  }

  // The model's own force for make_input's 800 samples: sim.csv.
  std::string simulated_record(const std::string &params) const {
    const std::string in = make_input("x.csv", 800), sim = file("sim.csv");
    const CmdResult r = rtb("simulate --quiet --params " + shell_quote(params) + " --input " +
                            shell_quote(in) + " --out " + shell_quote(sim));
    EXPECT_EQ(r.code, 0) << r.err;
    return sim;
  }

  std::string make_params(const std::string &name) const {
    write_text(file(name),
               "{\"model\":\"rt\",\"cells\":9,\"params\":{\"K0\":1000,\"Kpa\":800,\"Kr\":3000,"
               "\"C0\":40,\"alpha\":0.2,\"viscous_c\":0.5}}\n");
    return file(name);
  }

  std::string dir_;
};

}  // namespace

TEST_F(CliTest, HelpListsSubcommandsAndEachHasHelp) {
  const CmdResult r = rtb("--help");
  EXPECT_EQ(r.code, 0);
  for (const char *s : {"simulate", "validate", "info"}) {
    EXPECT_NE(r.out.find(s), std::string::npos) << r.out;
    const CmdResult h = rtb(std::string(s) + " --help");
    EXPECT_EQ(h.code, 0) << s;
    EXPECT_NE(h.out.find(std::string("usage: rtb ") + s), std::string::npos) << h.out;
  }
  const CmdResult none = rtb("");
  EXPECT_EQ(none.code, 2);
  EXPECT_NE(none.err.find("usage"), std::string::npos);
}

TEST_F(CliTest, UnknownSubcommandOrOptionExits2) {
  CmdResult r = rtb("frobnicate");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("unknown subcommand 'frobnicate'"), std::string::npos) << r.err;
  r = rtb("--frob");
  EXPECT_EQ(r.code, 2);
  r = rtb("info --frob");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--frob"), std::string::npos) << r.err;
  r = rtb("simulate --params x.json");  // missing required options
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("missing option --input"), std::string::npos) << r.err;
  r = rtb("simulate --params");  // option without value
  EXPECT_EQ(r.code, 2);
  // Out-of-range value: refused before anything is printed or written.
  r = rtb("demo --duration 1 --out-dir " + shell_quote(file("demo")));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--duration"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty()) << r.out;
  EXPECT_FALSE(fs::exists(file("demo")));
}

TEST_F(CliTest, InfoPrintsLibraryFacts) {
  const CmdResult r = rtb("info");
  EXPECT_EQ(r.code, 0);
  rtb_info info;
  rtb_get_info(&info);
  EXPECT_NE(r.out.find(info.version), std::string::npos);
  EXPECT_NE(r.out.find("ABI version      " + std::to_string(RTB_ABI_VERSION)), std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find(std::to_string(RTB_MAX_CELLS)), std::string::npos);
  EXPECT_NE(r.out.find("double"), std::string::npos);
  const CmdResult j = rtb("info --json");
  EXPECT_EQ(j.code, 0);
  const auto doc = nlohmann::json::parse(j.out);
  EXPECT_EQ(doc["max_cells"], RTB_MAX_CELLS);
  EXPECT_EQ(doc["abi_version"], RTB_ABI_VERSION);
}

TEST_F(CliTest, SimulateWritesForceColumnMatchingLibrary) {
  const std::string in = make_input("x.csv", 600);
  const std::string params = make_params("p.json");
  const std::string out = file("f.csv");
  const CmdResult r = rtb("simulate --params " + shell_quote(params) + " --input " + shell_quote(in) +
                    " --out " + shell_quote(out));
  ASSERT_EQ(r.code, 0) << r.err;
  const rtb::Record sim = rtb::read_record_csv(out);  // force column required
  EXPECT_EQ(sim.t.size(), 600u);
  EXPECT_EQ(sim.units, "time=s displacement=mm force=N");
  // Same numbers as the in-process forward model (%.17g round-trips).
  rtb::CsvReadOptions ro;
  ro.require_force = false;
  const rtb::Record rec = rtb::read_record_csv(in, ro);
  const std::vector<double> F = rtb::simulate_force(rtb::read_params_json(params), rec);
  ASSERT_EQ(F.size(), sim.F.size());
  for (size_t i = 0; i < F.size(); ++i) ASSERT_EQ(F[i], sim.F[i]) << "sample " << i;
  EXPECT_EQ(sim.t, rec.t);
  EXPECT_EQ(sim.x, rec.x);
  // The header line has no measured-force column when the input had none.
  EXPECT_NE(read_text(out).find("\ntime,displacement,force\n"), std::string::npos);
}

TEST_F(CliTest, ValidateSelfConsistentRecordHasZeroError) {
  const std::string params = make_params("p.json");
  const std::string sim = simulated_record(params);
  const std::string vj = file("v.json");
  const CmdResult r = rtb("validate --params " + shell_quote(params) + " --data " + shell_quote(sim) +
                    " --out " + shell_quote(vj));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("overall"), std::string::npos) << r.out;
  const auto doc = nlohmann::json::parse(read_text(vj));
  EXPECT_LT(doc["error"].get<double>(), 1e-12);
  ASSERT_EQ(doc["files"].size(), 1u);
  EXPECT_EQ(doc["files"][0]["path"], sim);
  EXPECT_EQ(doc["files"][0]["samples"], 800);
  EXPECT_EQ(doc["files"][0]["sha256"], rtb::sha256_file(sim));
  EXPECT_LT(doc["files"][0]["error"].get<double>(), 1e-12);
}

// A compression-positive load cell: the force falls as the displacement
// rises. The tool reads it as such (says so, records force_sign -1) and
// fits the same element; --force-sign 1 keeps the sign as recorded.
TEST_F(CliTest, AForceOfTheOtherSignConventionIsFlippedAndSaid) {
  const std::string params = make_params("p.json");
  const std::string sim = simulated_record(params);
  std::string flipped = "time,displacement,force\n";
  std::istringstream lines(read_text(sim));
  std::string line;
  while (std::getline(lines, line)) {
    if (line.empty() || line[0] == '#' || line[0] == 't') continue;
    double t, x, F;
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf,%lf,%lf", &t, &x, &F), 3) << line;
    char buf[128];
    std::snprintf(buf, sizeof buf, "%.17g,%.17g,%.17g\n", t, x, -F);
    flipped += buf;
  }
  write_text(file("flipped.csv"), flipped);
  const std::string vj = file("v.json");
  const CmdResult r = rtb("validate --params " + shell_quote(params) + " --data " +
                          shell_quote(file("flipped.csv")) + " --out " + shell_quote(vj));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("flipped"), std::string::npos) << r.err;
  const auto doc = nlohmann::json::parse(read_text(vj));
  EXPECT_LT(doc["error"].get<double>(), 1e-12);
  EXPECT_EQ(doc["preprocessing"]["force_sign"], -1);
  const CmdResult kept = rtb("validate --force-sign 1 --params " + shell_quote(params) +
                             " --data " + shell_quote(file("flipped.csv")) + " --out " + shell_quote(vj));
  ASSERT_EQ(kept.code, 0) << kept.err;
  EXPECT_GT(nlohmann::json::parse(read_text(vj))["error"].get<double>(), 1.9);  // |F + F| / |F| = 2
  EXPECT_EQ(rtb("validate --force-sign 2 --params " + shell_quote(params) + " --data " +
                shell_quote(file("flipped.csv")) + " --out " + shell_quote(vj)).code,
            2);
}

// --init friction: a sliding device (one slider, Kr = 1e-3 Kpa, alpha near
// its floor) is identified from the Jenkins start built from its own loop
// features (sts_init.h), and the JSON says which start was used.
TEST_F(CliTest, IdentifyFromTheFrictionStartFitsASlidingDevice) {
  const std::string in = make_input("x.csv", 1200);
  write_text(file("dev.json"),
             "{\"model\":\"rt\",\"cells\":9,\"params\":{\"K0\":0.2,\"Kpa\":30,\"Kr\":0.03,"
             "\"C0\":2.5,\"alpha\":0.01}}\n");
  const std::string sim = file("sim.csv");
  ASSERT_EQ(rtb("simulate --quiet --params " + shell_quote(file("dev.json")) + " --input " +
                shell_quote(in) + " --out " + shell_quote(sim))
                .code,
            0);
  const std::string id = file("id.json");
  const CmdResult r = rtb("identify --quiet --init friction --cells 9 --data " + shell_quote(sim) +
                          " --out " + shell_quote(id));
  ASSERT_EQ(r.code, 0) << r.err;
  const auto doc = nlohmann::json::parse(read_text(id));
  EXPECT_EQ(doc["init"], "friction");
  EXPECT_LT(doc["error"].get<double>(), 0.01) << r.out;
  std::printf("[cli] friction start: error %.2e -> %.2e\n", doc["error_start"].get<double>(), doc["error"].get<double>());
  EXPECT_LT(doc["error"].get<double>(), doc["error_start"].get<double>());
}

TEST_F(CliTest, ValidateMatchesMisfitNormsOverSeveralFiles) {
  const std::string params = make_params("p.json");
  const std::string a = make_input("a.csv", 500, true);
  const std::string b = make_input("b.csv", 300, true);
  const std::string vj = file("v.json");
  const CmdResult r = rtb("validate --quiet --params " + shell_quote(params) + " --data " +
                    shell_quote(a) + " --data " + shell_quote(b) + " --out " + shell_quote(vj));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, "");  // --quiet
  const rtb_params p = rtb::read_params_json(params);
  std::vector<rtb::MisfitNorms> parts;
  for (const std::string &f : {a, b}) {
    const rtb::Record rec = rtb::read_record_csv(f);
    parts.push_back(rtb::misfit_norms(rec.t, rtb::simulate_force(p, rec), rec.F));
  }
  const auto doc = nlohmann::json::parse(read_text(vj));
  const double overall = rtb::combined_relative_error(parts);
  EXPECT_GT(overall, 1e-3);
  EXPECT_DOUBLE_EQ(doc["error"].get<double>(), overall);
  EXPECT_DOUBLE_EQ(doc["files"][0]["error"].get<double>(), parts[0].relative_error());
  EXPECT_DOUBLE_EQ(doc["files"][1]["error"].get<double>(), parts[1].relative_error());
  EXPECT_DOUBLE_EQ(doc["files"][1]["nrmse_percent"].get<double>(), parts[1].nrmse_percent());
  // overall = sqrt(sum J / sum J0), between the per-file figures.
  EXPECT_DOUBLE_EQ(overall, std::sqrt((parts[0].J + parts[1].J) / (parts[0].J0 + parts[1].J0)));
}

TEST_F(CliTest, BadInputExits2WithoutOutput) {
  const std::string params = make_params("p.json");
  const std::string good = make_input("x.csv", 50, true);
  std::string bad_csv = "time,displacement\n0,0\n0.1,abc\n";
  for (int i = 0; i < 10; ++i) bad_csv += std::to_string(0.2 + i) + ",1\n";
  write_text(file("bad.csv"), bad_csv);
  write_text(file("bad.json"), "{\"model\":\"rt\",\"params\":{\"K0\":1,\"Kpa\":1,\"Kr\":1,\"C0\":1}}");
  const std::string out = file("out.csv");

  CmdResult r = rtb("simulate --params " + shell_quote(params) + " --input " +
              shell_quote(file("bad.csv")) + " --out " + shell_quote(out));
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err.rfind("rtb: error: ", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(file("bad.csv") + ":3:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("\"abc\""), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));

  r = rtb("simulate --params " + shell_quote(file("bad.json")) + " --input " + shell_quote(good) +
          " --out " + shell_quote(out));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("params.alpha"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));

  r = rtb("simulate --params " + shell_quote(params) + " --input " +
          shell_quote(file("missing.csv")) + " --out " + shell_quote(out));
  EXPECT_EQ(r.code, 2);
  EXPECT_FALSE(fs::exists(out));

  // validate: one bad file among good ones -> nothing written.
  const std::string vj = file("v.json");
  r = rtb("validate --params " + shell_quote(params) + " --data " + shell_quote(good) +
          " --data " + shell_quote(file("bad.csv")) + " --out " + shell_quote(vj));
  EXPECT_EQ(r.code, 2);
  EXPECT_FALSE(fs::exists(vj));
  // validate needs a force column.
  const std::string noforce = make_input("nf.csv", 50, false);
  r = rtb("validate --params " + shell_quote(params) + " --data " + shell_quote(noforce) +
          " --out " + shell_quote(vj));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("'force'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(vj));
  // --decimate: an integer >= 1, and only below the low-pass's Nyquist.
  const std::string big = make_input("big.csv", 400, true);
  r = rtb("validate --params " + shell_quote(params) + " --data " + shell_quote(big) +
          " --decimate 2.5 --out " + shell_quote(vj));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--decimate"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(vj));
  r = rtb("validate --params " + shell_quote(params) + " --data " + shell_quote(big) +
          " --decimate 4 --out " + shell_quote(vj));
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("Nyquist"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(vj));
  // No leftovers (temporary files) in the directory.
  for (const auto &e : fs::directory_iterator(dir_))
    EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << e.path();
}

#endif  // RTB_HAVE_OFFLINE
