// Tests of the ghost-cell immersed boundary coupled into the flow solver: the boundary-intercept
// substitution (Mittal et al. 2008) exact for linear fields, ghost values imposing a linear field
// exactly, the nonsymmetric momentum system, surface traction (buoyancy-like force in a uniform
// pressure gradient, wall shear of a linear shear flow) and a short immersed-cylinder run (mass
// conservation, mirror symmetry).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

#include "cfd/flow/flow_solver.hpp"
#include "cfd/immersed/ghost_cells.hpp"
#include "cfd/immersed/immersed_momentum_solver.hpp"
#include "cfd/immersed/immersed_polygon.hpp"
#include "cfd/forces/surface_traction.hpp"

namespace finverse::cfd {
namespace {

StretchedGrid test_grid(bool stretched) {
  if (!stretched) return StretchedGrid(Axis::uniform(0, 0.6, 96), Axis::uniform(0, 0.41, 64));
  return StretchedGrid(Axis::stretched(0, 0.6, 0.12, 0.3, 0.004, 1.08), Axis::stretched(0, 0.41, 0.12, 0.28, 0.004, 1.08));
}

double lin(double x, double y) { return 0.3 + 2.0 * x - 1.5 * y; }

Field linear_field(const StretchedGrid& g) {
  Field q(g);
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i) q(i, j, 0) = lin(g.xc(i), g.yc(j));
  return q;
}

TEST(ImmersedBoundary, SubstitutedStencilsAreExactForLinearFields) {
  const Polygon body = Polygon::circle(0.2, 0.2, 0.05, 128);
  for (bool stretched : {false, true}) {
    const StretchedGrid g = test_grid(stretched);
    const GhostCellSet set(g, body);
    const Field q = linear_field(g);
    int substituted = 0;
    for (const GhostCell& gc : set.ghosts()) {
      // No stencil node is the ghost cell itself or a solid cell.
      for (const PointStencil* st : {&gc.dirichlet, &gc.neumann})
        for (int n = 0; n < st->count; ++n) {
          const auto& c = st->cell[static_cast<std::size_t>(n)];
          EXPECT_FALSE(c[0] == gc.i && c[1] == gc.j);
          EXPECT_NE(set.kind(c[0], c[1]), CellKind::Solid);
        }
      const double exact = lin(gc.image[0], gc.image[1]);
      const double ub = lin(gc.boundary.point[0], gc.boundary.point[1]);
      const double dudn = 2.0 * gc.boundary.normal[0] - 1.5 * gc.boundary.normal[1];
      EXPECT_NEAR(gc.dirichlet.apply(q, ub), exact, 1e-12);
      EXPECT_NEAR(gc.neumann.apply(q, dudn), exact, 1e-12);
      substituted += gc.dirichlet.boundary_weight != 0.0;
    }
    EXPECT_GT(substituted, 0);  // the substitution is exercised
  }
}

TEST(ImmersedBoundary, DirichletGhostValuesReproduceALinearField) {
  const Polygon body = Polygon::circle(0.2, 0.2, 0.05, 128);
  const StretchedGrid g = test_grid(true);
  const GhostCellSet set(g, body);
  Field q = linear_field(g);
  std::vector<double> ub;
  for (const GhostCell& gc : set.ghosts()) {
    ub.push_back(lin(gc.boundary.point[0], gc.boundary.point[1]));
    q(gc.i, gc.j, 0) = 1e3;  // wrong on purpose: the sweeps must recover the coupled ghost values
  }
  set.impose_dirichlet(q, ub);
  for (const GhostCell& gc : set.ghosts()) EXPECT_NEAR(q(gc.i, gc.j, 0), lin(g.xc(gc.i), g.yc(gc.j)), 1e-11);
}

// A circle's ghost-cell momentum system on the test grid: the Helmholtz rows and the solver.
struct MomentumSystem {
  StretchedGrid g;
  GhostCellSet set;
  HelmholtzSolver hs;
  ImmersedMomentumSolver ms;

  explicit MomentumSystem(bool stretched)
      : g(test_grid(stretched)), set(g, Polygon::circle(0.2, 0.2, 0.05, 128)) {
    hs.setup(g, FaceCoefficients(g, 1.0), BoundaryConditions::all(BcType::Dirichlet));
    ms.setup(g);
  }
};

TEST(ImmersedBoundary, MomentumSystemWithGhostRowsConverges) {
  MomentumSystem sys(false);
  const StretchedGrid& g = sys.g;
  const GhostCellSet& set = sys.set;
  const HelmholtzSolver& hs = sys.hs;
  ImmersedMomentumSolver& ms = sys.ms;
  // Viscous-dominated: nu dt / h^2 = 2, far from the mass-dominated regime.
  const double h = 0.6 / 96, mass = 1.0, stiffness = 2.0 * h * h / 2;
  Field b(g), x(g);
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i) b(i, j, 0) = g.volume(i, j, 0) * std::sin(10 * g.xc(i)) * std::cos(7 * g.yc(j));
  std::vector<double> ub(set.ghosts().size(), 0.25);
  const HelmholtzStats st = ms.solve(hs, set, mass, stiffness, b, ub, 0.0, x, 1e-11, 500);
  EXPECT_TRUE(st.converged) << st.relative_residual;
  EXPECT_LT(st.iterations, 200);
  // The ghost rows hold: u_G + u_I = 2 u_B.
  for (const GhostCell& gc : set.ghosts())
    EXPECT_NEAR(x(gc.i, gc.j, 0) + gc.dirichlet.apply(x, 0.25), 0.5, 1e-8);
}

TEST(ImmersedBoundary, MomentumSolvePinsSolidCellsAndMatchesItsOperator) {
  // The solve keeps the rows' scales and solid cells of its own; the public operator must give the
  // residual it reports, and the solid rows must pin u to the body's value.
  MomentumSystem sys(true);
  const StretchedGrid& g = sys.g;
  const GhostCellSet& set = sys.set;
  const HelmholtzSolver& hs = sys.hs;
  ImmersedMomentumSolver& ms = sys.ms;
  const double mass = 1.0, stiffness = 1e-5;
  Field b(g), x(g), mx(g);
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i) b(i, j, 0) = g.volume(i, j, 0) * std::cos(9 * g.xc(i) + 4 * g.yc(j));
  const std::vector<double> ub(set.ghosts().size(), -0.4);
  const double solid_value = 0.3;
  const HelmholtzStats st = ms.solve(hs, set, mass, stiffness, b, ub, solid_value, x, 1e-10, 500);
  ASSERT_TRUE(st.converged) << st.relative_residual;
  int solid = 0;
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i)
      if (set.kind(i, j) == CellKind::Solid) {
        EXPECT_NEAR(x(i, j, 0), solid_value, 1e-9);
        ++solid;
      }
  EXPECT_GT(solid, 0);
  ImmersedMomentumSolver::apply(hs, set, mass, stiffness, x, mx);
  Field r(g);
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i) r(i, j, 0) = b(i, j, 0) - mx(i, j, 0);
  EXPECT_DOUBLE_EQ(norm2(r) / norm2(b), st.relative_residual);
}

TEST(ImmersedBoundary, ForceInAUniformPressureGradientIsTheBuoyancyIntegral) {
  const Polygon body = Polygon::circle(0.2, 0.2, 0.05, 96);
  for (bool stretched : {false, true}) {
    const StretchedGrid g = test_grid(stretched);
    const GhostCellSet set(g, body);
    const SurfaceTraction tr(g, set, body);
    Field u(g), v(g), p(g);
    const double gx = 3.0, gy = -2.0, rho = 1000;
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) p(i, j, 0) = 5.0 + gx * g.xc(i) + gy * g.yc(j);
    const SurfaceLoads L = tr.evaluate(u, v, p, 1e-3, rho);
    // F = -oint p n ds = -rho grad p * area (Archimedes), exactly for a linear p on a polygon.
    EXPECT_NEAR(L.force[0], -rho * gx * body.area(), 1e-9 * rho * body.area());
    EXPECT_NEAR(L.force[1], -rho * gy * body.area(), 1e-9 * rho * body.area());
    EXPECT_EQ(L.viscous_force[0], 0.0);
    EXPECT_NEAR(tr.wall_pressure(p, 0.15, 0.2), 5.0 + gx * 0.15 + gy * 0.2, 1e-12);
  }
}

TEST(ImmersedBoundary, QuadraticWallExtrapolationIsExactForAFieldQuadraticAlongTheNormal) {
  // An octagon in p = u = v = x y: bilinear, so the probes' interpolation is exact, and along a
  // face normal n quadratic, p(t) = p_w + g t + c t^2 with c = n_x n_y (+-1/2 on the four faces at
  // 45 degrees). The linear extrapolation misses p_w by -2 c d^2; the quadratic one and its
  // derivative are exact.
  std::vector<std::array<double, 2>> corners;
  for (int k = 0; k < 8; ++k) {
    const double t = std::numbers::pi * (0.125 + 0.25 * k);
    corners.push_back({0.3 + 0.1 * std::cos(t), 0.2 + 0.1 * std::sin(t)});
  }
  const Polygon body(corners);
  const auto near_corner = [&](const SurfaceSample& s) {
    for (const auto& c : corners)
      if (std::hypot(s.point[0] - c[0], s.point[1] - c[1]) < 4 * s.probe) return true;  // stencils see the next face
    return false;
  };
  for (bool stretched : {false, true}) {
    const StretchedGrid g = test_grid(stretched);
    const GhostCellSet set(g, body);
    const SurfaceTraction linear(g, set, body), quadratic(g, set, body, WallExtrapolation::Quadratic);
    Field q(g), zero(g);
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) q(i, j, 0) = g.xc(i) * g.yc(j);
    const double rho = 2.0, nu = 1e-3;
    const SurfaceLoads Ll = linear.evaluate(zero, zero, q, nu, rho), Lq = quadratic.evaluate(zero, zero, q, nu, rho);
    int checked = 0, diagonal = 0;
    for (std::size_t n = 0; n < quadratic.samples().size(); ++n) {
      const SurfaceSample& s = quadratic.samples()[n];
      if (near_corner(s)) continue;
      const double x = s.point[0], y = s.point[1], d = s.probe, c = s.normal[0] * s.normal[1];
      EXPECT_NEAR(Lq.pressure[n], rho * x * y, 1e-12);
      EXPECT_NEAR(Ll.pressure[n], rho * (x * y - 2 * c * d * d), 1e-12);
      ++checked;
      if (std::abs(c) > 0.49) {
        EXPECT_GT(std::abs(Ll.pressure[n] - rho * x * y), 0.9 * rho * d * d);
        ++diagonal;
      }
    }
    EXPECT_GT(checked, 40);
    EXPECT_GT(diagonal, 20);
    const auto& m = corners[0];  // the middle of the face between the first two corners
    const double xm = 0.5 * (m[0] + corners[1][0]), ym = 0.5 * (m[1] + corners[1][1]);
    EXPECT_NEAR(quadratic.wall_pressure(q, xm, ym), xm * ym, 1e-12);
    // The wall derivative, with the wall datum x_s y_s of one sample (a body moving at that
    // velocity): w = x y - x_s y_s vanishes there and dw/dn = y_s n_x + x_s n_y.
    int derivatives = 0;
    for (std::size_t n = 0; n < quadratic.samples().size(); n += 7) {
      const SurfaceSample& s = quadratic.samples()[n];
      if (near_corner(s)) continue;
      const double x = s.point[0], y = s.point[1];
      const auto wall = [&](double, double) { return std::array<double, 2>{x * y, x * y}; };
      const SurfaceLoads W = quadratic.evaluate(q, q, zero, nu, rho, wall);
      const double dwdn = y * s.normal[0] + x * s.normal[1];
      EXPECT_NEAR(W.traction[n][0], rho * nu * dwdn, 1e-12);
      EXPECT_NEAR(W.traction[n][1], rho * nu * dwdn, 1e-12);
      ++derivatives;
    }
    EXPECT_GT(derivatives, 5);
  }
}

TEST(ImmersedBoundary, WallShearOfALinearShearFlow) {
  // A square body; above it u = gamma (y - top): on the top face the traction is mu gamma along x.
  const double top = 0.25, gamma = 4.0, nu = 1e-3, rho = 2.0;
  const Polygon body({{0.15, 0.15}, {0.25, 0.15}, {0.25, top}, {0.15, top}});
  const StretchedGrid g(Axis::uniform(0, 0.4, 64), Axis::uniform(0, 0.41, 64));
  const GhostCellSet set(g, body);
  const SurfaceTraction tr(g, set, body);
  Field u(g), v(g), p(g);
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i) u(i, j, 0) = gamma * (g.yc(j) - top);
  const SurfaceLoads L = tr.evaluate(u, v, p, nu, rho);
  int checked = 0;
  for (std::size_t n = 0; n < tr.samples().size(); ++n) {
    const SurfaceSample& s = tr.samples()[n];
    if (s.normal[1] < 0.999 || s.point[0] < 0.16 || s.point[0] > 0.24) continue;  // top face, off the corners
    EXPECT_NEAR(L.traction[n][0], rho * nu * gamma, 1e-12);
    EXPECT_NEAR(L.traction[n][1], 0.0, 1e-12);
    ++checked;
  }
  EXPECT_GT(checked, 10);
}

TEST(ImmersedBoundary, CylinderInASymmetricChannelConservesMassAndHasNoLift) {
  // Re = Um D / nu = 20 at a coarse grid, 30 steps: divergence-free faces, no flux into the body,
  // and mirror symmetry about the channel's centre line (a centred cylinder has zero lift).
  const StretchedGrid g(Axis::uniform(0, 1.0, 80), Axis::uniform(0, 0.4, 32));
  FlowBoundary b;
  b[Side::XLo].type = FlowBcType::Inlet;
  b[Side::XLo].profile = InletProfile::Parabolic;
  b[Side::XLo].speed = 0.2;
  b[Side::XHi].type = FlowBcType::ConvectiveOutlet;
  FlowOptions opt;
  opt.nu = 1e-3;
  opt.dt = 0.02;
  opt.helmholtz_rtol = 1e-11;
  FlowSolver s;
  s.setup(g, b, opt);
  // Vertices half a step off the axes: a ghost centre on a diagonal through a vertex of the n-gon
  // would be equidistant from two edges, a tie that no ordering of the edges breaks symmetrically.
  std::vector<std::array<double, 2>> v;
  for (int k = 0; k < 64; ++k) {
    const double t = 2 * std::numbers::pi * (k + 0.5) / 64;
    v.push_back({0.3 + 0.05 * std::cos(t), 0.2 + 0.05 * std::sin(t)});
  }
  const Polygon body(v);
  s.immerse(body);
  s.initialise({});
  for (int n = 0; n < 30; ++n) {
    const StepStats st = s.step();
    EXPECT_LT(st.max_divergence, 1e-7);
    EXPECT_LT(st.poisson_iterations, 40);
  }
  const SurfaceTraction tr(g, *s.immersed(), body);
  const SurfaceLoads L = tr.evaluate(s.u(0), s.u(1), s.p(), opt.nu, 1.0);
  EXPECT_GT(L.force[0], 0.0);  // drag downstream
  EXPECT_LT(std::abs(L.force[1]), 1e-9 * L.force[0]);
  double worst = 0;
  for (int j = 0; j < g.ny() / 2; ++j)
    for (int i = 0; i < g.nx(); ++i)
      if (s.fluid(i, j, 0))
        worst = std::max(worst, std::abs(s.u(0)(i, j, 0) - s.u(0)(i, g.ny() - 1 - j, 0)) +
                                    std::abs(s.u(1)(i, j, 0) + s.u(1)(i, g.ny() - 1 - j, 0)));
  EXPECT_LT(worst, 1e-9);
}

}  // namespace
}  // namespace finverse::cfd
