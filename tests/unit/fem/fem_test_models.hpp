// Small models shared by the FEM unit tests.
#pragma once

#include "fem/model.hpp"

namespace finverse::fem::test {

// Straight cantilever along x from the origin, clamped at node 0, width along y, thickness
// along z; section tapers linearly from (b0, t0) at the root to (b1, t1) at the tip.
inline Model cantilever(int elements, double length, double E, double b0, double t0, double b1,
                        double t1, double density = 1000.0) {
  Model m;
  const int mat = m.add_material({"test", E, 0.3, density});
  for (int i = 0; i <= elements; ++i) m.add_node(Vec3(length * i / elements, 0, 0));
  for (int i = 0; i < elements; ++i) {
    const double x0 = static_cast<double>(i) / elements, x1 = static_cast<double>(i + 1) / elements;
    TaperedRectangle s{{b0 + (b1 - b0) * x0, b0 + (b1 - b0) * x1},
                       {t0 + (t1 - t0) * x0, t0 + (t1 - t0) * x1}};
    m.add_beam(i, i + 1, mat, s, Vec3(0, 1, 0));
  }
  m.fix_node(0);
  return m;
}

// Planar lattice of n x n nodes in the x-y plane joined by beams along x and y, clamped along
// the edge x = 0: a stand-in for a fin with rays and cross-links.
inline Model lattice(int n, double spacing = 0.01, double E = 1e9) {
  Model m;
  const int mat = m.add_material({"lattice", E, 0.35, 1100});
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) m.add_node(Vec3(spacing * i, spacing * j, 0));
  const auto s = TaperedRectangle::uniform(0.002, 0.0005);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * n + i;
      if (i + 1 < n) m.add_beam(a, a + 1, mat, s, Vec3(0, 1, 0));
      if (j + 1 < n) m.add_beam(a, a + n, mat, s, Vec3(1, 0, 0));
    }
  for (int j = 0; j < n; ++j) m.fix_node(j * n);
  return m;
}

}  // namespace finverse::fem::test
