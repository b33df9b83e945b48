// single_precision_test.cpp -- accuracy of the single-precision build
// (RTB_SINGLE, rtb_real = float; CMake target rt_bushing_float) against this
// double build, on the standard input of tests/single_client.c: section 3.4
// set (N = 15, SDIRK2), 300 steps of 1 ms of x = 1 mm sin(2 pi 10 Hz t) +
// 0.3 mm sin(2 pi 37 Hz t), the same float-rounded x fed to both.
// Figure: max |F_float - F_double| / max |F_double|, printed as "[single]".
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "rt_bushing/rt_bushing.h"

#ifdef RTB_SINGLE_CLIENT_PATH
TEST(SinglePrecision, ForcesMatchDoubleBuild) {
  FILE *pipe = popen(RTB_SINGLE_CLIENT_PATH, "r");
  ASSERT_NE(pipe, nullptr);
  char name[16] = {0};
  int bytes = 0;
  ASSERT_EQ(std::fscanf(pipe, "scalar %15s %d", name, &bytes), 2);
  std::vector<double> xs, Fs;
  std::vector<int> status;
  double x, F;
  int st;
  while (std::fscanf(pipe, "%lf %lf %d", &x, &F, &st) == 3) {
    xs.push_back(x);
    Fs.push_back(F);
    status.push_back(st);
  }
  ASSERT_EQ(pclose(pipe), 0);
  EXPECT_EQ(std::string(name), "float");
  EXPECT_EQ(bytes, 4);
  ASSERT_EQ(xs.size(), 300u);

  rtb_params p;
  rtb_state s;
  ASSERT_EQ(rtb_params_default(&p, RTB_MODEL_RT), RTB_OK);
  ASSERT_EQ(rtb_state_init(&s, &p, 0.0), RTB_OK);
  double dev = 0.0, peak = 0.0;
  for (size_t i = 0; i < xs.size(); ++i) {
    double Fd;
    ASSERT_EQ(rtb_step(&s, &p, nullptr, xs[i], 1e-3, &Fd), RTB_OK);
    EXPECT_GE(status[i], 0) << "step " << i;
    dev = std::max(dev, std::fabs(Fs[i] - Fd));
    peak = std::max(peak, std::fabs(Fd));
  }
  std::printf("[single] float vs double build, N=15 SDIRK2, 300 steps of 1 ms: max |dF| = %.3g N, "
              "peak %.1f N, relative %.2e\n", dev, peak, dev / peak);
  // Float rounding is 6e-8; the bound leaves a margin over the measured figure
  // (README) while failing on any real loss (a double-only path would not
  // even be reached, a wrong tolerance would show as 1e-3 or worse).
  EXPECT_LT(dev / peak, 1e-5);
  EXPECT_GT(dev, 0.0);  // it is really a different build
}
#endif
