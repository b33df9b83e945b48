// refgen_main.cpp -- `refgen`: writes the records of one scenario as CSV.
//
//   refgen --effect NAME[,NAME...] [--seed S] [--duration T] [--noise-free] --out-dir DIR
//   refgen --list
//
// DIR gets fit_*.csv (slow triangle, 1 and 5 Hz sines, ramp-and-hold,
// multi-sine), holdout_*.csv (a 15-30 Hz sine, an earthquake-like record) and
// truth.json (the parameters, effect sizes and noise floors).
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "refgen.h"

namespace {

const char *const kUsage =
    "usage: refgen --effect NAME[,NAME...] [--seed S] [--duration T] [--noise-free]\n"
    "              --out-dir DIR\n"
    "       refgen --list\n"
    "  --effect    effect words (see --list); 'none' is plain RT\n"
    "  --seed      scenario seed, a positive integer (default 1)\n"
    "  --duration  seconds per record, >= 1 (default 8)\n"
    "  --noise-free  no noise on either channel (to compare models)\n"
    "  --out-dir   created if missing; gets fit_*.csv, holdout_*.csv, truth.json\n";

std::vector<std::string> split_commas(const std::string &s) {
  std::vector<std::string> out;
  size_t pos = 0;
  for (;;) {
    const size_t e = s.find(',', pos);
    out.push_back(s.substr(pos, e == std::string::npos ? std::string::npos : e - pos));
    if (e == std::string::npos) return out;
    pos = e + 1;
  }
}

double parse_number(const std::string &opt, const std::string &v) {
  char *end = nullptr;
  const double x = std::strtod(v.c_str(), &end);
  if (v.empty() || *end != '\0') throw std::invalid_argument(opt + ": not a number: '" + v + "'");
  return x;
}

int run(int argc, char **argv) {
  std::string effects, out_dir;
  double seed = 1, duration = 8.0;
  bool noise_free = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--list") {
      for (const std::string &e : refgen::effect_names())
        std::printf("%-20s -> %s\n", e.c_str(), refgen::expected_word(e).c_str());
      return 0;
    }
    if (a == "--noise-free") {
      noise_free = true;
      continue;
    }
    if (a == "--help" || a == "-h") {
      std::fputs(kUsage, stdout);
      return 0;
    }
    if (i + 1 >= argc) throw std::invalid_argument(a + ": missing value (or unknown option)");
    const std::string v = argv[++i];
    if (a == "--effect") effects = v;
    else if (a == "--seed") seed = parse_number(a, v);
    else if (a == "--duration") duration = parse_number(a, v);
    else if (a == "--out-dir") out_dir = v;
    else throw std::invalid_argument("unknown option " + a);
  }
  if (effects.empty() || out_dir.empty()) throw std::invalid_argument("--effect and --out-dir are required");
  if (!(seed >= 1 && seed <= 1e9 && seed == (double)(unsigned)seed))
    throw std::invalid_argument("--seed must be a positive integer");
  refgen::Scenario sc = refgen::make_scenario(split_commas(effects), (unsigned)seed, duration);
  if (noise_free) sc.chain.force_noise = sc.chain.disp_noise = 0.0;
  std::vector<refgen::Samples> recs;  // all first: a failure writes nothing
  for (size_t i = 0; i < sc.records.size(); ++i) recs.push_back(refgen::run_scenario_record(sc, i));
  std::filesystem::create_directories(out_dir);
  for (size_t i = 0; i < sc.records.size(); ++i)
    refgen::write_record_csv(out_dir + "/" + sc.records[i].name + ".csv", recs[i], sc.column_style);
  refgen::write_truth_json(out_dir + "/truth.json", sc, recs);
  return 0;
}

}  // namespace

int main(int argc, char **argv) {
  try {
    return run(argc, argv);
  } catch (const std::exception &e) {
    std::fprintf(stderr, "refgen: %s\n%s", e.what(), kUsage);
    return 2;
  }
}
