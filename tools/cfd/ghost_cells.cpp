// Ghost-cell classification, probes and image-point stencils; see ghost_cells.hpp.
#include "cfd/ghost_cells.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace finverse::cfd {

namespace {
// Index c with centre(c) <= x < centre(c+1), or -1 when x is outside the centres' range.
int lower_centre(const Axis& a, double x) {
  const int n = a.size();
  if (n < 2 || x < a.centre(0) || x > a.centre(n - 1)) return -1;
  int lo = 0, hi = n - 1;  // centre(lo) <= x <= centre(hi)
  while (hi - lo > 1) {
    const int mid = (lo + hi) / 2;
    (a.centre(mid) <= x ? lo : hi) = mid;
  }
  return lo;
}
}  // namespace

GhostCellSet::GhostCellSet(const StretchedGrid& grid, const Polygon& body) : grid_(grid) {
  if (grid.dim() != 2) throw Error("immersed boundary: the polygon body needs a 2-D grid");
  const int nx = grid.nx(), ny = grid.ny();
  kind_.assign(grid.cells(), CellKind::Fluid);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      if (body.contains(grid.xc(i), grid.yc(j))) kind_[static_cast<std::size_t>(i + nx * j)] = CellKind::Solid;
  const auto fluid = [&](int i, int j) {
    return i >= 0 && j >= 0 && i < nx && j < ny && kind_[static_cast<std::size_t>(i + nx * j)] == CellKind::Fluid;
  };
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      if (fluid(i, j) || !(fluid(i - 1, j) || fluid(i + 1, j) || fluid(i, j - 1) || fluid(i, j + 1))) continue;
      kind_[static_cast<std::size_t>(i + nx * j)] = CellKind::Ghost;
      GhostCell g;
      g.i = i;
      g.j = j;
      const double x = grid.xc(i), y = grid.yc(j);
      g.boundary = body.closest(x, y);
      g.image = {2 * g.boundary.point[0] - x, 2 * g.boundary.point[1] - y};
      const int i0 = lower_centre(grid.axis(0), g.image[0]), j0 = lower_centre(grid.axis(1), g.image[1]);
      if (i0 < 0 || j0 < 0)
        throw Error("immersed boundary: the image point of ghost cell (" + std::to_string(i) + ", " + std::to_string(j) +
                    ") lies outside the grid (body too close to the domain boundary)");
      g.stencil = {i0, j0};
      const double tx = (g.image[0] - grid.xc(i0)) / (grid.xc(i0 + 1) - grid.xc(i0));
      const double ty = (g.image[1] - grid.yc(j0)) / (grid.yc(j0 + 1) - grid.yc(j0));
      g.weights = {(1 - tx) * (1 - ty), tx * (1 - ty), (1 - tx) * ty, tx * ty};
      ghosts_.push_back(g);
    }
  // Stencil fluidity is known only after every cell is classified.
  for (GhostCell& g : ghosts_) {
    const int i0 = g.stencil[0], j0 = g.stencil[1];
    g.stencil_all_fluid = fluid(i0, j0) && fluid(i0 + 1, j0) && fluid(i0, j0 + 1) && fluid(i0 + 1, j0 + 1);
  }
}

double GhostCellSet::image_value(const Field& q, const GhostCell& g) const {
  const int i0 = g.stencil[0], j0 = g.stencil[1];
  return g.weights[0] * q(i0, j0, 0) + g.weights[1] * q(i0 + 1, j0, 0) + g.weights[2] * q(i0, j0 + 1, 0) +
         g.weights[3] * q(i0 + 1, j0 + 1, 0);
}

}  // namespace finverse::cfd
