// Tests of the wall's momentum balance dp/dn = -nu d(omega)/ds (wall_pressure_gradient.hpp) on
// a velocity field with a known wall vorticity, and of its corner rule.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "cfd/field.hpp"
#include "cfd/ghost_cells.hpp"
#include "cfd/grid.hpp"
#include "cfd/wall_pressure_gradient.hpp"

namespace finverse::cfd {
namespace {

// Around a circle of radius R at the origin, u_theta = (r - R) sin(theta), u_r = 0: no slip on the
// circle, wall vorticity omega = d(u_theta)/dr = sin(theta), so with s along e_theta (t = z x e_r)
// dp/dn = -nu cos(theta) / R. The field is smooth (polynomial in x, y over r), also inside the body,
// so ghost cells simply hold its values.
double max_error(int n) {
  const double R = 0.25, nu = 0.01;
  const StretchedGrid grid(Axis::uniform(-0.6, 0.6, n), Axis::uniform(-0.6, 0.6, n));
  const std::vector<SolidRegion> regions{{Polygon::circle(0, 0, R, 512), false}};
  const GhostCellSet ghosts(grid, regions);
  Field u(grid), v(grid);
  for (int j = 0; j < grid.ny(); ++j)
    for (int i = 0; i < grid.nx(); ++i) {
      const double x = grid.xc(i), y = grid.yc(j), r = std::hypot(x, y);
      const double s = y / r, c = x / r, ut = (r - R) * s;
      u(i, j, 0) = -ut * s;
      v(i, j, 0) = ut * c;
    }
  const WallPressureGradient wall(grid, ghosts, regions);
  const std::vector<double> g = wall.evaluate(u, v, nu);
  EXPECT_EQ(g.size(), ghosts.ghosts().size());
  double err = 0;
  for (std::size_t k = 0; k < g.size(); ++k) {
    const auto& b = ghosts.ghosts()[k].boundary.point;
    const double exact = -nu * (b[0] / std::hypot(b[0], b[1])) / R;
    err = std::max(err, std::abs(g[k] - exact));
  }
  return err / (nu / R);
}

TEST(WallPressureGradient, MatchesTheWallVorticityGradient) {
  // The fitted slope's error is a fixed fraction set by the window in cells (the header): about
  // 2 % at 24 and at 48 cells per radius; a wrong sign, tangent or scale would be off by 100 %.
  EXPECT_LT(max_error(96), 0.03);
  EXPECT_LT(max_error(192), 0.03);
}

TEST(WallPressureGradient, ZeroNearTheCornersOfABox) {
  // A square body |x|, |y| < a in v = (x^2 - a^2)(y^2 - a^2) (no slip on the box): on the face
  // x = a the wall vorticity is dv/dx = 2a (y^2 - a^2), so dp/dn = -nu 4 a y there. Within the
  // fit's window of a corner the vorticity is singular on a real flow and the gradient is left 0.
  const double a = 0.3, h = 2.0 / 80, nu = 1.0;
  const StretchedGrid grid(Axis::uniform(-1, 1, 80), Axis::uniform(-1, 1, 80));
  const std::vector<SolidRegion> regions{{Polygon({{-a, -a}, {a, -a}, {a, a}, {-a, a}}), false}};
  const GhostCellSet ghosts(grid, regions);
  Field u(grid), v(grid);
  for (int j = 0; j < grid.ny(); ++j)
    for (int i = 0; i < grid.nx(); ++i) {
      const double x = grid.xc(i), y = grid.yc(j);
      v(i, j, 0) = (x * x - a * a) * (y * y - a * a);
    }
  const std::vector<double> g = WallPressureGradient(grid, ghosts, regions).evaluate(u, v, nu);
  int corner = 0, face = 0;
  for (std::size_t k = 0; k < g.size(); ++k) {
    const auto& b = ghosts.ghosts()[k].boundary.point;
    if (std::abs(b[0] - a) < 1e-9 && std::abs(b[1]) < a - 1e-9) {  // on the face x = a
      if (a - std::abs(b[1]) < 2 * h) {
        ++corner;
        EXPECT_EQ(g[k], 0.0) << b[0] << " " << b[1];
      } else if (a - std::abs(b[1]) > 7 * h) {
        ++face;
        EXPECT_NEAR(g[k], -4 * a * nu * b[1], 0.1 * 4 * a * nu * a) << b[0] << " " << b[1];
      }
    }
  }
  EXPECT_GT(corner, 0);
  EXPECT_GT(face, 3);
}

}  // namespace
}  // namespace finverse::cfd
