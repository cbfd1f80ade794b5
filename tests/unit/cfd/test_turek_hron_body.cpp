// The Turek-Hron cylinder + flag body as one polygon (turek_hron_cfd.hpp): closed and simple,
// counter-clockwise, the exact union area up to the arc's chord error, the flag's corners and the
// two points where the flag's edges meet the circle.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cfd/validation/turek_hron_cfd.hpp"

namespace finverse::cfd {
namespace {

using P = std::array<double, 2>;

double cross(const P& o, const P& a, const P& b) { return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]); }

// Proper or touching intersection of the closed segments ab and cd.
bool segments_meet(const P& a, const P& b, const P& c, const P& d) {
  const double d1 = cross(c, d, a), d2 = cross(c, d, b), d3 = cross(a, b, c), d4 = cross(a, b, d);
  return ((d1 > 0) != (d2 > 0) || d1 == 0 || d2 == 0) && ((d3 > 0) != (d4 > 0) || d3 == 0 || d4 == 0);
}

bool has_vertex(const std::vector<P>& v, double x, double y) {
  for (const P& p : v)
    if (std::abs(p[0] - x) < 1e-12 && std::abs(p[1] - y) < 1e-12) return true;
  return false;
}

TEST(TurekHronBody, UnionPolygonIsClosedSimpleWithTheExactAreaAndCorners) {
  const TurekHronGeometry g;
  const Polygon body = turek_hron_body(g, 256);
  const std::vector<P>& v = body.vertices();
  const std::size_t n = v.size();
  ASSERT_GT(n, 200u);

  // Closed: no repeated vertex (the last edge joins the last vertex to the first), no zero edge.
  for (std::size_t k = 0; k < n; ++k) {
    const P &a = v[k], &b = v[(k + 1) % n];
    EXPECT_GT(std::hypot(b[0] - a[0], b[1] - a[1]), 1e-4) << "edge " << k;
  }
  // Simple: no two non-adjacent edges meet.
  int crossings = 0;
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 2; j < n; ++j) {
      if (i == 0 && j == n - 1) continue;  // adjacent through the closing edge
      if (segments_meet(v[i], v[(i + 1) % n], v[j], v[(j + 1) % n])) ++crossings;
    }
  EXPECT_EQ(crossings, 0);

  // Counter-clockwise with the union's area: circle + strip - overlap, less the chord error of an
  // inscribed 256-gon, pi r^2 (1 - sin(2 pi / n) n / (2 pi)) = 3.1e-4 of the circle.
  const double exact = turek_hron_body_area(g);
  const double r = g.radius, a = 0.5 * g.flag_thickness;
  EXPECT_NEAR(exact, std::numbers::pi * r * r + 0.4 * 0.02 - (a * std::sqrt(r * r - a * a) + r * r * std::asin(a / r)), 1e-15);
  EXPECT_GT(body.area(), 0.0);
  EXPECT_NEAR(body.area(), exact, 4e-4 * std::numbers::pi * r * r);
  EXPECT_LT(body.area(), exact);

  // The flag's corners: tip at x = 0.6, edges at y = 0.19 and 0.21, joined to the circle where
  // those edges cut it, x = 0.2 + sqrt(0.05^2 - 0.01^2).
  const double xi = 0.2 + std::sqrt(0.05 * 0.05 - 0.01 * 0.01);
  EXPECT_TRUE(has_vertex(v, 0.6, 0.19));
  EXPECT_TRUE(has_vertex(v, 0.6, 0.21));
  EXPECT_TRUE(has_vertex(v, xi, 0.19));
  EXPECT_TRUE(has_vertex(v, xi, 0.21));

  // Inside/outside: the flag, the cylinder's front, and the slots just outside the flag.
  EXPECT_TRUE(body.contains(0.5, 0.2));
  EXPECT_TRUE(body.contains(0.16, 0.2));
  EXPECT_FALSE(body.contains(0.5, 0.215));
  EXPECT_FALSE(body.contains(0.5, 0.185));
  EXPECT_FALSE(body.contains(0.605, 0.2));
  // Every vertex of the arc lies on the circle and outside the flag's strip.
  for (const P& p : v)
    if (p[0] < xi + 1e-12) {
      EXPECT_NEAR(std::hypot(p[0] - 0.2, p[1] - 0.2), r, 1e-14);
    }
}

}  // namespace
}  // namespace finverse::cfd
