// Tests of the rigidly moving ghost-cell immersed boundary (flow_solver.hpp, moving_body.cpp):
// Galilean invariance (a body carried by a uniform stream at the stream's velocity leaves the
// stream untouched and feels no force), the re-classification after a shift of half a cell, and
// the values of freshly cleared cells next to a body started impulsively in still fluid.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cfd/flow_solver.hpp"
#include "cfd/ghost_cells.hpp"
#include "cfd/rigid_motion.hpp"
#include "cfd/surface_traction.hpp"

namespace finverse::cfd {
namespace {

// A polygonal circle with the vertices half a step off the axes (no exact ties of two edges).
Polygon cylinder(double cx, double cy, double r, int n) {
  std::vector<std::array<double, 2>> v;
  for (int k = 0; k < n; ++k) {
    const double t = 2 * std::numbers::pi * (k + 0.5) / n;
    v.push_back({cx + r * std::cos(t), cy + r * std::sin(t)});
  }
  return Polygon(v);
}

MovingBody translating(const Polygon& body, std::array<double, 2> pivot, std::array<double, 2> U) {
  return MovingBody{body, pivot, [U](double t) {
                      RigidState s;
                      s.displacement = {U[0] * t, U[1] * t};
                      s.velocity = U;
                      return s;
                    }};
}

TEST(MovingBody, BodyCarriedByAUniformStreamLeavesItUntouched) {
  // Periodic box, uniform stream U, the body translating with U: zero relative flow. Over 12
  // steps the body crosses more than a cell, so cells are cleared and covered.
  const StretchedGrid g(Axis::uniform(0, 1, 40), Axis::uniform(0, 1, 40));
  const std::array<double, 2> U{0.5, 0.25};
  const auto run = [&](bool treatment, double& force) {
    FlowOptions opt;
    opt.nu = 1e-3;
    opt.dt = 0.01;
    opt.fresh_cell_treatment = treatment;
    FlowSolver s;
    s.setup(g, FlowBoundary::all_periodic(), opt);
    const MovingBody body = translating(cylinder(0.4, 0.45, 0.12, 64), {0.4, 0.45}, U);
    s.immerse(body);
    s.initialise([&](double, double, double, double) { return std::array<double, 3>{U[0], U[1], 0}; });
    std::size_t cleared = 0;
    double worst = 0;
    for (int n = 0; n < 12; ++n) {
      s.step();
      cleared += s.freshly_cleared().size();
      for (int j = 0; j < g.ny(); ++j)
        for (int i = 0; i < g.nx(); ++i)
          if (s.fluid(i, j, 0))
            worst = std::max(worst, std::abs(s.u(0)(i, j, 0) - U[0]) + std::abs(s.u(1)(i, j, 0) - U[1]));
    }
    EXPECT_GT(cleared, 10u);
    const SurfaceTraction tr(g, *s.immersed(), s.body_polygon());
    const SurfaceLoads L = tr.evaluate(s.u(0), s.u(1), s.p(), opt.nu, 1.0, [&](double x, double y) {
      return body.velocity(s.body_state(), x, y);
    });
    force = std::abs(L.force[0]) + std::abs(L.force[1]);
    return worst;
  };
  double force = 0;
  EXPECT_LT(run(true, force), 1e-9);
  EXPECT_LT(force, 1e-9);
}

TEST(MovingBody, ReclassificationAfterAShiftOfHalfACell) {
  const StretchedGrid g(Axis::uniform(0, 1, 48), Axis::uniform(0, 1, 48));
  const double h = 1.0 / 48, dt = 0.01;
  FlowOptions opt;
  opt.dt = dt;
  FlowSolver s;
  s.setup(g, FlowBoundary::all_periodic(), opt);
  const Polygon ref = cylinder(0.5, 0.5, 0.15, 96);
  const std::array<double, 2> U{0.5 * h / dt, 0.0};  // half a cell per step
  s.immerse(translating(ref, {0.5, 0.5}, U));
  s.initialise({});
  const GhostCellSet before(g, ref);
  s.step();
  const GhostCellSet after(g, cylinder(0.5 + 0.5 * h, 0.5, 0.15, 96));
  int moved = 0;
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i) {
      ASSERT_EQ(s.immersed()->kind(i, j), after.kind(i, j)) << i << ", " << j;
      moved += before.kind(i, j) != after.kind(i, j);
    }
  EXPECT_GT(moved, 0);
  // Cleared cells: exactly those solid before and fluid after, all on the trailing side.
  std::size_t expected = 0;
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i) expected += before.solid(i, j) && after.kind(i, j) == CellKind::Fluid;
  ASSERT_EQ(s.freshly_cleared().size(), expected);
  EXPECT_GT(expected, 0u);
  for (const auto& f : s.freshly_cleared()) {
    EXPECT_TRUE(before.solid(f[0], f[1]));
    EXPECT_LT(g.xc(f[0]), 0.5);
  }
  // The intercepts lie on the shifted surface.
  for (const GhostCell& gc : s.immersed()->ghosts())
    EXPECT_NEAR(std::hypot(gc.boundary.point[0] - 0.5 - 0.5 * h, gc.boundary.point[1] - 0.5), 0.15, 2e-4);
}

TEST(MovingBody, ClearedCellsTakeValuesBetweenTheBodyAndTheFluid) {
  // A cylinder started impulsively at U in still fluid (closed box): each cleared cell lies next
  // to the body's trailing side, where the fluid is dragged along at close to U. With the
  // treatment its value is finite and in [0, U] up to the small overshoot of the interpolation.
  const StretchedGrid g(Axis::uniform(0, 1, 48), Axis::uniform(0, 0.5, 24));
  const double U = 0.2;
  FlowOptions opt;
  opt.nu = 2e-3;
  opt.dt = 0.02;
  FlowBoundary b;  // no-slip box
  FlowSolver s;
  s.setup(g, b, opt);
  s.immerse(translating(cylinder(0.4, 0.25, 0.08, 64), {0.4, 0.25}, {U, 0.0}));
  s.initialise({});
  std::size_t cleared = 0;
  for (int n = 0; n < 15; ++n) {
    s.step();
    for (const auto& f : s.freshly_cleared()) {
      const double u = s.u(0)(f[0], f[1], 0), v = s.u(1)(f[0], f[1], 0);
      ASSERT_TRUE(std::isfinite(u) && std::isfinite(v));
      EXPECT_GT(u, -0.1 * U);
      EXPECT_LT(u, 1.1 * U);
      EXPECT_LT(std::abs(v), 0.5 * U);
      ++cleared;
    }
  }
  EXPECT_GT(cleared, 5u);
}

}  // namespace
}  // namespace finverse::cfd
