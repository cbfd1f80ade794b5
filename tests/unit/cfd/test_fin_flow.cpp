// A tiny end-to-end run of fin-cfd's fin case (cfd/io/fin_flow_case.hpp): the heaving and pitching
// plate on a very coarse grid for a few steps; the loads history has the planned output times and
// shapes, its nodal forces sum to the integrated force, and a bad output interval is refused.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "cfd/io/fin_flow_case.hpp"
#include "cfd/io/loads_record.hpp"
#include "cfd/validation/thin_plate_case.hpp"
#include "tiny_fin_case.hpp"
#include "core/error.hpp"

namespace finverse::cfd::io {
namespace {

using test::tiny_plate;

// 10 ms: two outputs 5 ms apart.
FinFlowOptions tiny_flow_options() { return test::tiny_options(0.05); }

TEST(FinFlow, TinyPlateRunGivesAConsistentLoadsHistory) {
  const FinInput in = tiny_plate();
  FinFlowStats st;
  const stage::Loads l = run_fin_flow(in, tiny_flow_options(), st);
  ASSERT_EQ(l.time.size(), 2u);
  EXPECT_NEAR(l.time(0), 0.005, 1e-15);
  EXPECT_NEAR(l.time(1), 0.010, 1e-15);
  EXPECT_EQ(l.nodal_force.shape, (std::vector<std::size_t>{2, in.rest.size(), 3}));
  EXPECT_EQ(l.pressure_jump.shape, (std::vector<std::size_t>{2, in.mid_triangles.size()}));
  ASSERT_TRUE(l.period.has_value());
  EXPECT_DOUBLE_EQ(*l.period, 0.2);
  EXPECT_DOUBLE_EQ(*l.reference_area, 0.01 * 0.015);
  for (double e : nodal_sum_relative_error(l)) EXPECT_LE(e, 1e-12);
  double fmax = 0;
  for (double v : l.force_total.data) fmax = std::max(fmax, std::abs(v));
  EXPECT_GT(fmax, 0.0);  // the moving plate feels a force
  EXPECT_GT(st.steps, 1);
  // m steps per output; the run goes half an interval past the last output, so that its loads are
  // the mean over a whole interval centred on it (loads_window.hpp).
  const long m = std::lround(0.005 / st.dt);
  EXPECT_NEAR(st.dt * static_cast<double>(m), 0.005, 1e-12);
  EXPECT_EQ(st.steps, 2 * m + m / 2);
  EXPECT_LE(st.max_cfl, 2.0);
  // The swept body lies inside the grid's uniform core.
  for (int d = 0; d < 3; ++d) {
    EXPECT_GT(st.swept_lo[d], st.grid.axis(d).lo() + 0.5 * 0.01);
    EXPECT_LT(st.swept_hi[d], st.grid.axis(d).hi() - 0.5 * 0.01);
  }
  EXPECT_EQ(st.grid.nx() % 8, 0);
}

TEST(FinFlow, RefusesBadRunParameters) {
  const FinInput in = tiny_plate();
  auto expect = [&](const FinFlowOptions& o, const std::string& flag) {
    FinFlowStats st;
    try {
      run_fin_flow(in, o, st);
      ADD_FAILURE() << "no error for " << flag;
    } catch (const Error& e) {
      EXPECT_NE(std::string(e.what()).find(flag), std::string::npos) << e.what();
    }
  };
  FinFlowOptions o = tiny_flow_options();
  o.output_interval = 0.003;
  expect(o, "--output-interval");
  o = tiny_flow_options();
  o.downstream = 0.6;
  expect(o, "--downstream");
  o = tiny_flow_options();
  o.reynolds = -1;
  expect(o, "--reynolds");
}

}  // namespace
}  // namespace finverse::cfd::io
