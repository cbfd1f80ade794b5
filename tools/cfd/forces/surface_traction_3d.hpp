// Surface traction on the true surface of an immersed triangulated body in 3-D and the force on
// each triangle (SurfaceForces, triangulated_surface.hpp): the 3-D counterpart of
// surface_traction.hpp (DESIGN.md section 5.1: the force coefficients and the nodal loads come
// from this one traction).
//
// Each triangle is split into m^2 congruent sub-triangles (m = ceil(longest edge / (h/2)), h the
// smallest local cell width), sampled at their centroids with weight area/m^2 and the triangle's
// outward normal n. Along n two probes at d and 2d (d = the largest local cell width) are
// interpolated with the trilinear ghost-cell stencils (ghost_cells.hpp; a solid node is replaced by
// the sample point carrying the no-slip velocity). At the wall
//     p_w = 2 p(d) - p(2d),     dw/dn = [4 w(d) - w(2d)] / (2 d),     w = u - u_w,
// and the traction on the body is t = -p_w n + mu dw/dn (second order). For a body at rest or
// translating, mu dw/dn is exactly the viscous stress 2 mu S n (no-slip and continuity make the
// tangential derivatives and n . dw/dn vanish on the wall). For a rotating or deforming body u_w is
// the wall velocity at the sample point (the vertex velocities interpolated linearly), held
// constant along the probe: then mu dw/dn differs from 2 mu S n by mu (grad u_w)^T n-type terms of
// the wall's own velocity gradient, O(mu |grad u_w|), which are small against the pressure and the
// boundary-layer shear at moderate and high Re (an approximation for a flapping, bending fin).
//
// A body that crosses the domain boundary (SurfaceClip; e.g. the cylinder of DFG 3D-1Z, which
// spans the channel from wall to wall and is closed by end caps outside the domain): each triangle
// is clipped exactly against the domain box (Sutherland-Hodgman against the six planes), the
// clipped convex polygon is fanned into triangles and those are sampled as above, so only the
// wetted, in-domain part of the surface carries traction. A probe (and its sample point, the
// stencil's boundary point) between the outermost cell centre and the domain boundary is moved
// onto the outermost centre plane, and the domain boundary's own condition carries the value the
// rest of the way: the pressure has zero normal gradient on every non-periodic side (the solver's
// pressure condition), so it is taken unchanged; the velocity on a no-slip wall at rest is zero, so
// it is interpolated linearly between the wall and the centre plane, exactly as the solver's
// boundary ghost values (u_ghost = -u_1) do. Only fixed bodies and walls at rest are meant.
#pragma once

#include <vector>

#include "cfd/grid/field.hpp"
#include "cfd/immersed/ghost_cells.hpp"
#include "cfd/grid/stretched_grid.hpp"
#include "cfd/immersed/surface_geometry.hpp"
#include "cfd/immersed/triangulated_surface.hpp"

namespace finverse::cfd {

struct SurfaceSample3D {
  Vec3 point{}, normal{}, barycentric{};
  int triangle = -1;
  double area = 0;   // of the surface element
  double probe = 0;  // d
  PointStencil velocity1, velocity2, pressure1, pressure2;  // at d and 2d
};

// The part of triangle (a, b, c) inside the box [lo, hi] as a convex polygon (empty when none).
std::vector<Vec3> clip_triangle_to_box(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& lo, const Vec3& hi);

// The explicit permission for a body to cross the domain boundary, and the domain's walls.
struct SurfaceClip {
  bool enabled = false;  // false: the whole surface is sampled (it must lie inside the domain)
  // Per side (Side order: x-, x+, y-, y+, z-, z+): a no-slip wall at rest (velocity 0 on it);
  // otherwise the velocity is continued with zero normal gradient.
  std::array<bool, 6> no_slip{};
};

class SurfaceTraction3D {
 public:
  SurfaceTraction3D(const StretchedGrid& grid, const GhostCellSet& ghosts, const SurfaceGeometry& body,
                    const SurfaceClip& clip = {});

  const std::vector<SurfaceSample3D>& samples() const { return samples_; }

  // u, v, w: velocity components; p: kinematic pressure (p / rho); vertex_velocity: the wall's
  // vertex velocities (empty: at rest). Forces per triangle and their sums [N].
  SurfaceForces evaluate(const Field& u, const Field& v, const Field& w, const Field& p, double nu, double rho,
                         const std::vector<Vec3>& vertex_velocity = {}) const;

 private:
  int triangles_ = 0;
  std::vector<std::array<int, 3>> tri_;
  std::vector<SurfaceSample3D> samples_;
};

}  // namespace finverse::cfd
