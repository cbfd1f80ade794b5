// Tests of the surface traction on a triangulated body that crosses the domain boundary
// (SurfaceClip, surface_traction_3d.hpp; the wall-to-wall cylinder of DFG 3D-1Z): the exact clipping
// of a triangle to the domain box, the uniform-pressure force on a cylinder that crosses both z
// walls (zero net force, and the pressure on its front half equal to p times the projected
// in-domain area) and on one that crosses only one wall (the force of p on the cut cross-section),
// and the no-slip wall factor of the probes between the last cell centres and a wall.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cfd/immersed/ghost_cells.hpp"
#include "cfd/immersed/surface_shapes.hpp"
#include "cfd/forces/surface_traction_3d.hpp"
#include "core/error.hpp"

namespace finverse::cfd {
namespace {

constexpr double kR = 0.2, kXc = 0.5, kYc = 0.5, kDepth = 0.5, kP = 2.5;
constexpr int kSegments = 32;

StretchedGrid box_grid() {
  return StretchedGrid(Axis::uniform(0, 1, 16), Axis::stretched(0, 1, 0.25, 0.75, 0.05, 1.1), Axis::uniform(0, kDepth, 16));
}

SurfaceClip all_walls() {
  SurfaceClip c;
  c.enabled = true;
  c.no_slip.fill(true);
  return c;
}

// Forces of the uniform kinematic pressure kP (rho = 1) with the fluid at rest.
SurfaceForces uniform_pressure_forces(const StretchedGrid& g, const SurfaceTraction3D& t) {
  Field u(g), v(g), w(g), p(g);
  for (int k = -1; k <= g.nz(); ++k)
    for (int j = -1; j <= g.ny(); ++j)
      for (int i = -1; i <= g.nx(); ++i) p(i, j, k) = kP;
  return t.evaluate(u, v, w, p, 1e-3, 1.0);
}

TEST(SurfaceClip, TriangleClippedToBoxHasTheExactArea) {
  // x in [0, 1], y in [0, min(1, 2 (1 - x))]: area 0.5 + 0.25.
  const auto poly = clip_triangle_to_box({-1, 0, 0}, {1, 0, 0}, {0, 2, 0}, {0, 0, -1}, {1, 1, 1});
  ASSERT_GE(poly.size(), 3u);
  double area = 0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const auto& a = poly[i];
    const auto& b = poly[(i + 1) % poly.size()];
    area += 0.5 * (a[0] * b[1] - b[0] * a[1]);
  }
  EXPECT_NEAR(area, 0.75, 1e-15);
  EXPECT_TRUE(clip_triangle_to_box({2, 2, 0}, {3, 2, 0}, {2, 3, 0}, {0, 0, -1}, {1, 1, 1}).empty());
  const auto inside = clip_triangle_to_box({0.1, 0.1, 0}, {0.9, 0.1, 0}, {0.1, 0.9, 0}, {0, 0, -1}, {1, 1, 1});
  ASSERT_EQ(inside.size(), 3u);
  EXPECT_EQ(inside[1][0], 0.9);
}

TEST(SurfaceClip, UniformPressureOnACylinderCrossingBothWalls) {
  const StretchedGrid g = box_grid();
  // Rings every 0.0918: none on z = 0 or z = 0.5, so triangles straddle both walls.
  const SurfaceGeometry body(cylinder_surface(kXc, kYc, kR, -0.0713, kDepth + 0.0713, kSegments, 7));
  const GhostCellSet ib(g, body);
  // Without the explicit permission the samples outside the domain have no stencil.
  EXPECT_THROW(SurfaceTraction3D(g, ib, body), Error);
  const SurfaceTraction3D t(g, ib, body, all_walls());
  double area = 0;
  for (const auto& s : t.samples()) {
    EXPECT_GE(s.point[2], 0.0);
    EXPECT_LE(s.point[2], kDepth);
    area += s.area;
  }
  const double perimeter = kSegments * 2 * kR * std::sin(std::numbers::pi / kSegments);
  EXPECT_NEAR(area, perimeter * kDepth, 1e-13);
  const SurfaceForces F = uniform_pressure_forces(g, t);
  for (std::size_t c = 0; c < 3; ++c) EXPECT_NEAR(F.total[c], 0.0, 1e-12);
  // The front half (n_x < 0) is pushed in +x by p times its projection: the polygon's y extent
  // (2 R, vertices at 90 and 270 degrees) times the in-domain depth.
  double front = 0;
  for (int tri = 0; tri < body.triangles(); ++tri)
    if (body.triangle_normal(tri)[0] < 0) front += F.pressure[static_cast<std::size_t>(tri)][0];
  EXPECT_NEAR(front, kP * 2 * kR * kDepth, 1e-12);
}

TEST(SurfaceClip, UniformPressureOnACylinderCrossingOneWall) {
  const StretchedGrid g = box_grid();
  const SurfaceGeometry body(cylinder_surface(kXc, kYc, kR, -0.0713, 0.33, kSegments, 5));
  const GhostCellSet ib(g, body);
  const SurfaceTraction3D t(g, ib, body, all_walls());
  const SurfaceForces F = uniform_pressure_forces(g, t);
  // The in-domain part and the cut at z = 0 close a volume: p on the in-domain part is p times
  // the cut polygon's area, pointing to -z (the top cap is pushed down, the cut is open).
  const double section = 0.5 * kSegments * kR * kR * std::sin(2 * std::numbers::pi / kSegments);
  EXPECT_NEAR(F.total[0], 0.0, 1e-12);
  EXPECT_NEAR(F.total[1], 0.0, 1e-12);
  EXPECT_NEAR(F.total[2], -kP * section, 1e-12);
}

TEST(SurfaceClip, ProbesBetweenTheLastCentresAndANoSlipWallGoLinearlyToZero) {
  const StretchedGrid g = box_grid();
  const SurfaceGeometry body(cylinder_surface(kXc, kYc, kR, -0.0713, kDepth + 0.0713, kSegments, 7));
  const GhostCellSet ib(g, body);
  const double z0 = g.zc(0), z1 = g.zc(g.nz() - 1);
  const auto total = [](const PointStencil& s) {
    double w = s.boundary_weight;
    for (int k = 0; k < s.count; ++k) w += s.weight[static_cast<std::size_t>(k)];
    return w;
  };
  int near_wall = 0;
  for (const bool no_slip : {true, false}) {
    SurfaceClip clip = all_walls();
    clip.no_slip.fill(no_slip);
    const SurfaceTraction3D t(g, ib, body, clip);
    for (const auto& s : t.samples()) {
      // Lateral samples: the probes stay at the sample's height; the stencils reproduce constants
      // (weights sum to 1), scaled by the linear wall factor below the first/above the last centre.
      const double z = s.point[2];
      const double f = !no_slip ? 1.0 : z < z0 ? z / z0 : z > z1 ? (kDepth - z) / (kDepth - z1) : 1.0;
      near_wall += no_slip && f < 1;
      EXPECT_NEAR(total(s.velocity1), f, 1e-10);
      EXPECT_NEAR(total(s.velocity2), f, 1e-10);
      EXPECT_NEAR(total(s.pressure1), 1.0, 1e-10);
      for (int k = 0; k < s.velocity1.count; ++k) {
        const int kk = s.velocity1.cell[static_cast<std::size_t>(k)][2];
        EXPECT_TRUE(kk >= 0 && kk < g.nz());
      }
    }
  }
  EXPECT_GT(near_wall, 0);
}

}  // namespace
}  // namespace finverse::cfd
