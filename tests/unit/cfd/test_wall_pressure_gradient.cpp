// Tests of the wall's momentum balance dp/dn = -nu d(omega)/ds (wall_pressure_gradient.hpp) on
// a velocity field with a known wall vorticity, and of its corner rule; in 3-D dp/dn =
// -nu n . curl(omega) around a sphere and the rule at a box's edges (wall_pressure_gradient_3d.hpp).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "cfd/grid/field.hpp"
#include "cfd/immersed/ghost_cells.hpp"
#include "cfd/grid/stretched_grid.hpp"
#include "cfd/immersed/surface_shapes.hpp"
#include "cfd/forces/wall_pressure_gradient.hpp"
#include "cfd/forces/wall_pressure_gradient_3d.hpp"

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


// u = (r - R) w(x) around a sphere of radius R at the origin: no slip on the sphere, du/dn = w there,
// so the wall vorticity is F = n x w (n = x / r), and n . curl(omega) = n . curl(F) on the wall
// (the (r - R) curl(w) part of omega contributes n x curl(w), normal to n). The reference curl(F)
// is taken by central differences of F. w is an arbitrary smooth field; ghost cells hold u's values.
Vec3 w_field(double x, double y, double z) { return {-y + 0.4 * z, x + 1.2 * x * z, 0.5 * y + x * x}; }
Vec3 wall_vorticity(double x, double y, double z) {
  const double r = std::sqrt(x * x + y * y + z * z);
  const Vec3 n{x / r, y / r, z / r}, w = w_field(x, y, z);
  return {n[1] * w[2] - n[2] * w[1], n[2] * w[0] - n[0] * w[2], n[0] * w[1] - n[1] * w[0]};
}

TEST(WallPressureGradient3D, MatchesTheCurlOfTheWallVorticityOnASphere) {
  const double R = 0.25, nu = 0.01;
  const int n = 80;  // 16.7 cells per radius: the fit's window (6 cells) stays within 25 degrees
  const StretchedGrid grid(Axis::uniform(-0.6, 0.6, n), Axis::uniform(-0.6, 0.6, n), Axis::uniform(-0.6, 0.6, n));
  const SurfaceGeometry body(icosphere({0, 0, 0}, R, 5));
  const GhostCellSet ghosts(grid, body);
  Field u(grid), v(grid), w(grid);
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const double x = grid.xc(i), y = grid.yc(j), z = grid.zc(k), r = std::sqrt(x * x + y * y + z * z);
        const Vec3 f = w_field(x, y, z);
        u(i, j, k) = (r - R) * f[0];
        v(i, j, k) = (r - R) * f[1];
        w(i, j, k) = (r - R) * f[2];
      }
  const WallPressureGradient3D wall(grid, ghosts, body);
  EXPECT_EQ(wall.active(), ghosts.ghosts().size());
  const std::vector<double> g = wall.evaluate(u, v, w, nu);
  ASSERT_EQ(g.size(), ghosts.ghosts().size());
  double err = 0, scale = 0, rms = 0;
  for (std::size_t q = 0; q < g.size(); ++q) {
    const Vec3& b = ghosts.ghosts()[q].intercept;
    const double e = 1e-5;
    Vec3 d[3];  // d[a] = dF/dx_a
    for (int a = 0; a < 3; ++a) {
      Vec3 p = b, m = b;
      p[static_cast<std::size_t>(a)] += e;
      m[static_cast<std::size_t>(a)] -= e;
      const Vec3 fp = wall_vorticity(p[0], p[1], p[2]), fm = wall_vorticity(m[0], m[1], m[2]);
      for (std::size_t c = 0; c < 3; ++c) d[a][c] = (fp[c] - fm[c]) / (2 * e);
    }
    const Vec3 curl{d[1][2] - d[2][1], d[2][0] - d[0][2], d[0][1] - d[1][0]};
    const double r = std::sqrt(b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
    const double exact = -nu * (b[0] * curl[0] + b[1] * curl[1] + b[2] * curl[2]) / r;
    err = std::max(err, std::abs(g[q] - exact));
    scale = std::max(scale, std::abs(exact));
    rms += (g[q] - exact) * (g[q] - exact);
  }
  // Like the 2-D fit (about 2 % at 24 and 48 cells per radius), plus the facets' normals: measured
  // rms 1.7 % and largest 7 % of the largest value (3 % and 11 % with 4 subdivisions, 1.2 % and
  // 5 % with 6 at twice the cells). A wrong sign, tangent or scale is off by 100 %.
  EXPECT_LT(std::sqrt(rms / static_cast<double>(g.size())), 0.03 * scale);
  EXPECT_LT(err, 0.1 * scale) << "largest error " << err << " of " << scale;
}

TEST(WallPressureGradient3D, ZeroNearTheEdgesOfABox) {
  // The cube |x|, |y|, |z| < a in v = (x^2 - a^2) y (no slip on the faces x = +-a): there the wall
  // vorticity is (0, 0, 2 a y) sign(x), whose curl gives dp/dn = -2 a nu. Within the fit's window
  // of an edge the normals turn by 90 degrees and the gradient is left 0.
  const double a = 0.42, h = 2.0 / 40, nu = 1.0;
  const StretchedGrid grid(Axis::uniform(-1, 1, 40), Axis::uniform(-1, 1, 40), Axis::uniform(-1, 1, 40));
  const SurfaceGeometry body(box_surface({-a, -a, -a}, {a, a, a}));
  const GhostCellSet ghosts(grid, body);
  Field u(grid), v(grid), w(grid);
  for (int k = 0; k < 40; ++k)
    for (int j = 0; j < 40; ++j)
      for (int i = 0; i < 40; ++i) v(i, j, k) = (grid.xc(i) * grid.xc(i) - a * a) * grid.yc(j);
  const std::vector<double> g = WallPressureGradient3D(grid, ghosts, body).evaluate(u, v, w, nu);
  int near_edge = 0, inside_face = 0;
  for (std::size_t q = 0; q < g.size(); ++q) {
    const Vec3& b = ghosts.ghosts()[q].intercept;
    if (std::abs(std::abs(b[0]) - a) > 1e-9) continue;  // on a face x = +-a
    const double edge = a - std::max(std::abs(b[1]), std::abs(b[2]));
    if (edge < 2 * h) {
      ++near_edge;
      EXPECT_EQ(g[q], 0.0) << b[0] << " " << b[1] << " " << b[2];
    } else if (edge > 7 * h) {
      ++inside_face;
      EXPECT_NEAR(g[q], -2 * a * nu, 0.1 * 2 * a * nu) << b[0] << " " << b[1] << " " << b[2];
    }
  }
  EXPECT_GT(near_edge, 20);
  EXPECT_GT(inside_face, 4);
}
}  // namespace
}  // namespace finverse::cfd
