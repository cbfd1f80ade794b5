// Tests of the closed triangulated surface's geometry (surface_geometry.hpp): watertightness and
// orientation errors, inside/outside and closest point on a box (exact) and an icosphere (against
// the sphere, up to the facets' sag), points exactly on faces, edges and vertices.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

#include "cfd/immersed/surface_geometry.hpp"
#include "cfd/immersed/surface_shapes.hpp"
#include "core/error.hpp"

namespace finverse::cfd {
namespace {

TEST(SurfaceGeometry, BoxClosestPointAndSignAreExact) {
  const SurfaceGeometry box(box_surface({0, 0, 0}, {1, 2, 3}));
  EXPECT_NEAR(box.volume(), 6.0, 1e-12);
  EXPECT_NEAR(box.area(), 22.0, 1e-12);
  struct Case {
    Vec3 x, point;
    double distance;
  };
  const std::vector<Case> cases = {
      {{2, 0.5, 0.5}, {1, 0.5, 0.5}, 1.0},                        // face x = 1
      {{0.2, 1.0, 1.5}, {0, 1.0, 1.5}, -0.2},                     // inside, nearest face x = 0
      {{0.5, 1.0, 2.9}, {0.5, 1.0, 3}, -0.1},                     // inside, nearest face z = 3
      {{1.5, 2.5, 3.5}, {1, 2, 3}, std::sqrt(0.75)},              // beyond a corner
      {{-1, -1, 1.5}, {0, 0, 1.5}, std::sqrt(2.0)},               // beyond an edge
      {{0.5, 1.0, 1e-7}, {0.5, 1.0, 0}, -1e-7},                   // just inside face z = 0, on its diagonal
      {{0.5, 1.0, -1e-7}, {0.5, 1.0, 0}, 1e-7},                   // just outside there
  };
  for (const Case& c : cases) {
    const SurfaceHit h = box.closest(c.x);
    for (std::size_t d = 0; d < 3; ++d) EXPECT_NEAR(h.point[d], c.point[d], 1e-12);
    EXPECT_NEAR(h.distance, c.distance, 1e-12);
    EXPECT_EQ(box.inside(c.x), c.distance < 0);
    // The normal points from the surface towards an outside point.
    if (std::abs(c.distance) > 1e-3) {
      for (std::size_t d = 0; d < 3; ++d) EXPECT_NEAR(h.normal[d], (c.x[d] - c.point[d]) / c.distance, 1e-12);
    }
  }
}

TEST(SurfaceGeometry, PointsOnTheSurfaceCountAsOutside) {
  const SurfaceGeometry box(box_surface({0, 0, 0}, {1, 1, 1}));
  // A vertex, an edge midpoint, a face centre (on the face's diagonal edge) and a face point.
  for (const Vec3& x : std::vector<Vec3>{{1, 1, 1}, {0.5, 0, 0}, {0.5, 0.5, 1}, {0.25, 0.5, 0}, {1, 0.2, 0.7}}) {
    const SurfaceHit h = box.closest(x);
    EXPECT_EQ(h.distance, 0.0);
    EXPECT_FALSE(box.inside(x));
    EXPECT_NEAR(std::hypot(h.normal[0], h.normal[1], h.normal[2]), 1.0, 1e-12);
  }
}

TEST(SurfaceGeometry, IcosphereAgainstTheSphere) {
  const double r = 0.5;
  const TriangulatedSurface s = icosphere({0.1, -0.2, 0.3}, r, 3, true);
  const SurfaceGeometry g(s);
  EXPECT_EQ(g.triangles(), 20 * 64);
  EXPECT_NEAR(g.volume(), 4 * std::numbers::pi * r * r * r / 3, 1e-12);
  // Facet sag of a level-3 icosphere of radius 0.5: below 0.01.
  const double sag = 0.01;
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  int checked = 0;
  for (int n = 0; n < 2000; ++n) {
    const Vec3 x{0.1 + u(rng), -0.2 + u(rng), 0.3 + u(rng)};
    const double rho = std::hypot(x[0] - 0.1, x[1] + 0.2, x[2] - 0.3);
    const SurfaceHit h = g.closest(x);
    EXPECT_NEAR(h.distance, rho - r, sag);
    if (std::abs(rho - r) > sag) {
      EXPECT_EQ(g.inside(x), rho < r);
      ++checked;
    }
    const double cr = std::hypot(h.point[0] - 0.1, h.point[1] + 0.2, h.point[2] - 0.3);
    EXPECT_NEAR(cr, r, sag);
    // I = 2B - x lies on the other side of the surface at the same distance.
    if (std::abs(h.distance) > 0.05 && rho > 0.25) {
      const double cosine = ((x[0] - 0.1) * h.normal[0] + (x[1] + 0.2) * h.normal[1] + (x[2] - 0.3) * h.normal[2]) / rho;
      EXPECT_GT(cosine, 0.99);
    }
  }
  EXPECT_GT(checked, 1800);
}

TEST(SurfaceGeometry, MoveToRebuildsTheHierarchy) {
  SurfaceGeometry g(icosphere({0, 0, 0}, 0.5, 2));
  std::vector<Vec3> p = g.surface().points;
  for (auto& v : p) v[0] += 3;
  g.move_to(p);
  EXPECT_TRUE(g.inside({3, 0, 0}));
  EXPECT_FALSE(g.inside({0, 0, 0}));
  EXPECT_NEAR(g.closest({4, 0, 0}).distance, 0.5, 1e-12);  // (0.5, 0, 0) is a vertex
  EXPECT_NEAR(g.lower()[0], 2.5, 1e-12);
}

TEST(SurfaceGeometry, RejectsOpenAndInconsistentSurfaces) {
  TriangulatedSurface open = box_surface({0, 0, 0}, {1, 1, 1});
  open.triangles.pop_back();
  EXPECT_THROW(SurfaceGeometry{open}, Error);
  TriangulatedSurface flipped = box_surface({0, 0, 0}, {1, 1, 1});
  std::swap(flipped.triangles[3][1], flipped.triangles[3][2]);
  EXPECT_THROW(SurfaceGeometry{flipped}, Error);
  TriangulatedSurface inward = box_surface({0, 0, 0}, {1, 1, 1});
  for (auto& t : inward.triangles) std::swap(t[1], t[2]);
  EXPECT_THROW(SurfaceGeometry{inward}, Error);
  TriangulatedSurface doubled = box_surface({0, 0, 0}, {1, 1, 1});
  doubled.triangles.push_back(doubled.triangles[0]);
  EXPECT_THROW(SurfaceGeometry{doubled}, Error);
  TriangulatedSurface bad_index = box_surface({0, 0, 0}, {1, 1, 1});
  bad_index.triangles[0][0] = 8;
  EXPECT_THROW(SurfaceGeometry{bad_index}, Error);
  try {
    SurfaceGeometry{open, "fin.h5 /ibm"};
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("fin.h5 /ibm: edge"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace finverse::cfd
