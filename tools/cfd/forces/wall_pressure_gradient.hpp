// The normal pressure gradient on a no-slip wall at rest, from the momentum equation (2-D).
//
// On a wall at rest the velocity and its time and tangential derivatives vanish, so the momentum
// equation reduces there to grad p = nu lap u = -nu curl(omega) (p kinematic, div u = 0). With the
// outward normal n and the tangent t = z x n this is
//     dp/dn = -nu d(omega)/ds,       omega = n_x dv/dn - n_y du/dn on the wall,
// s the arc length along t. The ghost-cell method's pressure condition dp/dn = 0 (Mittal et al.
// 2008, a boundary-layer approximation) drops this term, and at the DFG benchmarks' Reynolds
// numbers it is not small (docs/studies/wall_momentum_balance.md). Per ghost cell, the wall
// vorticity is found at surface points B + k D h t, k = +-1 .. +-K, beside its boundary intercept B
// (h the local cell width, each point projected onto the body) from the one-sided derivative of two
// velocity probes along that point's normal, the same as in surface_traction.hpp, and its slope
// along the surface is fitted by least squares. Near a corner of the body (a point's normal more
// than ~25 degrees from B's) the vorticity is singular and the gradient is left 0.
#pragma once

#include <array>
#include <vector>

#include "cfd/grid/field.hpp"
#include "cfd/immersed/ghost_cells.hpp"
#include "cfd/grid/stretched_grid.hpp"
#include "cfd/immersed/immersed_polygon.hpp"

namespace finverse::cfd {

class WallPressureGradient {
 public:
  // ghosts: the fixed body's ghost cells (the stencils are built from them and keep no reference).
  WallPressureGradient(const StretchedGrid& grid, const GhostCellSet& ghosts, const std::vector<SolidRegion>& regions);

  // dp/dn (kinematic) at every ghost cell's intercept, in the order of ghosts.ghosts().
  std::vector<double> evaluate(const Field& u, const Field& v, double nu) const;

 private:
  struct WallPoint {
    std::array<double, 2> normal{};
    double probe = 0;
    PointStencil near, far;  // velocity at probe and 2 probe along the normal
  };
  struct Entry {
    std::vector<WallPoint> points;  // along t, at arc lengths s (least-squares slope)
    std::vector<double> s;
    double sxx = 0;  // sum of (s - mean)^2; 0: a corner, gradient left 0
    double mean = 0;
  };
  double vorticity(const WallPoint& w, const Field& u, const Field& v) const;

  std::vector<Entry> entries_;
};

}  // namespace finverse::cfd
