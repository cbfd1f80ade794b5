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

// Fin rays are nearly inextensible: bending must turn the ray, not stretch it. Every ray line (and
// every membrane line between rays) keeps its rest arc length over a whole period, to round-off.
// The former model, which added the bending deflection laterally to the rest shape, stretched the
// rays by 0.6-1.2 % on average and up to 1.9 % (middle rays) over the stroke and fails this.
TEST(KinematicModel, RayArcLengthPreservedOverAPeriod) {
  const auto fin = mesh::make_caudal_fin({});
  const auto f = make_fin_surface(fin, 4);
  const PrescribedKinematics k({});
  const std::size_t m = fin.rays[0].points.size(), ncol = f.size() / m;
  ASSERT_EQ(ncol * m, f.size());
  // Column-major vertex layout of make_fin_surface: column col, row k at col * m + k.
  auto length = [&](const NdArray<double>& x, std::size_t col) {
    double l = 0;
    for (std::size_t kk = 0; kk + 1 < m; ++kk) {
      const std::size_t a = col * m + kk, b = a + 1;
      l += std::hypot(x(b, 0) - x(a, 0), x(b, 1) - x(a, 1), x(b, 2) - x(a, 2));
    }
    return l;
  };
  double worst_ray = 0, worst_line = 0, tip_lateral = 0;
  const double T = k.period();
  for (int n = 0; n < 50; ++n) {
    const auto p = k.positions(f, n * T / 50);
    for (std::size_t col = 0; col < ncol; ++col) {
      const double strain = std::abs(length(p, col) / length(f.rest, col) - 1);
      worst_line = std::max(worst_line, strain);
      if (col % 4 == 0) worst_ray = std::max(worst_ray, strain);
    }
    // The bending still bends: the middle line's tip leaves its pitched root chord laterally.
    const std::size_t root = 38 * m, tip = root + m - 1;
    tip_lateral = std::max(tip_lateral, std::abs(p(tip, 1) - p(root, 1)));
  }
  EXPECT_LT(worst_ray, 1e-12);
  EXPECT_LT(worst_line, 1e-12);
  EXPECT_GT(tip_lateral, 0.1 * 0.01);
}
