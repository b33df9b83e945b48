// rtb_offline.h -- the offline half of rt_bushing: measured records in,
// identified parameters out. C++17; the forward model is the real-time
// stepper of rt_bushing.h itself, and every gradient is the exact adjoint of
// that discrete stepper.
//
// Top-down: data (Record), parameters (ParamSet), forward model (simulate),
// misfit and its adjoint gradient, identification, validation, output.
#ifndef RTB_OFFLINE_H
#define RTB_OFFLINE_H

#include <stdexcept>
#include <string>
#include <vector>

#include "rt_bushing/rt_bushing.h"

namespace rtb {

// ---------------------------------------------------------------- errors
// Bad user input (file, line and column named in what()). The CLI prints it
// and exits with status 2; nothing is written.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// ---------------------------------------------------------------- records
// One measured (or generated) force/displacement record.
struct Record {
  std::string path;                 // as given by the user
  std::string units;                // the "# units: ..." comment, "" if absent
  std::string sha256;               // of the file bytes, hex ("" if generated)
  std::vector<double> t, x, F;      // time, displacement, force (same length)
  double weight = 1.0;              // per-record weight in the misfit
  std::vector<unsigned char> masked;  // 1: sample excluded from the misfit (empty: none)
};

// CSV: '#' comment lines, a header naming time, displacement, force (any
// order, extra columns ignored), numeric rows. Throws InputError naming file
// and line for: missing file, missing column, non-numeric or non-finite cell,
// unequal row length, non-increasing time, fewer than kMinSamples rows.
constexpr int kMinSamples = 8;
Record read_record_csv(const std::string &path);

// Writes time,displacement,force[,extra columns] with %.17g, atomically.
void write_record_csv(const std::string &path, const std::vector<double> &t,
                      const std::vector<double> &x, const std::vector<double> &F,
                      const std::string &units);

// ---------------------------------------------------------------- files
// Write `content` to `path` via a temporary file in the same directory and
// rename(2): readers never see a partial file and a failure leaves any
// existing file untouched. Throws std::runtime_error on I/O failure.
void write_file_atomic(const std::string &path, const std::string &content);
std::string sha256_hex(const std::string &bytes);
std::string sha256_file(const std::string &path);

// ---------------------------------------------------------------- params
// Parameter JSON: {"model":"rt"|"sts","cells":15,"integrator":"sdirk2"|"be",
//   "params":{"K0":..,"Kpa":..,"Kr":..,"C0":..,"alpha":.., optional
//   extensions: every other field of RTB_PARAM_FIELDS (rt_bushing.h) by its
//   name, e.g. "k3", "maxwell_tau", "backlash", "slack", "spec_k"; STS: "Ff"},
//   optional top-level "smoothing" (eq. (14), 0 = off)}. Throws InputError on
// a missing or non-numeric value, and on a value the library's
// rtb_params_check rejects, naming the field and its rule.
rtb_params read_params_json(const std::string &path);
rtb_params params_from_json_text(const std::string &text, const std::string &origin);
// The "model/cells/integrator/params" part of a parameter file, as JSON text
// (used by identify to build its richer output).
std::string params_to_json_text(const rtb_params &p);

// Identifiable parameters: the fields of kind FIT in RTB_PARAM_FIELDS
// (rt_bushing.h), in struct order: the five of the paper, then the extensions.
#define RTB_PARAM_ID_FIT(name) P_##name,
#define RTB_PARAM_ID_SETTING(name)
#define RTB_PARAM_ID(name, rule, kind, unit, text) RTB_PARAM_ID_##kind(name)
enum ParamId { RTB_PARAM_FIELDS(RTB_PARAM_ID) P_COUNT };
#undef RTB_PARAM_ID
#undef RTB_PARAM_ID_FIT
#undef RTB_PARAM_ID_SETTING
const char *param_name(ParamId id);          // "K0", "Kpa", ... as in the JSON
double &param_ref(rtb_params &p, ParamId id);
double param_get(const rtb_params &p, ParamId id);

// ---------------------------------------------------------------- forward
// How the element reaches a record's first displacement x[0] from rest at 0.
enum class StartMode {
  automatic,  // hold when |x[0]| is beyond 5% of the record's largest |x|, else ramp
  ramp,       // a linear ramp 0 -> x[0] just before the record (section 5.5's first loading)
  hold        // the ramp, then x[0] held ~1e5 s: a specimen preloaded and left to relax
};
const char *start_mode_name(StartMode m);  // "auto", "ramp", "hold"

struct SimOptions {
  double ramp_time = 0.0;   // ramp in linearly from rest to x[0] over this
                            // time before the record (<= 0: automatic)
  StartMode start = StartMode::automatic;
  double tol = 0.0;         // Newton tolerance of the stepper (rtb_settings.tol);
                            // 0: the library default (RTB_TOL_DEFAULT, 1e-8),
                            // i.e. exactly what a controller passing NULL
                            // settings runs -- except in fits (below)
};
// Newton tolerance of every fit and its sensitivities (misfit, adjoint,
// tangent sweeps, the diagnosis) when SimOptions::tol is 0. Tighter than the
// real-time default: the adjoint is the exact derivative of the converged
// discrete map, and the identification resolves parameters to ~1e-13 only
// when the forward map is resolved to ~1e-12 (docs/benchmarks.md, session
// 21). The forces differ from the controller's by ~1e-9 of the peak.
constexpr double kFitTol = 1e-12;
inline double fit_tol(const SimOptions &sim) { return sim.tol > 0.0 ? sim.tol : kFitTol; }
// Force predicted by the stepper for the record's displacement and time grid.
// Throws std::runtime_error if the stepper reports an error.
std::vector<double> simulate_force(const rtb_params &p, const Record &rec,
                                   const SimOptions &opt = SimOptions());

}  // namespace rtb

#endif
