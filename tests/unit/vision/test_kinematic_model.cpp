// The prescribed trout kinematics (seed paper sections 4.2, 4.4): frequency from St and Re, root
// heave of 0.44 c, U-shaped pitch amplitude and W-shaped pitch phase across the rays, periodicity.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "vision/kinematic_model.hpp"

using namespace finverse;
using namespace finverse::vision;

TEST(KinematicModel, FrequencyFromStrouhalAndReynolds) {
  const PrescribedKinematics k({});
  EXPECT_NEAR(k.speed(), 0.1, 1e-15);            // U = Re nu / c = 1000 * 1e-6 / 0.01
  EXPECT_NEAR(k.frequency(), 5.0, 1e-12);        // f = St U / (2 A) = 0.44 * 0.1 / (2 * 0.0044)
  EXPECT_NEAR(k.period() * 500, 100.0, 1e-9);    // 100 frames per period at 500 fps
}

TEST(KinematicModel, UShapedAmplitudeWShapedPhase) {
  const PrescribedKinematics k({});
  std::vector<double> amp, phase;
  for (int r = 0; r < 20; ++r) {
    const double eta = 1.0 - 2.0 * r / 19;
    amp.push_back(k.pitch_amplitude(eta));
    phase.push_back(k.pitch_phase(eta));
  }
  // U: largest at the edges, smallest in the middle, monotone in between.
  for (int r = 0; r < 9; ++r) EXPECT_GT(amp[r], amp[r + 1]);
  for (int r = 10; r < 19; ++r) EXPECT_LT(amp[r], amp[r + 1]);
  // W: maxima at both edges and in the middle, minima near the quarter spans.
  auto local_min = [&](int r) { return phase[r] < phase[r - 1] && phase[r] < phase[r + 1]; };
  int minima = 0;
  for (int r = 1; r < 19; ++r) minima += local_min(r);
  EXPECT_EQ(minima, 2);
  EXPECT_GT(phase[0], phase[5]);
  EXPECT_GT(phase[9], phase[5]);
  EXPECT_GT(phase[19], phase[14]);
}

TEST(KinematicModel, RootHeavesRigidlyAndMotionIsPeriodic) {
  const auto fin = mesh::make_caudal_fin({});
  const auto f = make_fin_surface(fin, 4);
  const PrescribedKinematics k({});
  const double T = k.period();
  const auto quarter = k.positions(f, 0.25 * T);
  const auto p0 = k.positions(f, 0.1 * T), p1 = k.positions(f, 1.1 * T);
  double root_seen = 0;
  for (std::size_t i = 0; i < f.size(); ++i) {
    for (int d = 0; d < 3; ++d) EXPECT_NEAR(p0(i, d), p1(i, d), 1e-15);
    if (f.s[i] == 0.0) {  // root: pure heave, 0.44 c at a quarter period
      EXPECT_NEAR(quarter(i, 1), 0.44 * 0.01, 1e-15);
      EXPECT_DOUBLE_EQ(quarter(i, 0), f.rest(i, 0));
      EXPECT_DOUBLE_EQ(quarter(i, 2), f.rest(i, 2));
      ++root_seen;
    }
  }
  EXPECT_GT(root_seen, 20);
  // Trailing-edge peak-to-peak excursion close to the paper's reconstruction (about 0.9-1.1 c).
  const std::size_t tip_mid = 38 * 25 + 24;  // column 38 of 77 (between rays 10 and 11), tip row
  ASSERT_DOUBLE_EQ(f.s[tip_mid], 1.0);
  double lo = 1e9, hi = -1e9;
  for (int n = 0; n < 100; ++n) {
    const double y = k.positions(f, n * T / 100)(tip_mid, 1);
    lo = std::min(lo, y);
    hi = std::max(hi, y);
  }
  EXPECT_GT((hi - lo) / 0.01, 0.8);
  EXPECT_LT((hi - lo) / 0.01, 1.3);
}
