// fit_common.h -- options and outputs shared by the fitting subcommands
// (identify, diagnose): data files, start point, method, masking, JSON.
#ifndef RTB_OFFLINE_CLI_FIT_COMMON_H
#define RTB_OFFLINE_CLI_FIT_COMMON_H

#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "cli/cli.h"
#include "identify/identify.h"
#include "identify/sts_init.h"
#include "io/header_writer.h"
#include "preprocess/preprocess.h"

namespace rtb {
namespace cli {

struct FitSetup {
  std::vector<Record> recs;
  rtb_params start{};
  std::string init = "sts";     // "sts" or a JSON path
  double alpha0 = 0.2;
  bool sts_used = false;
  LoopFeatures features;
  StsParams sts;
  std::string sts_note;
  IdentifyOptions opt;
  double reg_weight = 0.0;
  Preprocess pre;               // applied to recs before the start point
};

// --scale-*, --lowpass, --mask, --mask-reversals, --weight (preprocess_options.cpp).
std::vector<OptionSpec> preprocess_option_specs();
CommandSpec with_preprocess_options(CommandSpec spec);  // spec + the options above
Preprocess preprocess_from(const Args &a);
// Decides an `auto` force sign from the fit records (force_sign_of) and says
// so on stderr when it flips; a given sign is kept.
void resolve_force_sign(Preprocess &pp, const std::vector<Record> &fit, bool quiet);

// The common options: --data, --cells, --method, --init, --alpha0,
// --fit-from, --ramp-time, --free, --reg-weight, --max-iter, --quiet,
// plus `extra`.
std::vector<OptionSpec> fit_option_specs(std::vector<OptionSpec> extra);
// Reads the files and builds the start point (throws InputError/UsageError).
FitSetup parse_fit_setup(const Args &a);
IdentifyResult run_fit(const FitSetup &fs, bool quiet);
void print_fit_summary(const IdentifyResult &r, const FitSetup &fs);
nlohmann::ordered_json fit_result_json(const IdentifyResult &r, const FitSetup &fs);
nlohmann::ordered_json uncertainty_json(const Uncertainty &u);
HeaderInfo header_info_for(const IdentifyResult &r, const FitSetup &fs, const std::string &name);
std::vector<ParamId> parse_param_list(const std::string &csv);

}  // namespace cli
}  // namespace rtb

#endif
