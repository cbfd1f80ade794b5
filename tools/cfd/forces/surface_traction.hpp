// Surface traction on the true surface of an immersed body and its integral, the hydrodynamic
// force (DESIGN.md section 5.1: force coefficients and nodal loads come from this one traction).
//
// The surface is sampled at the midpoints of sub-segments of the polygon's edges (no longer than
// half a local cell), each with its outward normal n and length ds. Along n two probes at
// distances d and 2d (d = the larger local cell width) are interpolated from the cell values with
// the ghost-cell stencils of ghost_cells.hpp (fluid and ghost cells; a solid node is replaced by
// the surface point itself, carrying the no-slip velocity). Then, at the wall,
//     p_w = 2 p(d) - p(2d)                                   (linear extrapolation, O(d^2)),
//     du/dn = [4 (u(d) - u_w) - (u(2d) - u_w)] / (2 d)       (one-sided, O(d^2)),
// and the traction on the body is t = -p_w n + mu du/dn. For a body at rest (or translating) the
// tangential derivatives of u vanish on the wall and continuity gives n . du/dn = 0 there, so
// mu du/dn is exactly the viscous stress vector 2 mu S n. Force per unit depth: F = sum t ds.
// A moving rigid body (rigid_motion.hpp): the same with the velocity relative to the rigid-body
// field, w = u - u_B(x) (the wall datum of the substituted nodes is u_B at the sample point). A
// rigid motion has no strain, S(u) = S(w), and w = 0 on the wall with div w = 0, so mu dw/dn is
// again the exact viscous stress of a translating and rotating wall.
// A deforming body (deforming_polygon.hpp): the wall velocity u_w is linear along each edge, with
// the tangential derivative g = du_w/ds constant on it; with w = u - u_w(sample point) the probes
// give du/dn, and on a straight no-slip wall continuity (du_n/dn = -g . t) and the wall's own
// motion (du_n/ds = g . n) complete the viscous stress:
//     2 mu S n = mu [du/dn + (g . n) t - (g . t) n],     t = e_z x n,
// which for a rigid motion (g = -Omega n) is the rigid body's mu d(u - u_B)/dn above.
// WallExtrapolation::Quadratic adds a third probe at 3d and takes the next order,
//     p_w = 3 p(d) - 3 p(2d) + p(3d),   du/dn = [18 w(d) - 9 w(2d) + 2 w(3d)] / (6 d)   (O(d^3)),
// to measure how much of a force is the evaluation's rather than the flow's. The default stays
// linear, which agrees with the control-volume drag (docs/studies/dfg_2d2_lift_maximum.md).
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "cfd/grid/field.hpp"
#include "cfd/immersed/ghost_cells.hpp"
#include "cfd/grid/stretched_grid.hpp"
#include "cfd/immersed/immersed_polygon.hpp"

namespace finverse::cfd {

enum class WallExtrapolation { Linear, Quadratic };

struct SurfaceSample {
  std::array<double, 2> point{}, normal{};
  double ds = 0;      // length of the surface element (2-D: area per unit depth)
  double probe = 0;   // d
  int edge = 0;       // the polygon edge it lies on (vertices edge -> edge + 1)
  double edge_t = 0;  // its parameter along the edge in (0, 1)
  PointStencil velocity1, velocity2, pressure1, pressure2;  // at d and 2d
  PointStencil velocity3, pressure3;                        // at 3d (Quadratic only)
};

struct SurfaceLoads {
  std::vector<double> pressure;                 // p_w per sample [Pa]
  std::vector<std::array<double, 2>> traction;  // t per sample [Pa]
  std::array<double, 2> pressure_force{}, viscous_force{}, force{};  // per unit depth [N/m]
};

// The traction of a deforming 2-D body sampled by edge, for the structure's loads (FSI): each
// sample's point, the caller's edge it lies on and its local coordinate xi in [0, 1] along it (from
// the edge's vertex e to e + 1), and its force per unit depth, traction x ds [N/m]; the totals are
// their sums (the pressure and viscous parts: the same sums of the two parts of the traction).
struct EdgeTractionSample {
  std::array<double, 2> point{};
  int edge = 0;
  double xi = 0;
  std::array<double, 2> force{};
};
struct EdgeTraction {
  std::vector<EdgeTractionSample> samples;
  std::array<double, 2> pressure_force{}, viscous_force{}, force{};
};

class SurfaceTraction {
 public:
  // ghosts must outlive this object (wall_pressure builds stencils on demand).
  SurfaceTraction(const StretchedGrid& grid, const GhostCellSet& ghosts, const Polygon& body,
                  WallExtrapolation extrapolation = WallExtrapolation::Linear);

  const std::vector<SurfaceSample>& samples() const { return samples_; }

  // u, v: velocity components; p: kinematic pressure (p / rho); body at rest.
  SurfaceLoads evaluate(const Field& u, const Field& v, const Field& p, double nu, double rho) const;
  // Body moving with the rigid-body velocity field wall_velocity(x, y).
  SurfaceLoads evaluate(const Field& u, const Field& v, const Field& p, double nu, double rho,
                        const std::function<std::array<double, 2>(double, double)>& wall_velocity) const;

  // Deforming body: the wall velocity linear along each edge between vertex_velocity (one per
  // vertex of the polygon, in its stored counter-clockwise order).
  SurfaceLoads evaluate_deforming(const Field& u, const Field& v, const Field& p, double nu, double rho,
                                  const std::vector<std::array<double, 2>>& vertex_velocity) const;

  // Wall pressure (kinematic) at the surface point closest to (x, y), by the same extrapolation.
  double wall_pressure(const Field& p, double x, double y) const;

 private:
  SurfaceSample sample(double x, double y, const SurfacePoint& s, double ds) const;
  // Wall value from the probes' values q1, q2 (and q3) at d, 2d (and 3d).
  double wall_value(double q1, double q2, double q3) const;
  // Wall-normal derivative of w (w = 0 on the wall) from its probe values.
  double wall_derivative(double w1, double w2, double w3, double d) const;

  StretchedGrid grid_;
  const GhostCellSet* ghosts_;
  Polygon body_;
  WallExtrapolation extrapolation_;
  std::vector<SurfaceSample> samples_;
};

}  // namespace finverse::cfd
