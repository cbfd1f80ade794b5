// Tests of the cut-cell face apertures (cut_faces.hpp): exact apertures and fluid centroids of an
// axis-aligned rectangle, chord lengths of a circle, and the identity the cut-cell mass balance
// rests on: over the fluid part of every cell, the flux of a rigid velocity field through the
// faces' fluid parts (aperture times face length, at the fluid centroid) is minus its flux through
// the piece of the body surface inside the cell, which is computed here independently by clipping
// the polygon's edges to the cell.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "cfd/immersed/cut_faces.hpp"

namespace finverse::cfd {
namespace {

// Solid length and centroid of [a, b] overlapped with [lo, hi].
double overlap(double a, double b, double lo, double hi) { return std::max(0.0, std::min(b, hi) - std::max(a, lo)); }

TEST(CutFaces, RectangleGivesExactAperturesAndFluidCentroids) {
  const StretchedGrid g(Axis::uniform(0, 1, 10), Axis::stretched(0, 1, 0.3, 0.7, 0.08, 1.1));
  const double x0 = 0.23, x1 = 0.61, y0 = 0.352, y1 = 0.718;
  const Polygon box({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}});
  const CutFaces cf = cut_faces(g, box);
  int partial = 0;
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i <= g.nx(); ++i) {  // x faces
      const double x = g.axis(0).face(i), a = g.axis(1).face(j), b = g.axis(1).face(j + 1);
      const double solid = (x > x0 && x < x1) ? overlap(a, b, y0, y1) : 0.0;
      const double alpha = 1 - solid / (b - a);
      ASSERT_NEAR(cf.aperture(0, i, j, 0), alpha, 1e-12) << i << ", " << j;
      if (alpha > 0 && alpha < 1) {
        ++partial;
        // The fluid part is the one interval of [a, b] outside [y0, y1].
        const double f0 = a < y0 ? a : std::max(a, y1), f1 = a < y0 ? std::min(b, y0) : b;
        EXPECT_NEAR(cf.centroid(0, i, j, 0), 0.5 * (f0 + f1), 1e-12) << i << ", " << j;
      } else {
        EXPECT_NEAR(cf.centroid(0, i, j, 0), g.yc(j), 1e-12);
      }
    }
  for (int j = 0; j <= g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i) {  // y faces
      const double y = g.axis(1).face(j), a = g.axis(0).face(i), b = g.axis(0).face(i + 1);
      const double solid = (y > y0 && y < y1) ? overlap(a, b, x0, x1) : 0.0;
      ASSERT_NEAR(cf.aperture(1, i, j, 0), 1 - solid / (b - a), 1e-12) << i << ", " << j;
      partial += solid > 0 && solid < b - a;
    }
  EXPECT_GT(partial, 8);
}

TEST(CutFaces, CircleApertureDefectsAddUpToItsChords) {
  const StretchedGrid g(Axis::uniform(0, 1, 32), Axis::uniform(0, 1, 32));
  const double r = 0.3;
  const Polygon c = Polygon::circle(0.5, 0.5, r, 2000);
  const CutFaces cf = cut_faces(g, c);
  for (int i = 1; i < g.nx(); ++i) {
    const double x = g.axis(0).face(i);
    double solid = 0;
    for (int j = 0; j < g.ny(); ++j) solid += (1 - cf.aperture(0, i, j, 0)) * g.dy(j);
    const double chord = std::abs(x - 0.5) < r ? 2 * std::sqrt(r * r - (x - 0.5) * (x - 0.5)) : 0.0;
    EXPECT_NEAR(solid, chord, 2e-6) << "x = " << x;
  }
}

// Flux of u through the part of segment p -> q inside [xl, xh] x [yl, yh], normal (dy, -dx) / |pq|
// (outward for a counter-clockwise polygon), by Liang-Barsky clipping and the midpoint rule (exact
// for linear u).
template <class F>
double clipped_flux(std::array<double, 2> p, std::array<double, 2> q, double xl, double xh, double yl, double yh, F u) {
  double t0 = 0, t1 = 1;
  const double dx = q[0] - p[0], dy = q[1] - p[1];
  const double P[4] = {-dx, dx, -dy, dy}, Q[4] = {p[0] - xl, xh - p[0], p[1] - yl, yh - p[1]};
  for (int k = 0; k < 4; ++k) {
    if (P[k] == 0) {
      if (Q[k] < 0) return 0;
      continue;
    }
    const double t = Q[k] / P[k];
    if (P[k] < 0) t0 = std::max(t0, t);
    else t1 = std::min(t1, t);
  }
  if (t1 <= t0) return 0;
  const double tm = 0.5 * (t0 + t1);
  const auto v = u(p[0] + tm * dx, p[1] + tm * dy);
  return (t1 - t0) * (v[0] * dy - v[1] * dx);
}

TEST(CutFaces, RigidFluxThroughFluidFacesBalancesTheBodyPieceInEveryCell) {
  const StretchedGrid g(Axis::stretched(0, 1, 0.3, 0.7, 0.04, 1.1), Axis::uniform(0, 1, 24));
  const Polygon body = Polygon::circle(0.47, 0.52, 0.17, 96);
  const CutFaces cf = cut_faces(g, body);
  const double U = 0.7, V = -0.4, Om = 2.3, xc = 0.47, yc = 0.52;
  const auto u = [&](double x, double y) { return std::array<double, 2>{U - Om * (y - yc), V + Om * (x - xc)}; };
  const auto& v = body.vertices();
  int cut = 0;
  double worst = 0;
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i) {
      double faces = 0;  // out of the cell through the fluid parts of its faces
      bool partial = false;
      for (int d = 0; d < 2; ++d)
        for (int side = 0; side < 2; ++side) {
          const int fi = i + (d == 0 ? side : 0), fj = j + (d == 1 ? side : 0);
          const double a = cf.aperture(d, fi, fj, 0), t = cf.centroid(d, fi, fj, 0);
          partial = partial || (a > 0 && a < 1);
          const double len = d == 0 ? g.dy(j) : g.dx(i);
          const auto w = d == 0 ? u(g.axis(0).face(fi), t) : u(t, g.axis(1).face(fj));
          faces += (side ? 1.0 : -1.0) * a * len * w[static_cast<std::size_t>(d)];
        }
      if (!partial) continue;
      ++cut;
      // Out of the fluid through the body piece: along -n of the polygon's outward normal.
      double piece = 0;
      for (std::size_t e = 0; e < v.size(); ++e)
        piece -= clipped_flux(v[e], v[(e + 1) % v.size()], g.axis(0).face(i), g.axis(0).face(i + 1),
                              g.axis(1).face(j), g.axis(1).face(j + 1), u);
      worst = std::max(worst, std::abs(faces + piece));
    }
  EXPECT_GT(cut, 25);
  EXPECT_LT(worst, 1e-12);
}

}  // namespace
}  // namespace finverse::cfd
