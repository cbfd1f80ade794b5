// Fin template invariants (seed paper section 4.1): 20 rays ordered dorsal to ventral, edge rays
// thickest, monotone taper, simple outline, forked trailing edge; and the one-line errors for a
// template without rays or with a self-intersecting planform.
#include <gtest/gtest.h>

#include <cmath>

#include "core/error.hpp"
#include "mesh/fin_template.hpp"

using namespace finverse;
using namespace finverse::mesh;

namespace {

void expect_error(const std::function<void()>& fn, const std::string& fragment) {
  try {
    fn();
    FAIL() << "expected finverse::Error mentioning '" << fragment << "'";
  } catch (const Error& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find(fragment), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << "not one line: " << m;
  }
}

}  // namespace

TEST(FinTemplate, DefaultIsThePapersTroutFin) {
  const auto t = make_caudal_fin({});
  EXPECT_EQ(t.ray_count(), 20u);
  EXPECT_DOUBLE_EQ(t.chord, 0.01);
  // Lobe tips: x = c, dorsal-ventral distance 1.5 c.
  const auto dorsal_tip = t.rays.front().points.back(), ventral_tip = t.rays.back().points.back();
  EXPECT_NEAR(dorsal_tip[0], 0.01, 1e-12);
  EXPECT_NEAR(ventral_tip[0], 0.01, 1e-12);
  EXPECT_NEAR(dorsal_tip[1] - ventral_tip[1], 0.015, 1e-12);
  // Root at x = 0.
  for (const auto& r : t.rays) EXPECT_NEAR(r.points.front()[0], 0.0, 1e-15);
}

TEST(FinTemplate, RaysOrderedDorsalToVentral) {
  const auto t = make_caudal_fin({});
  for (std::size_t r = 0; r + 1 < t.ray_count(); ++r) {
    EXPECT_GT(t.rays[r].points.front()[1], t.rays[r + 1].points.front()[1]) << "root of ray " << r + 1;
    EXPECT_GT(t.rays[r].points.back()[1], t.rays[r + 1].points.back()[1]) << "tip of ray " << r + 1;
    for (double s : {0.25, 0.5, 0.75})  // and everywhere between: rays never cross
      EXPECT_GT(t.point_at(r, s)[1], t.point_at(r + 1, s)[1]);
  }
}

TEST(FinTemplate, EdgeRaysThickestAndEveryRayTapers) {
  const auto t = make_caudal_fin({});
  const std::size_t n = t.ray_count();
  for (std::size_t r = 1; r + 1 < n; ++r) {
    EXPECT_GT(t.section(0, 0).thickness, t.section(r, 0).thickness);
    EXPECT_GT(t.section(n - 1, 0).thickness, t.section(r, 0).thickness);
  }
  // U-shaped across the fin: decreasing towards the middle from either edge.
  for (std::size_t r = 0; r + 1 < n / 2; ++r) EXPECT_GT(t.section(r, 0).thickness, t.section(r + 1, 0).thickness);
  for (std::size_t r = n / 2; r + 1 < n; ++r) EXPECT_LT(t.section(r, 0).thickness, t.section(r + 1, 0).thickness);
  for (std::size_t r = 0; r < n; ++r) {
    const auto& sec = t.rays[r].sections;
    for (std::size_t i = 1; i < sec.size(); ++i) {
      EXPECT_LT(sec[i].thickness, sec[i - 1].thickness) << "ray " << r + 1 << " point " << i;
      EXPECT_LT(sec[i].width, sec[i - 1].width);
    }
    EXPECT_NEAR(t.section(r, 1).thickness / t.section(r, 0).thickness, 0.2, 1e-12);
  }
}

TEST(FinTemplate, OutlineIsSimpleCounterClockwiseAndForked) {
  const auto t = make_caudal_fin({});
  const auto poly = t.outline();
  EXPECT_GT(t.area(), 0);
  // The planform lies between root (x = 0) and lobes (x = c) and has the emarginate notch: the
  // middle of the trailing edge is fork_depth upstream of the lobe tips.
  const auto mid = t.rays[9].points.back(), mid2 = t.rays[10].points.back();
  EXPECT_LT(0.5 * (mid[0] + mid2[0]), 0.01 * (1 - 0.2));
  EXPECT_GT(0.5 * (mid[0] + mid2[0]), 0.01 * (1 - 0.25) - 1e-12);
  EXPECT_NO_THROW(validate(t));
  // The planform is the union of the strips between neighbouring rays: their areas add up to
  // the outline's (no overlap, no gap), and the fork and the concave edge rays keep it below the
  // trapezoid through root and lobe tips.
  double strips = 0;
  for (std::size_t r = 0; r + 1 < t.ray_count(); ++r) {
    std::vector<Point2> q(t.rays[r + 1].points);
    q.insert(q.end(), t.rays[r].points.rbegin(), t.rays[r].points.rend());
    double a = 0;
    for (std::size_t i = 0, j = q.size() - 1; i < q.size(); j = i++) a += q[j][0] * q[i][1] - q[i][0] * q[j][1];
    EXPECT_GT(a, 0) << "strip " << r + 1;
    strips += 0.5 * a;
  }
  EXPECT_NEAR(strips, t.area(), 1e-12 * t.area());
  EXPECT_LT(t.area(), 0.5 * (0.015 + 0.005) * 0.01);
  // Trailing edge points go dorsal (+z) in outline order after the ventral ray.
  EXPECT_EQ(poly.size(), 2 * t.rays[0].points.size() + t.ray_count() - 2);
}

TEST(FinTemplate, ParametricFinFollowsItsParameters) {
  CaudalFinParams p;
  p.rays = 7;
  p.chord_m = 0.02;
  p.height_over_chord = 2.0;
  p.fork_depth = 0;
  const auto t = make_caudal_fin(p);
  EXPECT_EQ(t.ray_count(), 7u);
  for (const auto& r : t.rays) EXPECT_NEAR(r.points.back()[0], 0.02, 1e-12);  // no fork: straight edge
  EXPECT_NEAR(t.rays.front().points.back()[1] - t.rays.back().points.back()[1], 0.04, 1e-12);
}

TEST(FinTemplate, JsonRoundTrip) {
  const auto t = make_caudal_fin({});
  const auto back = from_json(to_json(t), "test");
  ASSERT_EQ(back.ray_count(), t.ray_count());
  EXPECT_EQ(back.rays[3].points, t.rays[3].points);
  EXPECT_DOUBLE_EQ(back.section(4, 0.3).thickness, t.section(4, 0.3).thickness);
}

TEST(FinTemplate, TemplateWithoutRaysIsAnError) {
  auto j = to_json(make_caudal_fin({}));
  j["rays"] = nlohmann::json::array();
  expect_error([&] { from_json(j, "fin.json"); }, "fin.json: has 0 rays");
  CaudalFinParams p;
  p.rays = 0;
  expect_error([&] { make_caudal_fin(p); }, "--rays 0");
}

TEST(FinTemplate, SelfIntersectingPlanformIsAnError) {
  // Swap the tips of two interior rays: they cross.
  auto t = make_caudal_fin({});
  std::swap(t.rays[5].points.back(), t.rays[12].points.back());
  expect_error([&] { validate(t, "fin.json"); }, "self-intersects");
  // Pull the dorsal lobe tip below the ventral one: the outline crosses itself.
  auto u = make_caudal_fin({});
  u.rays.front().points.back()[1] = -0.02;
  expect_error([&] { validate(u, "fin.json"); }, "fin.json");
  // Rays listed ventral to dorsal: wrong orientation, named as such.
  auto v = make_caudal_fin({});
  std::reverse(v.rays.begin(), v.rays.end());
  expect_error([&] { validate(v, "fin.json"); }, "dorsal edge");
}
