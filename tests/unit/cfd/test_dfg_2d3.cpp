// DFG 2D-3's driver (dfg_benchmark.hpp, variant 3): the sine inflow 1.5 sin(pi t / 8) from rest,
// run with a fixed time step that lands on t_end exactly (the benchmark compares dp at t = 8), and
// the drag growing with the accelerating inflow. The whole 8 s are the validation case
// (fin-cfd dfg_2d3); here a coarse grid and the first half second.
#include <gtest/gtest.h>

#include <cmath>

#include "cfd/validation/dfg_benchmark.hpp"

namespace finverse::cfd {
namespace {

DfgSetup sine_inflow(double t_end) {
  DfgSetup ds;
  ds.variant = 3;
  ds.cells_per_diameter = 8;
  ds.t_end = t_end;
  return ds;
}

// An end time that no step of the solver's own choice divides (its cap is 1/240 s here).
TEST(Dfg2d3, FixedStepLandsOnTheEndTime) {
  const DfgResult r = run_dfg(sine_inflow(0.401));
  ASSERT_GE(r.history.size(), 10u);
  EXPECT_NEAR(r.history.back().t, 0.401, 1e-12);
  const double dt = r.history[0].t;
  EXPECT_NEAR(dt * static_cast<double>(r.history.size()), 0.401, 1e-12);
  for (std::size_t n = 1; n < r.history.size(); ++n) EXPECT_NEAR(r.history[n].t - r.history[n - 1].t, dt, 1e-12);
}

TEST(Dfg2d3, DragGrowsWithTheSineInflowFromRest) {
  const DfgResult r = run_dfg(sine_inflow(0.5));
  // The coefficients are scaled by the peak mean velocity (1 m/s), so they grow with the inflow,
  // which at t = 0.5 s is sin(pi / 16) ~ 0.2 of its peak: the drag is well below 2D-3's maximum
  // (2.95 at t ~ 3.94 s) and, past the first steps' start-up, rises at every step.
  const std::size_t n = r.history.size();
  for (std::size_t m = n / 4; m < n; ++m) EXPECT_GT(r.history[m].cd, r.history[m - 1].cd) << "step " << m;
  EXPECT_GT(r.history.back().cd, 0.05);
  EXPECT_LT(r.history.back().cd, 1.0);
  EXPECT_LT(std::abs(r.history.back().cl), 0.05 * r.history.back().cd);
  // The maximum over the run is the last (the inflow still accelerates) and is dated with it.
  EXPECT_DOUBLE_EQ(r.cd_max, r.history.back().cd);
  EXPECT_DOUBLE_EQ(r.t_cd_max, r.history.back().t);
}

TEST(Dfg2d3, RefusesAnUnknownVariant) {
  DfgSetup ds = sine_inflow(0.1);
  ds.variant = 4;
  EXPECT_THROW(run_dfg(ds), std::exception);
}

}  // namespace
}  // namespace finverse::cfd
