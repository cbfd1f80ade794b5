// The control-volume momentum balance (control_volume_force.hpp) on fields whose surface integrals
// are known in closed form: convective flux, pressure and viscous terms each exact on a uniform
// grid for the chosen polynomials; the momentum sum skips the body's cells; the time derivative of
// a linearly growing momentum; bad rectangles are refused; the same in a 3-D box around a sphere.
#include <gtest/gtest.h>

#include <cmath>

#include "cfd/forces/control_volume_force.hpp"
#include "cfd/immersed/surface_shapes.hpp"
#include "core/error.hpp"

namespace finverse::cfd {
namespace {

struct Box {
  StretchedGrid grid{Axis::uniform(0, 1, 40), Axis::uniform(0, 1, 40)};
  Polygon body = Polygon::circle(0.5, 0.5, 0.1, 128);
  GhostCellSet ghosts{grid, body};
};

TEST(ControlVolumeForce, SurfaceIntegralsOfPolynomialFieldsAreExact) {
  Box s;
  const double c = 0.7, a = 2.0, b = -3.0, nu = 0.01, v0 = 0.5;
  const auto uf = [&](double y) { return 1 + c * y * y; };
  Field u(s.grid), v(s.grid), p(s.grid);
  FaceField U(s.grid);
  for (int j = 0; j < 40; ++j)
    for (int i = 0; i < 40; ++i) {
      u(i, j, 0) = uf(s.grid.yc(j));
      v(i, j, 0) = v0;
      p(i, j, 0) = a * s.grid.xc(i) + b * s.grid.yc(j);
    }
  for (int j = 0; j < 40; ++j)
    for (int i = 0; i <= 40; ++i) U(0, i, j, 0) = uf(s.grid.yc(j));
  for (int j = 0; j <= 40; ++j)
    for (int i = 0; i < 40; ++i) U(1, i, j, 0) = v0;
  // Faces at multiples of 0.025: the rectangle is taken as given.
  const double x0 = 0.2, x1 = 0.8, y0 = 0.25, y1 = 0.75, L = x1 - x0, H = y1 - y0;
  const ControlVolumeForce cv(s.grid, s.ghosts, x0, x1, y0, y1);
  EXPECT_EQ(cv.cells()[0], 8);
  EXPECT_EQ(cv.cells()[3], 30);
  const ControlVolumeSample q = cv.evaluate(0.0, u, v, U, p, nu);
  // x: convection through the top and bottom (the face interpolation's error c h^2 / 4 cancels),
  // pressure a L H, viscous -nu [2 c y] L between the two; y: only the pressure b L H.
  const double fx = v0 * c * (y1 * y1 - y0 * y0) * L + a * L * H - nu * 2 * c * (y1 - y0) * L;
  EXPECT_NEAR(q.flux[0], fx, 1e-12);
  EXPECT_NEAR(q.flux[1], b * L * H, 1e-12);
  // Momentum: only the fluid cells of the rectangle (the body's cells left out).
  double mx = 0;
  int fluid = 0;
  for (int j = 10; j < 30; ++j)
    for (int i = 8; i < 32; ++i)
      if (s.ghosts.kind(i, j) == CellKind::Fluid) {
        mx += s.grid.volume(i, j, 0) * u(i, j, 0);
        ++fluid;
      }
  EXPECT_LT(fluid, 24 * 20 - 40);  // the circle of radius 4 cells covers ~50 cells
  EXPECT_NEAR(q.momentum[0], mx, 1e-14);
  EXPECT_NEAR(q.momentum[1], v0 * 0.025 * 0.025 * fluid, 1e-14);
}

// The 3-D box: u = 1 + c y^2, v = v0, w = w0, p = a x + b y + e z around a sphere. Only the
// convection of u through the y faces, the pressure and the viscous term of u on the y faces
// survive; each is exact on the uniform grid. Extents differ per axis, so a mixed-up axis shows.
TEST(ControlVolumeForce, BoxIntegralsOfPolynomialFieldsAreExactIn3D) {
  const int n = 24;
  const StretchedGrid g(Axis::uniform(0, 1, n), Axis::uniform(0, 1, n), Axis::uniform(0, 1, n));
  const SurfaceGeometry body(icosphere({0.5, 0.5, 0.47}, 0.12, 2));
  const GhostCellSet ghosts(g, body);
  const double c = 0.7, a = 2.0, b = -3.0, e = 0.4, nu = 0.01, v0 = 0.5, w0 = -0.3;
  const auto uf = [&](double y) { return 1 + c * y * y; };
  Field u(g), v(g), w(g), p(g);
  FaceField U(g);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i <= n; ++i) {
        U(0, i, j, k) = uf(g.yc(j));
        U(1, j, i, k) = v0;  // (j, i, k): i runs over the faces along y
        U(2, j, k, i) = w0;
        if (i == n) continue;
        u(i, j, k) = uf(g.yc(j));
        v(i, j, k) = v0;
        w(i, j, k) = w0;
        p(i, j, k) = a * g.xc(i) + b * g.yc(j) + e * g.zc(k);
      }
  const double x0 = 6.0 / n, x1 = 18.0 / n, y0 = 5.0 / n, y1 = 19.0 / n, z0 = 6.0 / n, z1 = 17.0 / n;
  const double L = x1 - x0, H = y1 - y0, Z = z1 - z0;
  const ControlVolumeForce cv(g, ghosts, {x0, x1, y0, y1, z0, z1});
  EXPECT_EQ(cv.cells()[2], 5);
  EXPECT_EQ(cv.cells_z()[1], 17);
  const ControlVolumeSample q = cv.evaluate(0.0, u, v, w, U, p, nu);
  const double fx = (v0 * c * (y1 * y1 - y0 * y0) * L + a * L * H - nu * 2 * c * (y1 - y0) * L) * Z;
  EXPECT_NEAR(q.flux[0], fx, 1e-12);
  EXPECT_NEAR(q.flux[1], b * L * H * Z, 1e-12);
  EXPECT_NEAR(q.flux[2], e * L * H * Z, 1e-12);
  int fluid = 0;
  for (int k = 6; k < 17; ++k)
    for (int j = 5; j < 19; ++j)
      for (int i = 6; i < 18; ++i) fluid += ghosts.kind(i, j, k) == CellKind::Fluid;
  EXPECT_LT(fluid, 12 * 14 * 11 - 20);  // the sphere's cells are left out
  EXPECT_NEAR(q.momentum[2], w0 * fluid / (n * n * n * 1.0), 1e-14);
  // The 2-D evaluate refuses a 3-D box; a box cutting the sphere is refused.
  EXPECT_THROW(cv.evaluate(0.0, u, v, U, p, nu), Error);
  EXPECT_THROW(ControlVolumeForce(g, ghosts, {x0, x1, y0, y1, 0.45, z1}), Error);
}

TEST(ControlVolumeForce, ForceIsMinusRhoTimesMomentumRatePlusFlux) {
  // M(t) = (3 t, -2 t^2) with a constant flux: central differences are exact for a quadratic.
  std::vector<ControlVolumeSample> s;
  const double ts[] = {0.0, 0.1, 0.25, 0.3};
  for (const double t : ts) {
    ControlVolumeSample q;
    q.t = t;
    q.momentum = {3 * t, -2 * t * t};
    q.flux = {1.5, -0.5};
    s.push_back(q);
  }
  const auto F = control_volume_forces(s, 2.0);
  ASSERT_EQ(F.size(), 4u);
  for (std::size_t k = 0; k < 4; ++k) EXPECT_NEAR(F[k][0], -2.0 * (3 + 1.5), 1e-12) << k;
  // Interior: dM_y/dt = -2 (t_{k+1}^2 - t_{k-1}^2) / (t_{k+1} - t_{k-1}) = -2 (t_{k+1} + t_{k-1}).
  EXPECT_NEAR(F[1][1], -2.0 * (-2 * (0.25 + 0.0) - 0.5), 1e-12);
  EXPECT_NEAR(F[2][1], -2.0 * (-2 * (0.3 + 0.1) - 0.5), 1e-12);
  EXPECT_THROW(control_volume_forces({s[0]}, 1.0), Error);
}

TEST(ControlVolumeForce, RefusesRectanglesThatCutTheBodyOrLeaveTheDomain) {
  Box s;
  EXPECT_THROW(ControlVolumeForce(s.grid, s.ghosts, 0.45, 0.8, 0.2, 0.8), Error);   // cuts the body
  EXPECT_THROW(ControlVolumeForce(s.grid, s.ghosts, 0.0, 0.8, 0.2, 0.8), Error);    // on the boundary
  EXPECT_THROW(ControlVolumeForce(s.grid, s.ghosts, 0.38, 0.62, 0.38, 0.62), Error);  // too close
  EXPECT_NO_THROW(ControlVolumeForce(s.grid, s.ghosts, 0.3, 0.7, 0.3, 0.7));
}

}  // namespace
}  // namespace finverse::cfd
