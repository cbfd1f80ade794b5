// Ghost cells of the sharp-interface immersed boundary (Mittal et al. 2008, J. Comput. Phys.
// 227:4825, section 2.2), 2-D: cells whose centre lies inside the body are solid; a solid cell with
// at least one fluid neighbour across a face is a ghost cell. From each ghost-cell centre G a probe
// along the surface normal through the boundary intercept B (the closest surface point) reaches
// the image point I = 2B - G, so B is midway between G and I. The value at I is interpolated
// bilinearly from the four surrounding cell centres; the ghost value then imposes the boundary
// condition at B to second order:
//     Dirichlet (velocity):  phi_G = 2 phi_B - phi_I
//     Neumann (pressure):    phi_G = phi_I - |I - G| dphi/dn(B)
// Where the image point's stencil contains the ghost cell itself or a solid (non-ghost) cell,
// Mittal et al. replace that node by the boundary intercept B, carrying the boundary condition:
// the interpolant phi = c1 + c2 x + c3 y + c4 x y is fitted to the remaining cell values and to
// phi(B) = phi_B (Dirichlet) or n . grad phi(B) = dphi/dn (Neumann), which gives the image value as
// sum_k w_k phi_k + w_B (boundary datum) (PointStencil). Other ghost cells in the stencil stay as
// unknowns: the ghost values are solved for together (implicitly in the momentum system, by
// sweeps in impose_*). Where the substitution leaves fewer than four usable points, or the
// bilinear fit is singular (two nodes replaced by one intercept), the fit falls back to the linear
// interpolant by least squares, still exact for linear fields. The stencil structures carry 3-D
// indices and up to 8 nodes, so the trilinear 3-D version fills the same types.
// 3-D (closed triangulated surface, surface_geometry.hpp): the same method with the cell centre
// classified by the signed distance to the surface, the intercept the closest surface point, the
// image point's value interpolated trilinearly from the eight surrounding centres, and the
// substitution fit phi = c1 + c2 x + c3 y + c4 z + c5 xy + c6 yz + c7 xz + c8 xyz (least-squares
// linear fallback: at least four usable points). A body must be at least about three cells thick
// everywhere, so that cell centres lie inside it and every ghost cell's image point lies in the
// fluid on its own side; thinner parts are not seen by the grid.
#pragma once

#include <array>
#include <cmath>
#include <vector>

#include "cfd/grid/field.hpp"
#include "cfd/grid/stretched_grid.hpp"
#include "cfd/immersed/immersed_polygon.hpp"
#include "cfd/immersed/surface_geometry.hpp"

namespace finverse::cfd {

enum class CellKind : unsigned char { Fluid = 0, Solid = 1, Ghost = 2 };

enum class BoundaryCondition { Dirichlet, Neumann, None };

// The value at a point as a linear combination of cell values plus one boundary datum.
struct PointStencil {
  int count = 0;
  std::array<std::array<int, 3>, 8> cell{};
  std::array<double, 8> weight{};
  double boundary_weight = 0;  // multiplies phi_B (Dirichlet) or dphi/dn at B (Neumann)
  double apply(const Field& q, double boundary_datum) const {
    double s = boundary_weight * boundary_datum;
    for (int k = 0; k < count; ++k) {
      const auto& c = cell[static_cast<std::size_t>(k)];
      s += weight[static_cast<std::size_t>(k)] * q(c[0], c[1], c[2]);
    }
    return s;
  }
};

struct GhostCell {
  int i = 0, j = 0, k = 0;
  SurfacePoint boundary;               // intercept B, outward normal, signed distance of G (<= 0) (3-D: x, y of them)
                                       // (> 0 only with frozen kinds: G on the fluid side of the wall)
  std::array<double, 2> image{};       // I = 2B - G (G outside the wall: I = 2G - B)
  std::array<int, 2> stencil{};        // lower-left cell (i0, j0) of the bilinear stencil of I
  std::array<double, 4> weights{};     // for (i0,j0), (i0+1,j0), (i0,j0+1), (i0+1,j0+1)
  bool stencil_all_fluid = true;       // false: needs the boundary-intercept substitution
  PointStencil dirichlet, neumann;     // image value with the boundary-intercept substitution
  // B, its outward normal and I in 3-D (2-D: z = 0); a triangulated body's intercept also carries
  // its triangle and barycentric coordinates (for interpolating vertex data; 2-D: -1).
  std::array<double, 3> intercept{}, normal{}, image_point{};
  int triangle = -1;
  std::array<double, 3> barycentric{};
  double probe = -1;                   // |I - G| where set (frozen kinds, G outside the wall)
  double probe_length() const { return probe >= 0 ? probe : 2 * std::abs(boundary.distance); }  // |I - G|
};

// A fluid cell's closed face toward a ghost cell where the wall crosses the cell between its
// centre and that face (ghost_cells_3d.cpp, near_wall_faces): side -1 the cell's lower face along
// axis, +1 its upper face.
struct NearWallFace {
  std::array<int, 3> cell{};
  int axis = 0;
  int side = 0;
};

class GhostCellSet {
 public:
  // Classifies the cells of a 2-D grid against the body. Throws finverse::Error when an image point
  // leaves the grid (the body too close to the domain boundary).
  GhostCellSet(const StretchedGrid& grid, const Polygon& body);
  // The cells' kinds from the polygon kinds_from, the ghost geometry (intercepts, normals, image
  // points) from body: the set of a coupling iteration whose kinds stay those of the step's first
  // iterate (FlowSolver::set_body_state), so that the ghost values change continuously with body.
  // A ghost centre that body has left (on the fluid side, distance d > 0) gets the image point
  // I = 2G - B, so G lies midway between B and I: phi_G = (phi_B + phi_I) / 2 (Dirichlet),
  // phi_G = phi_I - d dphi/dn (Neumann); as d -> 0 both tend to phi_B, as the usual rule does.
  GhostCellSet(const StretchedGrid& grid, const Polygon& body, const Polygon& kinds_from);
  // Several solid regions (disjoint; each ghost cell takes the surface closest to it).
  GhostCellSet(const StretchedGrid& grid, const std::vector<SolidRegion>& regions);
  // Classifies the cells of a 3-D grid against a closed triangulated surface.
  GhostCellSet(const StretchedGrid& grid, const SurfaceGeometry& body);

  int dim() const { return grid_.dim(); }
  CellKind kind(int i, int j) const { return kind_[static_cast<std::size_t>(i + grid_.nx() * j)]; }
  CellKind kind(int i, int j, int k) const {
    return kind_[static_cast<std::size_t>(i) +
                 static_cast<std::size_t>(grid_.nx()) * (static_cast<std::size_t>(j) + static_cast<std::size_t>(grid_.ny()) * static_cast<std::size_t>(k))];
  }
  bool solid(int i, int j) const { return kind(i, j) != CellKind::Fluid; }
  bool solid(int i, int j, int k) const { return kind(i, j, k) != CellKind::Fluid; }
  const std::vector<GhostCell>& ghosts() const { return ghosts_; }
  // 3-D: the closed faces of fluid cells whose centre lies within half a spacing of the wall
  // (2-D: none). Without the cut-cell balance the flow's cell-centred gradients count these faces'
  // gradients as zero (FlowSolver::cell_gradient; docs/studies/pipe_flow.md, "Fluid centres at the wall").
  const std::vector<NearWallFace>& near_wall_faces() const { return near_wall_; }

  // Bilinear (3-D: trilinear) interpolation of a cell-centred field at the ghost cell's image point.
  double image_value(const Field& q, const GhostCell& g) const;
  // Ghost values imposing phi_B at the boundary intercept, or dphi/dn there.
  double dirichlet_ghost(const Field& q, const GhostCell& g, double boundary_value) const {
    return g.probe >= 0 ? 0.5 * (boundary_value + image_value(q, g)) : 2 * boundary_value - image_value(q, g);
  }
  double neumann_ghost(const Field& q, const GhostCell& g, double normal_derivative) const {
    return image_value(q, g) - g.probe_length() * normal_derivative;
  }

  // Interpolation stencil at point x from the four surrounding cell centres; fluid and ghost cells
  // are used (except the cell `self`), other nodes are replaced by the boundary point b with the
  // condition bc (None: dropped). Throws finverse::Error when x is outside the centres' range.
  PointStencil stencil(const std::array<double, 2>& x, const SurfacePoint& b, BoundaryCondition bc,
                       std::array<int, 2> self = {-1, -1}) const;
  // 3-D: from the eight surrounding centres, trilinear, with the boundary point b (outward normal
  // n) substituted for solid nodes and `self`.
  PointStencil stencil(const std::array<double, 3>& x, const std::array<double, 3>& b, const std::array<double, 3>& n,
                       BoundaryCondition bc, std::array<int, 3> self = {-1, -1, -1}) const;
  // 3-D: fills near_wall_ from the classified cells and the ghosts' tangent planes.
  void find_near_wall_faces();

  // Ghost values that impose the conditions with the substituted stencils, by Gauss-Seidel sweeps
  // over the ghost cells (they couple where one ghost cell's image stencil holds another):
  //   Dirichlet: phi_G = 2 phi_B - phi_I, phi_B = boundary_value[g] (empty: 0);
  //   Neumann, homogeneous: phi_G = phi_I.
  void impose_dirichlet(Field& q, const std::vector<double>& boundary_value) const;
  void impose_neumann(Field& q) const;
  //   Neumann, inhomogeneous: phi_G = phi_I - |I - G| dphi/dn, dphi/dn = normal_derivative[g] at B
  //   (a moving body's pressure, rigid_motion.hpp).
  void impose_neumann(Field& q, const std::vector<double>& normal_derivative) const;
  // Sets every solid non-ghost cell to value.
  void fill_solid(Field& q, double value) const;

 private:
  // Kinds from kinds_from, ghost geometry from regions; frozen: G may lie outside the wall.
  void classify(const std::vector<SolidRegion>& kinds_from, const std::vector<SolidRegion>& regions, bool frozen);

  StretchedGrid grid_;
  std::vector<CellKind> kind_;
  std::vector<GhostCell> ghosts_;
  std::vector<NearWallFace> near_wall_;
};

}  // namespace finverse::cfd
