// A deforming closed 2-D body whose surface the caller sets (issue 32, the FSI coupling; seed paper
// section 2.3; Mittal et al. 2008, J. Comput. Phys. 227:4825, section 2.4; Seo & Mittal 2011,
// J. Comput. Phys. 230:7347): a polygon with a fixed vertex count and order, each vertex with its
// position, velocity and acceleration at one time level (PolygonState). Along each edge the wall's
// velocity and acceleration are interpolated linearly between its end vertices, which gives
//   - the no-slip datum u_B and the pressure's Neumann datum dp/dn = -a_B . n at a boundary
//     intercept (velocity(), acceleration() at a SurfacePoint of polygon().closest()),
//   - the body's flux through the piece of its boundary inside each cell (wall_flux()): the edges
//     are clipped by the grid lines, and over a sub-segment [t0, t1] of an edge a -> b
//         int u_B . n dl = (t1 - t0) u_B(t_mid) . (b - a) x e_z,
//     exact for the linear u_B (the cut-cell mass balance of flow_solver.hpp).
// Polygon stores its vertices counter-clockwise; a clockwise state is reversed, and the edge
// indices reported to the caller (caller_edge()) are those of the caller's order. A rigid motion
// expressed as vertex states (rigid_polygon_state()) is the same body as a MovingBody.
#pragma once

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "cfd/grid/stretched_grid.hpp"
#include "cfd/immersed/immersed_polygon.hpp"
#include "cfd/immersed/rigid_motion.hpp"

namespace finverse::cfd {

// Per-vertex state of a deforming polygon at one time level (the caller's vertex order, either
// orientation; velocity and acceleration may be empty: zero).
struct PolygonState {
  std::vector<std::array<double, 2>> position, velocity, acceleration;
};

// The vertex state of a rigidly moving body at state s (its reference polygon's vertex order).
PolygonState rigid_polygon_state(const MovingBody& body, const RigidState& s);

class DeformingPolygon {
 public:
  // Validates s (at least 3 vertices, velocity/acceleration empty or one per vertex, all finite,
  // nonzero area); `expected_vertices` > 0: the count s must have. `what` prefixes the one-line
  // finverse::Error (e.g. "flow solver: deforming body at t = 0.25").
  DeformingPolygon(const PolygonState& s, const std::string& what, std::size_t expected_vertices = 0);

  const Polygon& polygon() const { return polygon_; }
  const PolygonState& state() const { return state_; }  // as given (caller's order)
  bool reversed() const { return reversed_; }
  // Signed area of the caller's vertex order (its sign must not change while the body deforms).
  double signed_area() const { return signed_area_; }

  // Wall velocity and acceleration at a point of polygon().closest() (linear along its edge).
  std::array<double, 2> velocity(const SurfacePoint& b) const { return along(vel_, b.edge, b.edge_t); }
  std::array<double, 2> acceleration(const SurfacePoint& b) const { return along(acc_, b.edge, b.edge_t); }
  // The same on stored edge e (polygon().vertices() e -> e + 1) at parameter t in [0, 1].
  std::array<double, 2> velocity(int e, double t) const { return along(vel_, e, t); }
  // Vertex velocities in the stored (counter-clockwise) order.
  const std::vector<std::array<double, 2>>& stored_velocity() const { return vel_; }

  // The caller's edge index and local coordinate xi in [0, 1] (from its vertex e to e + 1) of
  // stored edge e at parameter t.
  std::pair<int, double> caller_edge(int e, double t) const;

  // The body's flux int u_B . n dl through its boundary inside each cell (cells are the half-open
  // boxes (lo, hi] along each axis, as the crossing rule of cut_faces), in the order of the edges;
  // `net`: their sum, d(area)/dt of the polygon, and `length`: per entry, the clipped length.
  struct CellFlux {
    std::array<int, 3> cell{};
    double flux = 0, length = 0;
  };
  std::vector<CellFlux> wall_flux(const StretchedGrid& grid, double& net) const;

 private:
  std::array<double, 2> along(const std::vector<std::array<double, 2>>& q, int e, double t) const;

  PolygonState state_;
  Polygon polygon_;
  bool reversed_ = false;
  double signed_area_ = 0;
  std::vector<std::array<double, 2>> vel_, acc_;  // stored order
};

}  // namespace finverse::cfd
