// cmd_gradcheck.cpp -- `rtb gradcheck`: the adjoint gradient of the discrete
// misfit against central finite differences, and the dot-product test of
// eq. (15)-(16).
#include <cstdio>
#include <nlohmann/json.hpp>

#include "cli/cli.h"
#include "cli/fit_common.h"
#include "identify/gradcheck.h"
#include "io/params_json.h"

namespace rtb {
namespace cli {

int run_gradcheck(int argc, char **argv) {
  static const CommandSpec spec{
      "gradcheck",
      "Check the exact adjoint gradient of the misfit (eq. (11)) against central\n"
      "finite differences of the same discrete misfit, and the dot-product test of\n"
      "the linearized step and its adjoint (eq. (15)-(16)).",
      {
          {"params", "FILE", "parameter JSON at which to check", true},
          {"data", "FILE", "record CSV; repeat for several", true, true},
          {"free", "LIST", "parameters to check (default: every nonzero one)"},
          {"fit-from", "S", "mask samples before t0 + S"},
          {"out", "FILE", "write the figures as JSON"},
          {"smoothing", "S", "eq. (14) sigmoid smoothing s [1/velocity] (default: the file's, 0 = off)"},
      },
      "FD: Richardson-extrapolated central differences with relative step 1e-4, the\n"
      "stepper at Newton tolerance 1e-15. rel = |adjoint - FD| / |FD| (components\n"
      "below 1e-8 of the largest scaled component are judged against that floor)."};
  Args a;
  if (parse_or_help(spec, argc, argv, a)) return kExitOk;
  rtb_params p = read_params_json(a.get("params"));
  p.smoothing = a.get_double("smoothing", p.smoothing);  // eq. (14); finite by get_double
  if (p.smoothing < 0.0) throw UsageError("--smoothing must be >= 0 (0 = off)");
  if (p.model != RTB_MODEL_RT) throw InputError(a.get("params") + ": gradcheck needs an \"rt\" model");
  std::vector<Record> recs;
  for (const std::string &path : a.all("data")) recs.push_back(read_record_csv(path));
  MisfitOptions mo;
  mo.fit_from = a.get_double("fit-from", 0.0);
  std::vector<ParamId> ids;
  if (a.has("free")) ids = parse_param_list(a.get("free"));
  const GradcheckResult g = gradcheck(p, recs, mo, ids);
  std::printf("J = %.17g\n%-12s %24s %24s %10s\n", g.J, "parameter", "adjoint", "finite diff.", "rel");
  for (const GradcheckRow &r : g.rows)
    std::printf("%-12s %24.15e %24.15e %10.2e\n", param_name(r.id), r.adjoint, r.fd, r.rel);
  std::printf("max_rel_diff %.3e\ndot_product_rel_mismatch %.3e\n", g.max_rel_diff,
              g.dot_product_rel_mismatch);
  if (a.has("out")) {
    nlohmann::ordered_json j;
    j["J"] = g.J;
    nlohmann::ordered_json rows = nlohmann::ordered_json::array();
    for (const GradcheckRow &r : g.rows)
      rows.push_back({{"param", param_name(r.id)}, {"adjoint", r.adjoint}, {"fd", r.fd}, {"rel", r.rel}});
    j["gradient"] = rows;
    j["max_rel_diff"] = g.max_rel_diff;
    j["dot_product_rel_mismatch"] = g.dot_product_rel_mismatch;
    j["tool"] = tool_version();
    write_file_atomic(a.get("out"), j.dump(2) + "\n");
  }
  return kExitOk;
}

}  // namespace cli
}  // namespace rtb
