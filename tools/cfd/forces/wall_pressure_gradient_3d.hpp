// The normal pressure gradient on a no-slip wall at rest from the momentum equation, in 3-D: the
// counterpart of wall_pressure_gradient.hpp for a fixed closed triangulated body.
//
// On a wall at rest the velocity and its time and tangential derivatives vanish, so the momentum
// equation reduces there to grad p = nu lap u = -nu curl(omega) (p kinematic, div u = 0):
//     dp/dn = -nu n . curl(omega),      omega = n x du/dn on the wall.
// Only the derivatives of omega along the surface enter n . curl(omega) (the normal one is
// crossed with n), so with an orthonormal tangent pair t1, t2 at the boundary intercept B
//     n . curl(omega) = n . (t1 x d(omega)/ds1 + t2 x d(omega)/ds2).
// Per ghost cell the wall vorticity is found at surface points beside B (B + k D h t_a,
// k = +-1 .. +-K along both tangents, h the local cell width, each point projected onto the body)
// from the one-sided derivative of two velocity probes along that point's normal (as
// surface_traction_3d.hpp), and its two slopes are fitted by least squares over the plane
// (s1, s2). Where a point's normal turns by more than ~25 degrees from B's (an edge or corner of
// the body) or a probe leaves the grid's cell centres (a body crossing the domain boundary, DFG
// 3D-1Z), the gradient is left 0 there: dp/dn = 0 of Mittal et al. (2008).
//
// Off by default (FlowOptions::viscous_wall_pressure; fin-cfd sphere_re100 / dfg_3d1z
// --wall-momentum-balance): in 3-D it drove the traction and the control-volume drag apart, where in
// 2-D it brought them together (docs/studies/wall_momentum_balance.md).
#pragma once

#include <array>
#include <vector>

#include "cfd/grid/field.hpp"
#include "cfd/immersed/ghost_cells.hpp"
#include "cfd/grid/stretched_grid.hpp"
#include "cfd/immersed/surface_geometry.hpp"

namespace finverse::cfd {

class WallPressureGradient3D {
 public:
  // ghosts: the fixed body's ghost cells (the stencils are built from them and keep no reference).
  WallPressureGradient3D(const StretchedGrid& grid, const GhostCellSet& ghosts, const SurfaceGeometry& body);

  // dp/dn (kinematic) at every ghost cell's intercept, in the order of ghosts.ghosts().
  std::vector<double> evaluate(const Field& u, const Field& v, const Field& w, double nu) const;

  // Ghost cells whose gradient is evaluated (the others keep dp/dn = 0).
  std::size_t active() const;

 private:
  struct WallPoint {
    Vec3 normal{};
    double probe = 0;
    PointStencil near, far;  // velocity at probe and 2 probe along the normal
  };
  struct Entry {
    std::vector<WallPoint> points;
    std::vector<double> w1, w2;  // least-squares weights of the slopes along t1 and t2
    Vec3 n{}, t1{}, t2{};
  };
  Vec3 vorticity(const WallPoint& p, const Field& u, const Field& v, const Field& w) const;

  std::vector<Entry> entries_;
};

}  // namespace finverse::cfd
