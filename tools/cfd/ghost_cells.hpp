// Ghost cells of the sharp-interface immersed boundary (Mittal et al. 2008, J. Comput. Phys.
// 227:4825, section 2.2), 2-D: cells whose centre lies inside the body are solid; a solid cell with
// at least one fluid neighbour across a face is a ghost cell. From each ghost-cell centre G a probe
// along the surface normal through the boundary intercept B (the closest surface point) reaches
// the image point I = 2B - G, so B is midway between G and I. The value at I is interpolated
// bilinearly from the four surrounding cell centres; the ghost value then imposes the boundary
// condition at B to second order:
//     Dirichlet (velocity):  phi_G = 2 phi_B - phi_I
//     Neumann (pressure):    phi_G = phi_I - |I - G| dphi/dn(B)
// Where the image point's stencil contains a non-fluid cell, Mittal et al. replace that node by
// the boundary intercept; that substitution and the coupling of the ghost values into the
// momentum and pressure systems are the next step (not implemented here): this file provides the
// classification, the probes and the interpolation stencils.
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "cfd/field.hpp"
#include "cfd/grid.hpp"
#include "cfd/immersed_polygon.hpp"

namespace finverse::cfd {

enum class CellKind : unsigned char { Fluid = 0, Solid = 1, Ghost = 2 };

struct GhostCell {
  int i = 0, j = 0;
  SurfacePoint boundary;               // intercept B, outward normal, signed distance of G (<= 0)
  std::array<double, 2> image{};       // I = 2B - G
  std::array<int, 2> stencil{};        // lower-left cell (i0, j0) of the bilinear stencil of I
  std::array<double, 4> weights{};     // for (i0,j0), (i0+1,j0), (i0,j0+1), (i0+1,j0+1)
  bool stencil_all_fluid = true;       // false: needs the boundary-intercept substitution
  double probe_length() const { return 2 * std::abs(boundary.distance); }  // |I - G|
};

class GhostCellSet {
 public:
  // Classifies the cells of a 2-D grid against the body. Throws finverse::Error when an image point
  // leaves the grid (the body too close to the domain boundary).
  GhostCellSet(const StretchedGrid& grid, const Polygon& body);

  CellKind kind(int i, int j) const { return kind_[static_cast<std::size_t>(i + grid_.nx() * j)]; }
  bool solid(int i, int j) const { return kind(i, j) != CellKind::Fluid; }
  const std::vector<GhostCell>& ghosts() const { return ghosts_; }

  // Bilinear interpolation of a cell-centred field at the ghost cell's image point.
  double image_value(const Field& q, const GhostCell& g) const;
  // Ghost values imposing phi_B at the boundary intercept, or dphi/dn there.
  double dirichlet_ghost(const Field& q, const GhostCell& g, double boundary_value) const {
    return 2 * boundary_value - image_value(q, g);
  }
  double neumann_ghost(const Field& q, const GhostCell& g, double normal_derivative) const {
    return image_value(q, g) - g.probe_length() * normal_derivative;
  }

 private:
  StretchedGrid grid_;
  std::vector<CellKind> kind_;
  std::vector<GhostCell> ghosts_;
};

}  // namespace finverse::cfd
