// smoothing_test.cpp -- the optional sigmoid smoothing of eq. (14)
// (rtb_params.smoothing, [1/velocity], 0 = off) in the real-time library:
// validation, the smoothed law and its inverse, finite converged steps with
// an exact tangent dF/dx, and convergence to eq. (1) as s grows. The adjoint
// side (Table 1's trend) is in adjoint_test.cpp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>
#include <vector>

#include "dashpot_law.h"
#include "physics_helpers.h"
#include "test_numbers.h"

namespace {

using rtbtest::kPi;


// Forces of the stepper for x = 1 mm sin(2 pi t) + 0.1 mm sin(20 pi t) over
// `seconds`; every step must succeed (RTB_OK: converged) with a finite force.
std::vector<double> run(const rtb_params &p, double dt, double seconds) {
  rtb_state s;
  EXPECT_EQ(rtb_state_init(&s, &p, 0.0), RTB_OK);
  std::vector<double> F;
  const int n = (int)std::lround(seconds / dt);
  for (int i = 1; i <= n; ++i) {
    const double t = i * dt;
    const double x = std::sin(2 * kPi * t) + 0.1 * std::sin(20 * kPi * t);
    double f = kNaN;
    const rtb_status st = rtb_step(&s, &p, nullptr, x, dt, &f);
    EXPECT_EQ(st, RTB_OK) << "s " << p.smoothing << " step " << i;
    EXPECT_TRUE(std::isfinite(f)) << "s " << p.smoothing << " step " << i;
    F.push_back(f);
  }
  return F;
}

// max |a - b| / max |b|.
double rel_diff(const std::vector<double> &a, const std::vector<double> &b) {
  double d = 0.0, m = 0.0;
  for (size_t i = 0; i < a.size(); ++i) {
    d = std::fmax(d, std::fabs(a[i] - b[i]));
    m = std::fmax(m, std::fabs(b[i]));
  }
  return d / m;
}

}  // namespace

TEST(Smoothing, AbiSlotAndValidation) {
  // smoothing took reserved[0] (the softening spring the next two; ABI 3's
  // extensions the next seven): same size, same offsets of everything else.
  static_assert(offsetof(rtb_params, smoothing) + 3 * sizeof(rtb_real) ==
                    offsetof(rtb_params, slack),
                "smoothing, sat_force, sat_disp sit just before the ABI 3 fields");
  static_assert(sizeof(rtb_params) == 4 * sizeof(int32_t) + 30 * sizeof(rtb_real),
                "rtb_params keeps its size");
  EXPECT_GE(RTB_ABI_VERSION, 3);  // the slots were taken in ABI 2 and 3
  for (int model : {RTB_MODEL_RT, RTB_MODEL_STS}) {
    rtb_params p;
    ASSERT_EQ(rtb_params_default(&p, model), RTB_OK);
    EXPECT_EQ(p.smoothing, 0.0);  // off by default
    for (double s : {0.0, 1e-300, 1.0, 1e300}) {
      p.smoothing = s;
      EXPECT_EQ(rtb_params_validate(&p), RTB_OK) << s;
    }
    for (double s : {-1.0, -1e-300}) {
      p.smoothing = s;
      EXPECT_EQ(rtb_params_validate(&p), RTB_ERR_PARAM_RANGE) << s;
    }
    for (double s : {kNaN, kInf, -kInf}) {
      p.smoothing = s;
      EXPECT_EQ(rtb_params_validate(&p), RTB_ERR_PARAM_NONFINITE) << s;
    }
    // A bad value is rejected by the step without touching the state.
    rtb_params good;
    rtb_params_default(&good, model);
    rtb_state s;
    ASSERT_EQ(rtb_state_init(&s, &good, 0.0), RTB_OK);
    const rtb_state before = s;
    p.smoothing = -1.0;
    double f = 7.0;
    EXPECT_EQ(rtb_step(&s, &p, nullptr, 0.1, 1e-3, &f), RTB_ERR_PARAM_RANGE);
    EXPECT_EQ(std::memcmp(&s, &before, sizeof s), 0);
    EXPECT_EQ(f, 7.0);
  }
}

TEST(Smoothing, StsIgnoresIt) {
  rtb_params p = rtbtest::paper_params(RTB_MODEL_STS);
  const std::vector<double> a = run(p, 1e-3, 1.0);
  p.smoothing = 3.0;
  const std::vector<double> b = run(p, 1e-3, 1.0);
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0);
}

TEST(Smoothing, LawIsOddIncreasingWithFiniteSlopeAndExactInverse) {
  const double C0 = 40.0;
  for (double alpha : {RTB_ALPHA_MIN, 0.2, 0.4, 0.9}) {
    for (double s : {0.01, 1.0, 100.0, 1e6}) {
      // Slope at 0: C0 (s/2)^(1-alpha) (ln 2)^alpha, finite.
      double d0 = 0.0;
      EXPECT_EQ(rtb_slaw_force(0.0, C0, alpha, s, &d0), 0.0);
      EXPECT_NEAR(d0, C0 * std::pow(s / 2, 1 - alpha) * std::pow(std::log(2.0), alpha), 1e-12 * d0);
      double prev = -kInf;
      for (double lv = -12; lv <= 12; lv += 0.25) {
        for (double sign : {-1.0, 1.0}) {
          const double v = sign * std::pow(10.0, lv);
          double d = kNaN;
          const double f = rtb_slaw_force(v, C0, alpha, s, &d);
          ASSERT_TRUE(std::isfinite(f) && std::isfinite(d) && d > 0.0) << v;
          EXPECT_EQ(rtb_slaw_force(-v, C0, alpha, s, nullptr), -f);  // odd
          // Inverse, from a useless guess: force error at rounding level.
          const double vi = rtb_slaw_velocity(f, C0, alpha, s, -v);
          EXPECT_NEAR(rtb_slaw_force(vi, C0, alpha, s, nullptr), f, 64 * DBL_EPSILON * std::fabs(f))
              << "alpha " << alpha << " s " << s << " v " << v;
          // Slope against a central difference.
          const double h = 1e-6 * std::fmax(std::fabs(v), 1.0 / s);
          const double fd = (rtb_slaw_force(v + h, C0, alpha, s, nullptr) -
                             rtb_slaw_force(v - h, C0, alpha, s, nullptr)) / (2 * h);
          EXPECT_NEAR(d, fd, 1e-5 * d) << "alpha " << alpha << " s " << s << " v " << v;
        }
        const double f = rtb_slaw_force(std::pow(10.0, lv), C0, alpha, s, nullptr);
        EXPECT_GT(f, prev);  // increasing
        prev = f;
      }
    }
  }
  // psi_s -> psi: at fixed |v| the relative error falls (like exp(-s|v|)).
  double last = kInf;
  for (double s : {1.0, 10.0, 100.0, 1e3, 1e4}) {
    const double e = std::fabs(rtb_slaw_force(1.0, C0, 0.2, s, nullptr) / rtb_law_force(1.0, C0, 0.2) - 1);
    EXPECT_LE(e, last);  // 0 once s|v| >= RTB_SLAW_SHARP: eq. (1) to rounding
    EXPECT_LT(e, 2.0 / s);
    last = e;
  }
}

TEST(Smoothing, ExtremeValuesNeverNaN) {
  // Far outside the useful range (s from 1e-300 to 1e300, dt from RTB_DT_MIN
  // to RTB_DT_MAX, |x| up to RTB_X_MAX) every call is still a valid input:
  // it must succeed with a finite force and tangent, and the inverse never
  // returns a NaN. The step's work is bounded (RTB_STEP_WORK plus the
  // stage starts of the last response, rt_bushing.h): the extreme smoothings
  // s >= 1e12 need 200-600 Newton sweeps here, far beyond it (measured: 64
  // of their 240 calls give up), the others converge but for 2 (x = 1e12
  // at dt = 1e-9, and x = 0 after it with alpha near 1).
  for (double alpha : {RTB_ALPHA_MIN, 0.5, std::nextafter(1.0, 0.0)})
    for (double s : {1e-300, 1e-12, 1e12, 1e300})
      for (double f : {0.0, 1e-300, 1e-3, 1.0, 1e6, 1e300}) {
        const double v = rtb_slaw_velocity(f, 40.0, alpha, s, kNaN);
        EXPECT_FALSE(std::isnan(v)) << alpha << " " << s << " " << f;
        EXPECT_GE(v, 0.0);
        double d;
        EXPECT_FALSE(std::isnan(rtb_slaw_force(v, 40.0, alpha, s, &d)));
        EXPECT_FALSE(std::isnan(d));
      }
  int not_converged_moderate = 0;
  for (int integrator : {RTB_INTEGRATOR_SDIRK2, RTB_INTEGRATOR_BE})
    for (double alpha : {RTB_ALPHA_MIN, 0.5, std::nextafter(1.0, 0.0)})
      for (double s : {1e-300, 1e-12, 1e12, 1e300})
        for (double dt : {RTB_DT_MIN, 1e-3, RTB_DT_MAX}) {
          rtb_params p = rtbtest::paper_params(RTB_MODEL_RT, RTB_DEFAULT_CELLS, integrator);
          p.alpha = alpha;
          p.smoothing = s;
          rtb_state st;
          ASSERT_EQ(rtb_state_init(&st, &p, 0.0), RTB_OK);
          const int sweep = 3 * p.cells; /* one smoothed sweep, RTB_SLAW_UNIT 3 */
          const int slack = 6 * sweep; /* the last response's stage starts */
          for (double x : {1e-9, 1.0, -1e6, 1e12, 0.0}) {
            double F = 0.0, dF = 0.0;
            rtb_state tr;
            rtb_step_info info;
            const rtb_status r = rtb_evaluate_ex(&st, &p, nullptr, x, dt, &tr, &F, &dF, &info);
            ASSERT_GE(r, 0) << rtb_status_message(r) << ": alpha " << alpha << " s " << s
                            << " dt " << dt << " x " << x;
            EXPECT_LE(info.work, RTB_STEP_WORK + slack);
            not_converged_moderate += r == RTB_NOT_CONVERGED && s < 1e12;
            EXPECT_TRUE(std::isfinite(F) && std::isfinite(dF))
                << "alpha " << alpha << " s " << s << " dt " << dt << " x " << x;
            st = tr;
          }
        }
  EXPECT_LE(not_converged_moderate, 2);
}

// d phi / d alpha at a pair the Newton tolerance left off the curve, with
// the force rounded to 0 or |f| / C0 underflowing while v is not 0: the
// dashpots of a fit whose C0 went to 4e-14 (forces at 1e-15, one exactly 0
// beside v = -1.4e-3). ln(0) made it infinite, and every later sensitivity
// of the record NaN (blindgen backlash_held_s31). It is 0 there, as at
// f = 0 on the curve, and unchanged elsewhere.
TEST(DashpotLaw, AlphaSensitivityIsFiniteWhereTheForceRoundsToZero) {
  const double alpha = 0.999999999;
  for (double s : {0.0, 1e3}) {
    EXPECT_EQ(rtb_dashpot_dv_dalpha(0.0, -1.4e-3, 4e-14, alpha, s), 0.0) << s;
    EXPECT_EQ(rtb_dashpot_dv_dalpha(-0.0, 1.4e-3, 4e-14, alpha, s), 0.0) << s;
  }
  EXPECT_EQ(rtb_law_dv_dalpha(1e-320, 2e-3, 1e10, 0.5), 0.0);  // |f| / C0 underflows
  const double f = 3.0, C0 = 40.0, a = 0.3, v = rtb_law_velocity(f, C0, a);
  EXPECT_DOUBLE_EQ(rtb_law_dv_dalpha(f, v, C0, a), -v * std::log(f / C0) / (a * a));
}

class SmoothingSteps : public ::testing::TestWithParam<int> {};

TEST_P(SmoothingSteps, ConvergeAndTendToUnsmoothed) {
  rtb_params p = rtbtest::paper_params(RTB_MODEL_RT, RTB_DEFAULT_CELLS, GetParam());
  const std::vector<double> F0 = run(p, 1e-3, 2.0);
  // s in s/mm; the cell speeds here are up to ~10 mm/s, so s = 0.1 smooths
  // the whole cycle and s = 1e4 only |v| < 1e-4 mm/s.
  double last = kInf;
  for (double s : {0.1, 1.0, 10.0, 100.0, 1e3, 1e4}) {
    p.smoothing = s;
    const double d = rel_diff(run(p, 1e-3, 2.0), F0);
    EXPECT_LT(d, last) << "s " << s;
    last = d;
  }
  EXPECT_LT(last, 1e-5);  // s = 1e4
  // In time: the smoothed solution converges as dt -> 0 (a 1e-5 s reference).
  p.smoothing = 1.0;
  const std::vector<double> ref = run(p, 1e-5, 0.5);
  double prev = kInf;
  for (double dt : {1e-2, 1e-3, 1e-4}) {
    const std::vector<double> F = run(p, dt, 0.5);
    std::vector<double> sub;
    const size_t stride = (size_t)std::lround(dt / 1e-5);
    for (size_t i = 0; i < F.size(); ++i) sub.push_back(ref[(i + 1) * stride - 1]);
    const double e = rel_diff(F, sub);
    EXPECT_LT(e, 0.5 * prev) << "dt " << dt;
    prev = e;
  }
  EXPECT_LT(prev, 1e-3);
}

TEST_P(SmoothingSteps, TangentMatchesFiniteDifference) {
  // rtb_evaluate's analytic dF/dx uses the smoothed law's derivative too.
  for (double s : {0.1, 10.0, 1e3}) {
    rtb_params p = rtbtest::paper_params(RTB_MODEL_RT, RTB_DEFAULT_CELLS, GetParam());
    p.smoothing = s;
    rtb_state st;
    ASSERT_EQ(rtb_state_init(&st, &p, 0.0), RTB_OK);
    const double dt = 1e-3;
    for (int i = 1; i <= 1000; ++i) {
      const double x = std::sin(2 * kPi * i * dt) + 0.1 * std::sin(20 * kPi * i * dt);
      rtb_state tr;
      double F, dF;
      ASSERT_EQ(rtb_evaluate(&st, &p, nullptr, x, dt, &tr, &F, &dF), RTB_OK);
      if (i % 50 == 0) {
        const double h = 1e-6;
        rtb_state t2;
        double Fp, Fm;
        rtb_settings set;
        rtb_settings_default(&set);
        set.tol = 1e-15;
        ASSERT_GE(rtb_evaluate(&st, &p, &set, x + h, dt, &t2, &Fp, nullptr), 0);
        ASSERT_GE(rtb_evaluate(&st, &p, &set, x - h, dt, &t2, &Fm, nullptr), 0);
        EXPECT_NEAR(dF, (Fp - Fm) / (2 * h), 1e-6 * dF) << "s " << s << " step " << i;
      }
      st = tr;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Both, SmoothingSteps,
                         ::testing::Values((int)RTB_INTEGRATOR_SDIRK2, (int)RTB_INTEGRATOR_BE));

#ifdef RTB_HAVE_OFFLINE
#include <sys/wait.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "offline/io/header_writer.h"
#include "offline/io/params_json.h"

// Parameter JSON: top-level "smoothing" like "integrator"; absent = 0, and
// not written when 0 (unsmoothed files are unchanged).
TEST(SmoothingIo, ParamsJson) {
  const std::string core = "\"params\":{\"K0\":1000,\"Kpa\":800,\"Kr\":3000,\"C0\":40,\"alpha\":0.2}";
  const rtb_params a = rtb::params_from_json_text("{\"model\":\"rt\"," + core + "}", "a.json");
  EXPECT_EQ(a.smoothing, 0.0);
  EXPECT_EQ(rtb::params_to_json_text(a).find("smoothing"), std::string::npos);
  const rtb_params b =
      rtb::params_from_json_text("{\"model\":\"rt\",\"smoothing\":0.25," + core + "}", "b.json");
  EXPECT_EQ(b.smoothing, 0.25);
  const rtb_params c = rtb::params_from_json_text(rtb::params_to_json_text(b), "c.json");
  EXPECT_EQ(std::memcmp(&b, &c, sizeof b), 0) << rtb::params_to_json_text(b);
  for (const char *bad : {"-1", "\"1\"", "null"}) {
    try {
      rtb::params_from_json_text(std::string("{\"model\":\"rt\",\"smoothing\":") + bad + "," + core + "}",
                                 "bad.json");
      ADD_FAILURE() << bad;
    } catch (const rtb::InputError &e) {
      EXPECT_NE(std::string(e.what()).find("smoothing"), std::string::npos) << e.what();
    }
  }
}

// The generated header carries the setting, so a host runs the same model.
TEST(SmoothingIo, HeaderCarriesTheField) {
  rtb_params p = rtbtest::paper_params(RTB_MODEL_RT);
  rtb::HeaderInfo hi;
  hi.name = "smoothed_bushing";
  const std::string h0 = rtb::emit_parameter_header(p, hi);
  EXPECT_NE(h0.find("0x0p+0, /* smoothing = 0"), std::string::npos) << h0;
  EXPECT_EQ(h0.find("eq. (14) smoothing s ="), std::string::npos);
  p.smoothing = 0.5;
  const std::string h1 = rtb::emit_parameter_header(p, hi);
  EXPECT_NE(h1.find("0x1p-1, /* smoothing = 0.5"), std::string::npos) << h1;
  EXPECT_NE(h1.find("eq. (14) smoothing s = 0.5"), std::string::npos) << h1;
}

#ifdef RTB_CLI_PATH
namespace {
int run_cli(const std::string &args, std::string *out) {
  FILE *f = popen((std::string(RTB_CLI_PATH) + " " + args + " 2>&1").c_str(), "r");
  if (!f) return -1;
  char buf[4096];
  size_t n;
  while ((n = std::fread(buf, 1, sizeof buf, f)) > 0) out->append(buf, n);
  const int st = pclose(f);
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}
}  // namespace

TEST(SmoothingIo, CliOption) {
  for (const char *cmd : {"gradcheck", "identify"}) {
    std::string out;
    EXPECT_EQ(run_cli(std::string(cmd) + " --help", &out), 0);
    EXPECT_NE(out.find("--smoothing S"), std::string::npos) << out;
  }
  // A negative value is a usage error naming the option.
  const std::string dir = ::testing::TempDir();
  {
    std::ofstream pj(dir + "/smoothing_cli.json");
    pj << rtb::params_to_json_text(rtbtest::paper_params(RTB_MODEL_RT));
    std::ofstream csv(dir + "/smoothing_cli.csv");
    csv << "time,displacement,force\n";
    for (int i = 0; i < 20; ++i) csv << i * 1e-3 << "," << 0.01 * i << "," << 10.0 * i << "\n";
  }
  std::string out;
  EXPECT_EQ(run_cli("gradcheck --params " + dir + "/smoothing_cli.json --data " + dir +
                        "/smoothing_cli.csv --smoothing=-1",
                    &out),
            2)
      << out;
  EXPECT_NE(out.find("--smoothing"), std::string::npos) << out;
}
#endif
#endif  // RTB_HAVE_OFFLINE
