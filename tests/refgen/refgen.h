// refgen.h -- an independent reference generator of test-rig records for the
// RT bushing model (issue #10, item 8).
//
// It shares no code with the element (rt_bushing/) or the offline tool
// (offline/): only the C++ standard library. Its purpose is to be a yardstick
// made with other conventions than the element's:
//  * the RT model of Puel, Bourgeteau & Aubry (2013), eq. (2) and (11), is
//    integrated in its primal form y' = phi(b(t) - K y), phi the inverse of
//    the dashpot law eq. (1), by a 2-stage Radau IIA scheme (order 3,
//    L-stable) with full Newton at a fine internal step (substeps per sample),
//    where the element uses SDIRK2 in dashpot-force variables;
//  * its own effect definitions (see effects.cpp), some deliberately unlike
//    the element's (smooth asymmetry, Mullins on the whole K0 path, a
//    held-end clearance, slack, a relaxation spectrum, friction asymmetry);
//  * a measurement chain: servo low-pass between command and specimen, noise
//    on displacement and force, force-channel delay, offset and mains hum.
// Units: mm, N, s (stiffness N/mm, C0 N (s/mm)^alpha, mass t = N s^2/mm).
#ifndef RTB_TESTS_REFGEN_H
#define RTB_TESTS_REFGEN_H

#include <string>
#include <vector>

namespace refgen {

// ------------------------------------------------------------------ specimen
struct Branch {
  double k = 0.0;    // spring of a Maxwell branch [N/mm]
  double tau = 0.0;  // its relaxation time = dashpot / k [s]
};

// Clearance between actuator and specimen (half_gap per side).
enum class Gap {
  none,
  floating,  // the specimen end floats free in the gap: bushing force 0
  held       // the specimen end stays where contact was lost (play operator)
};

struct Specimen {
  // RT core, eq. (2): N cells (spring Kr || dashpot C0 sign(v)|v|^alpha)
  // chained between Kpa and ground; K0 in parallel. F = K0 xb + Kpa (xb - y1).
  double K0 = 1000, Kpa = 800, Kr = 3000, C0 = 40, alpha = 0.2;
  int N = 15;
  double c0_neg_ratio = 1.0;  // dashpot level for negative velocity / C0 (friction asymmetry)
  double cubic = 0.0;         // F += cubic xb^3                         [N/mm^3]
  double asym = 0.0;          // F += asym xb tanh(xb / asym_width)      [N/mm]
  double asym_width = 0.05;   //                                         [mm]
  double soft_k = 0.0;        // F += soft_k xb / sqrt(1 + (xb/soft_x)^2) [N/mm]
  double soft_x = 1.0;        //                                         [mm]
  double mullins = 0.0;       // fraction of the K0 path lost below the prior max |xb|
  // Other definitions of the same effects (another lab's conventions):
  double quad = 0.0;          // F += quad xb^2: asymmetry as a quadratic term  [N/mm^2]
  double quintic = 0.0;       // F += quintic xb^5: stiffening of fifth order    [N/mm^5]
  bool soft_tanh = false;     // softening as soft_k soft_x tanh(xb/soft_x) instead
  bool mullins_erf = false;   // Mullins loss mu erf(2 (1 - (xb/xb_max)^2)): nearly
                              // uniform below the prior max (Ogden-Roxburgh-like)
  std::vector<Branch> branches;  // Maxwell branches in parallel on xb
  double viscous = 0.0;       // F += viscous xb'                        [N s/mm]
  double mass = 0.0;          // actuator-side fixture mass: F += mass x'' [t]
  Gap gap = Gap::none;
  double half_gap = 0.0;      // clearance per side                      [mm]
  bool slack = false;         // cannot push: end floats free when force would be < 0
  double drift_rate = 0.0;    // stiffnesses scale by (1 + drift_rate t) [1/s]
};

// Static force for a displacement held forever (plain RT): every dashpot has
// relaxed, the N springs Kr are in series with Kpa.
double static_force(const Specimen &s, double x);

// ------------------------------------------------------------------ commanded signal
enum class Kind { triangle, sine, step, multisine, random };

struct Tone {
  double amp = 0.0, hz = 0.0, phase = 0.0;
};

struct Command {
  Kind kind = Kind::sine;
  double amp = 1.0;        // [mm] (random: peak)
  double hz = 1.0;         // triangle, sine
  double duration = 8.0;   // [s]
  bool tension = false;    // one-sided (0 .. 2 amp) for specimens that cannot push
  double t_up = 0.3, ramp_time = 0.1, t_down = 4.0;  // step: up at t_up, down at t_down
  std::vector<Tone> tones;                       // multisine, random
  double t_strong = 1.0, t_decay = 5.0;          // random: envelope build-up end, decay start
  double value(double t) const;  // [mm]
  double slope(double t) const;  // [mm/s]
};

// ------------------------------------------------------------------ measurement chain
struct Chain {
  int servo_order = 2;       // 1 or 2: low-pass between command and actuator
  double servo_hz = 40.0;    // its corner frequency
  double servo_zeta = 0.7;   // damping ratio (order 2)
  double dt = 1e-3;          // sample interval [s]
  int substeps = 10;         // fine integration steps per sample
  double force_noise = 0.005;  // force noise std / max |F| of the record
  double disp_noise = 0.003;   // displacement noise std / max |x| of the record
  double delay = 0.0;        // force channel lag [s]
  double disp_delay = 0.0;   // displacement channel lag [s] (the force then leads)
  double force_lowpass_hz = 0.0;  // first-order low-pass of the force channel (amplifier) [Hz], 0 = off
  double offset = 0.0;       // force sensor zero error [N]
  double zero_drift = 0.0;   // the force zero moves linearly from 0 to this over the record [N]
  double hum = 0.0;          // 50 Hz mains hum amplitude on the force [N] (+30% at 150 Hz)
  double hum_phase = 0.0;
  double preload = 0.0;      // static actuator position the records oscillate about [mm];
                             // the specimen has been held there (relaxed) before t = 0
  double force_sign = 1.0;   // -1: a compression-positive load cell (force recorded negated)
  double noise_hz = 0.0;     // > 0: the noise on both channels is band-limited (an
                             // acquisition's anti-alias filter): a first-order low-pass
                             // at this corner, same standard deviation [Hz]; 0: white
  double clip = 0.0;         // load-cell saturation: |F| recorded at most this [N] (0 = off)
  double spikes = 0.0;       // acquisition glitches: size of isolated outlier samples [N]
  double spike_rate = 0.0;   // their probability per sample
  unsigned long long seed = 1;  // noise stream
};

struct Samples {
  std::vector<double> t, x, F;  // recorded (with noise)
  std::vector<double> F_clean;  // recorded force without noise
  std::vector<double> x_true;   // actuator position without noise
};

// Integrates the specimen driven by the servo-smoothed command at dt/substeps
// and samples it through the chain. Throws std::runtime_error if the
// integration cannot converge even at 1/2^16 of the fine step.
Samples run_record(const Specimen &s, const Command &c, const Chain &chain);

// ------------------------------------------------------------------ scenarios
// Effect words: the diagnosis vocabulary (cubic_stiffness, asymmetry, maxwell,
// viscous, backlash = floating end, backlash_held, mullins, delay, inertia,
// offset, softening), the new words (slack, relaxation_spectrum,
// friction_asymmetry) and out of vocabulary (hum, drift, temperature); "none"
// is plain RT.
const std::vector<std::string> &effect_names();
// The diagnosis word the effect should be named by ("backlash" for both
// clearances; "unexplained" for hum, drift and temperature).
std::string expected_word(const std::string &effect);

struct RecordSpec {
  std::string name;  // file stem, e.g. fit_triangle
  bool holdout = false;
  Command cmd;
  double stiffness = 1.0;  // the specimen's force laws scale by this in this record
                           // (a temperature that differs between tests)
};

struct Scenario {
  std::vector<std::string> effects;
  unsigned seed = 1;
  Specimen specimen;
  Chain chain;
  double amplitude = 1.0;  // reference displacement amplitude A [mm]
  int column_style = 0;    // CSV header convention (see csv_out.cpp)
  std::vector<RecordSpec> records;
};

// Randomized per seed: RT parameters, chain conventions, record set
// (fit: slow triangle, 1 and 5 Hz sines, ramp-and-hold, multi-sine;
// held out: a 15-30 Hz sine and an earthquake-like record), effects sized to
// be clearly visible. Throws std::invalid_argument for an unknown effect or an
// unsupported combination.
Scenario make_scenario(const std::vector<std::string> &effects, unsigned seed,
                       double duration = 8.0);

// Record i of the scenario: its own noise stream (seed 100 sc.seed + i) and
// the specimen at the record's stiffness. Throws as run_record.
Samples run_scenario_record(const Scenario &sc, size_t i);

// ------------------------------------------------------------------ output
// Writes one record as CSV in the scenario's column convention (temp file +
// rename: no partial file). Throws std::runtime_error on I/O failure.
void write_record_csv(const std::string &path, const Samples &r, int column_style);
// Truth and per-record noise floor as JSON (temp file + rename).
void write_truth_json(const std::string &path, const Scenario &sc,
                      const std::vector<Samples> &records);
// The force-noise floor of eq. (27): the relative error sqrt(int (F_clean -
// F)^2 / int F^2) a perfect model would make on these records (uniform grids,
// so plain sums). Displacement noise adds to it through the stiffness.
double noise_floor(const std::vector<const Samples *> &recs);

}  // namespace refgen

#endif
