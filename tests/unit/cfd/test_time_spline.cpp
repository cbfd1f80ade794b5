// Tests of the cubic-spline time interpolation of node motion (cfd/time_spline.hpp): linear motion
// reproduced exactly with its velocity, periodic splines smooth across the wrap, the layouts of
// periodic sample sets, and out-of-range times.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cfd/immersed/time_spline.hpp"
#include "core/error.hpp"

namespace finverse::cfd {
namespace {

TEST(TimeSpline, LinearMotionIsExactWithItsVelocity) {
  const std::vector<double> t{0.0, 0.013, 0.05, 0.051, 0.09, 0.2};  // non-uniform
  std::vector<double> y;
  for (double s : t) y.insert(y.end(), {1.0 + 2.0 * s, -3.0 * s, 0.25});
  const TimeSpline sp(t, y, 3, std::nullopt);
  for (double s : {0.0, 0.004, 0.05, 0.0505, 0.11, 0.2}) {
    double v[3], d[3], a[3];
    sp.evaluate(s, v, d, a);
    EXPECT_NEAR(v[0], 1.0 + 2.0 * s, 1e-14);
    EXPECT_NEAR(v[1], -3.0 * s, 1e-14);
    EXPECT_NEAR(v[2], 0.25, 1e-14);
    EXPECT_NEAR(d[0], 2.0, 1e-11);
    EXPECT_NEAR(d[1], -3.0, 1e-11);
    EXPECT_NEAR(d[2], 0.0, 1e-11);
    for (double q : a) EXPECT_NEAR(q, 0.0, 1e-8);
  }
  // Two samples: the straight line.
  const TimeSpline two({1.0, 2.0}, {0.0, 4.0}, 1, std::nullopt);
  double v, d;
  two.evaluate(1.25, &v, &d, nullptr);
  EXPECT_DOUBLE_EQ(v, 1.0);
  EXPECT_DOUBLE_EQ(d, 4.0);
}

TEST(TimeSpline, PeriodicSplineInterpolatesAndWrapsSmoothly) {
  const double T = 0.2;
  const int n = 40;
  std::vector<double> t, y;
  const double w = 2 * std::numbers::pi / T;
  for (int k = 0; k < n; ++k) {
    t.push_back(T * k / n);
    y.push_back(std::sin(w * t.back()));
  }
  const TimeSpline sp(t, y, 1, T);
  double ev = 0, ed = 0, ea = 0;
  for (int k = 0; k < n; ++k) {
    double v;
    sp.evaluate(t[static_cast<std::size_t>(k)], &v, nullptr, nullptr);
    EXPECT_NEAR(v, y[static_cast<std::size_t>(k)], 1e-15);
  }
  for (int q = 0; q <= 400; ++q) {
    const double s = 1.7 * T * q / 400;  // beyond one period: wraps
    double v, d, a;
    sp.evaluate(s, &v, &d, &a);
    ev = std::max(ev, std::abs(v - std::sin(w * s)));
    ed = std::max(ed, std::abs(d - w * std::cos(w * s)) / w);
    ea = std::max(ea, std::abs(a + w * w * std::sin(w * s)) / (w * w));
  }
  // Cubic spline errors O(h^4), O(h^3), O(h^2) with h = 2 pi / 40.
  EXPECT_LT(ev, 1e-5);
  EXPECT_LT(ed, 1e-3);
  EXPECT_LT(ea, 1e-2);
  // C2 across the wrap.
  double v0, d0, a0, v1, d1, a1;
  sp.evaluate(0.0, &v0, &d0, &a0);
  sp.evaluate(T - 1e-12, &v1, &d1, &a1);
  EXPECT_NEAR(v0, v1, 1e-9);
  EXPECT_NEAR(d0, d1, 1e-6 * w);
  EXPECT_NEAR(a0, a1, 1e-6 * w * w);
}

TEST(TimeSpline, PeriodicLayouts) {
  // fin-synth: t_k = k T / n.
  std::vector<double> t;
  for (int k = 0; k < 10; ++k) t.push_back(0.02 * k);
  auto l = periodic_layout(t, 0.2);
  ASSERT_TRUE(l.wrap);
  EXPECT_NEAR(*l.wrap, 0.2, 1e-15);
  EXPECT_EQ(l.frames, 10u);
  // The last sample repeats the first one period later: dropped.
  t.push_back(0.2);
  l = periodic_layout(t, 0.2);
  ASSERT_TRUE(l.wrap);
  EXPECT_EQ(l.frames, 10u);
  // Two periods sampled.
  std::vector<double> t2;
  for (int k = 0; k < 20; ++k) t2.push_back(0.02 * k);
  l = periodic_layout(t2, 0.2);
  ASSERT_TRUE(l.wrap);
  EXPECT_NEAR(*l.wrap, 0.4, 1e-15);
  // 1.5 periods: not periodic, with a note.
  std::vector<double> t3;
  for (int k = 0; k < 15; ++k) t3.push_back(0.02 * k);
  l = periodic_layout(t3, 0.2);
  EXPECT_FALSE(l.wrap);
  EXPECT_FALSE(l.note.empty());
  EXPECT_FALSE(periodic_layout(t3, std::nullopt).wrap);
}

TEST(TimeSpline, RejectsBadSamplesAndTimesOutsideTheSpan) {
  EXPECT_THROW(TimeSpline({0.0}, {1.0}, 1, std::nullopt), Error);
  EXPECT_THROW(TimeSpline({0.0, 0.1, 0.1}, {1.0, 2.0, 3.0}, 1, std::nullopt), Error);
  EXPECT_THROW(TimeSpline({0.0, 0.1}, {1.0}, 1, std::nullopt), Error);
  const TimeSpline sp({0.0, 0.1, 0.2}, {0.0, 1.0, 0.0}, 1, std::nullopt);
  double v;
  EXPECT_THROW(sp.evaluate(0.21, &v, nullptr, nullptr), Error);
  EXPECT_THROW(sp.evaluate(-0.01, &v, nullptr, nullptr), Error);
  EXPECT_NO_THROW(sp.evaluate(0.2, &v, nullptr, nullptr));
}

}  // namespace
}  // namespace finverse::cfd
