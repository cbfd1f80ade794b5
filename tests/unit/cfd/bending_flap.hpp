// A deforming 2-D body for the flow solver's coupling tests (test_frozen_cell_kinds.cpp,
// test_warm_started_repeats.cpp, test_deforming_body.cpp): a flap of constant thickness whose
// centre line bends as y = y0 + dy + sign a sin(w t) xi^2 (xi along the flap). Each vertical
// section keeps its thickness, so the area stays constant. The vertices run along the lower side,
// then back along the upper side (counter-clockwise for sign = +1; sign = -1 mirrors the flap about
// y = y0 + dy with the same vertex order, clockwise). And a solver on the unit square with the flap
// immersed at rest.
#pragma once

#include <cmath>
#include <numbers>

#include "cfd/flow/flow_solver.hpp"

namespace finverse::cfd::test {

constexpr int kBendingFlapCells = 48;  // cells per side of the unit square

inline PolygonState bending_flap(double t, double dy, double sign = 1.0) {
  const double x0 = 0.2537, L = 0.5, y0 = 0.5, half = 0.035, a = 0.06, w = 2 * std::numbers::pi;
  const int n = 40;
  PolygonState s;
  const auto add = [&](int k, double side) {
    const double xi = static_cast<double>(k) / n;
    const double shape = xi * xi;
    s.position.push_back({x0 + L * xi, y0 + dy + sign * (a * std::sin(w * t) * shape + side * half)});
    s.velocity.push_back({0, sign * a * w * std::cos(w * t) * shape});
    s.acceleration.push_back({0, -sign * a * w * w * std::sin(w * t) * shape});
  };
  for (int k = 0; k <= n; ++k) add(k, -1);
  for (int k = n; k >= 0; --k) add(k, +1);
  return s;
}

inline FlowSolver bending_flap_solver() {
  const StretchedGrid g(Axis::uniform(0, 1, kBendingFlapCells), Axis::uniform(0, 1, kBendingFlapCells));
  FlowOptions opt;
  opt.nu = 2e-3;
  opt.dt = 0.01;
  FlowSolver s;
  s.setup(g, FlowBoundary{}, opt);
  s.immerse_deforming(bending_flap(0, 0));
  s.initialise({});
  return s;
}

}  // namespace finverse::cfd::test
