// DFG 2D-2's periodic statistics (dfg_benchmark.hpp, dfg_periodic_statistics) on a synthetic
// history with known answers: a lift CL = m + A sin(2 pi f t) and a pressure difference
// dp = c + B sin(2 pi f t + phi), sampled with an uneven step. The lift peaks at 2 pi f t0 = pi/2
// (mod 2 pi), so dp(t0 + 1/(2f)) = c + B sin(3 pi / 2 + phi) = c - B cos(phi).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cfd/validation/dfg_benchmark.hpp"

namespace finverse::cfd {
namespace {

DfgResult synthetic(double t_end, double f, double phi) {
  DfgResult r;
  const double w = 2 * std::numbers::pi * f;
  double t = 0;
  for (int n = 0; t < t_end; ++n) {
    t = std::min(t_end, t + (n % 3 == 0 ? 4e-4 : 3e-4));  // uneven steps, as the adaptive step
    DfgSample s;
    s.t = t;
    s.cl = -0.017 + 1.0 * std::sin(w * t);
    s.cd = 3.2 + 0.02 * std::sin(2 * w * t);
    s.dp = 2.46 + 0.04 * std::sin(w * t + phi);
    r.history.push_back(s);
  }
  return r;
}

TEST(DfgPeriodicStatistics, StrouhalMaximaAndPressureDifferenceAtHalfPeriod) {
  const double f = 3.0, phi = 0.7;
  DfgResult r = synthetic(10.0, f, phi);
  dfg_periodic_statistics(r, 3.0);
  EXPECT_NEAR(r.st, f * 0.1, 1e-6);  // St = f D / Ubar, D = 0.1, Ubar = 1
  EXPECT_NEAR(r.cl_max, 0.983, 1e-6);
  EXPECT_NEAR(r.cl_min, -1.017, 1e-6);
  EXPECT_NEAR(r.cd_max, 3.22, 1e-6);
  EXPECT_EQ(r.periods, 7);  // up-crossings at 7 1/3 ... 9 2/3 s
  ASSERT_TRUE(std::isfinite(r.dp_half_period));
  // The parabola's vertex to O(dt^2) relative to the period, dp interpolated to O(dt^2).
  EXPECT_NEAR(r.dp_half_period, 2.46 - 0.04 * std::cos(phi), 1e-6);
  // t0 is a lift maximum inside the window whose half period ends by t_end.
  EXPECT_NEAR(std::sin(2 * std::numbers::pi * f * r.t_lift_peak), 1.0, 1e-8);
  EXPECT_GE(r.t_lift_peak, 7.0);
  EXPECT_LE(r.t_lift_peak + 0.5 / f, 10.0);
}

// A window without a full lift period gives no Strouhal number and no pressure difference.
TEST(DfgPeriodicStatistics, NoPeriodNoPressureDifference) {
  DfgResult r = synthetic(1.0, 0.2, 0.0);
  dfg_periodic_statistics(r, 0.4);
  EXPECT_EQ(r.periods, 0);
  EXPECT_FALSE(std::isfinite(r.dp_half_period));
}

}  // namespace
}  // namespace finverse::cfd
