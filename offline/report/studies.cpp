// studies.cpp -- the two real-data studies of `rtb report` (issue #5): which
// records, which preprocessing, and why. File names are those of
// ../shared/data (see its README for provenance and quirks).
#include "report/study.h"

namespace rtb {

StudySpec friction_damper_study() {
  StudySpec s;
  s.name = "friction_damper";
  s.title = "Friction damper with backlash (BRFD, ARTS-Laboratory data)";
  s.length_unit = "in";
  s.force_unit = "kip";
  s.intro =
      "A banded rotary friction device: almost no elastic restoring force, rate-independent "
      "friction (the RT dashpot exponent alpha is pushed to its floor) and a clearance at every "
      "reversal. **Fit records**: three dataset-2 sine tests at 36 lb band tension spanning the "
      "frequencies (0.25, 0.5, 1 Hz) and amplitudes (1.5, 1, 0.5 in). 36 lb because the "
      "earthquake records' negative sliding force (-3.3 to -3.9 kip) matches the 36 lb sine "
      "tests, not the 30 lb ones (data README); 2 Hz tests are left out (the most disturbed by "
      "rig oscillation). **Validation**: the four earthquake displacement records. **Low-pass** "
      "20 Hz, zero phase: removes the 40-56 Hz rig oscillation riding on the sliding force "
      "(0.05-0.6 kip rms), far above the 0.25-1 Hz test content. **Decimated** 5x after the "
      "low-pass (1024 -> 205 Hz, Nyquist 102 Hz): the same fitted model and errors as at 1024 Hz "
      "(the test `RealData.FrictionDamper*` compares), in a fifth of the time.";
  s.fit_files = {"friction_damper/d2_sine_0.25Hz_1.5in_36lb.csv",
                 "friction_damper/d2_sine_0.5Hz_1in_36lb.csv",
                 "friction_damper/d2_sine_1Hz_0.5in_36lb.csv"};
  s.validation_files = {"friction_damper/d3_quake_ImperialValleyDBE.csv",
                        "friction_damper/d3_quake_ImperialValleyMCE.csv",
                        "friction_damper/d3_quake_KocaeliDBE.csv",
                        "friction_damper/d3_quake_KocaeliMCE.csv"};
  s.pre.lowpass_hz = 20.0;
  s.pre.decimate = 5;
  s.second_stage = {"offset", "asymmetry", "viscous"};
  s.validation_bound = 0.9;
  return s;
}

StudySpec vhb4910_study() {
  StudySpec s;
  s.name = "vhb4910";
  s.title = "VHB 4910 elastomer strip (uniaxial tension)";
  s.length_unit = "mm";
  s.force_unit = "N";
  s.intro =
      "An acrylic elastomer strip in tension: strongly rate-dependent, an elastic response that "
      "softens then stiffens with stretch, relaxation close to a power law over four decades of "
      "time, and a strip that goes slack (force about 0) near the end of unloading. **Fit "
      "records**: all 16 loading-unloading tests (rates 0.01-0.05 1/s, stretch 1.5-3.0) at once. "
      "**Validation**: the relaxation tests inside the identified stretch range (1.5-3.0); their "
      "0.25 1/s ramps are 5x faster than any fit record. **Masks**: the first 0.15 s of every "
      "record (ramp-start spike) and 0.6 s after every displacement reversal (the reversal dip "
      "of the load-unload tests, the end-of-ramp dip and displacement overshoot of the "
      "relaxation tests): machine transients, not material response.";
  const char *rates[] = {"0.01", "0.03", "0.05"};
  const char *stretches[] = {"1.5", "2.0", "2.5", "3.0"};
  for (const char *st : stretches)
    for (const char *r : rates) {
      const std::string base = std::string("vhb4910/loadunload_rate") + r + "_stretch" + st;
      s.fit_files.push_back(base + "_run1.csv");
    }
  s.fit_files.push_back("vhb4910/loadunload_rate0.03_stretch1.5_run2.csv");
  s.fit_files.push_back("vhb4910/loadunload_rate0.03_stretch2.0_run2.csv");
  s.fit_files.push_back("vhb4910/loadunload_rate0.05_stretch1.5_run2.csv");
  s.fit_files.push_back("vhb4910/loadunload_rate0.05_stretch2.0_run2.csv");
  for (const char *st : stretches)
    s.validation_files.push_back(std::string("vhb4910/relax_stretch") + st + ".csv");
  s.pre.masks = {TimeWindow{0.0, 0.15}};
  s.pre.mask_after_reversal = 0.6;
  s.log_time_validation = true;
  s.second_stage = {"softening", "cubic_stiffness", "maxwell"};
  s.validation_bound = 0.6;
  return s;
}

}  // namespace rtb
