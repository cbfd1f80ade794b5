// The flow solver's moving 2-D immersed body, rigid (rigid_motion.hpp) or deforming with a state
// the caller sets (deforming_polygon.hpp) (Mittal et al. 2008, J. Comput. Phys. 227:4825, section
// 2.4): placing the body at a time level (classification, ghost data, the cut-cell balance or the
// masked pressure operator) and the step from one placement to the next with the treatment of
// freshly cleared cells; see flow_solver.hpp. The two differ only in where the wall's velocity and
// acceleration come from (the rigid field, or the vertex states linear along each edge), in the
// solid cells' velocity (the rigid field, or the closest surface point's) and in the body's flux
// through the cut cells (through the faces' fluid parts, exact for a rigid field, or integrated
// over the clipped edges).
#include <algorithm>
#include <cstdio>
#include <string>

#include "cfd/flow/flow_solver.hpp"
#include "core/error.hpp"

namespace finverse::cfd {

void FlowSolver::immerse(const MovingBody& body) {
  if (dim() != 2) throw Error("flow solver: an immersed polygon needs a 2-D grid");
  if (!body.motion) throw Error("flow solver: the moving body has no motion");
  wall_dpdn_.reset();
  wall_dpdn_3d_.reset();
  moving_ = body;
  deforming_.reset();
  next_polygon_.reset();
  surface_.reset();
  surface_motion_ = nullptr;
  caller_surface_ = false;
  fresh_.clear();
  ib_momentum_.setup(grid_);
  place_body(time_);
}

std::array<double, 2> FlowSolver::wall_velocity_2d(const SurfacePoint& b) const {
  return moving_ ? moving_->velocity(body_state_, b.point[0], b.point[1]) : deforming_->velocity(b);
}

std::array<double, 2> FlowSolver::wall_acceleration_2d(const SurfacePoint& b) const {
  return moving_ ? moving_->acceleration(body_state_, b.point[0], b.point[1]) : deforming_->acceleration(b);
}

void FlowSolver::place_body(double t) {
  if (moving_) {
    body_state_ = moving_->motion(t);
    body_now_ = moving_->placed(body_state_);
  } else {
    body_now_ = deforming_->polygon();
  }
  try {
    // A deforming body is checked against the domain explicitly: one that leaves it is not always
    // caught by the ghost cells (an image point can still lie inside the grid).
    if (deforming_) {
      const auto box = polygon_box(body_now_);
      for (int d = 0; d < 2; ++d) {
        const Axis& ax = grid_.axis(d);
        const double lo = box[static_cast<std::size_t>(2 * d)], hi = box[static_cast<std::size_t>(2 * d + 1)];
        if (!(lo > ax.lo() && hi < ax.hi())) {
          char b[160];
          std::snprintf(b, sizeof b, "the body (%c from %.6g to %.6g m) leaves the domain (%.6g to %.6g m)", "xy"[d], lo,
                        hi, ax.lo(), ax.hi());
          throw Error(b);
        }
      }
    }
    if (deforming_ && kinds_polygon_) ib_.emplace(grid_, body_now_, *kinds_polygon_);
    else ib_.emplace(grid_, body_now_);
  } catch (const Error& e) {
    throw Error(std::string("flow solver: ") + (moving_ ? "moving" : "deforming") + " body at t = " + std::to_string(t) +
                ": " + e.what());
  }
  index_body_faces();
  for (auto& w : ib_wall_) w.clear();
  ib_dpdn_.clear();
  for (const GhostCell& g : ib_->ghosts()) {
    const auto v = wall_velocity_2d(g.boundary);
    const auto a = wall_acceleration_2d(g.boundary);
    for (int c = 0; c < 2; ++c) ib_wall_[static_cast<std::size_t>(c)].push_back(v[static_cast<std::size_t>(c)]);
    // Normal momentum balance at the no-slip wall (kinematic pressure): dp/dn = -a_B . n.
    ib_dpdn_.push_back(-(a[0] * g.boundary.normal[0] + a[1] * g.boundary.normal[1]));
  }
  // The wall velocity near x (a deforming body's: its closest surface point's).
  const auto near_wall = [&](int d, const Vec3& x) {
    return wall_velocity_2d(body_now_.closest(x[0], x[1]))[static_cast<std::size_t>(d)];
  };
  if (deforming_) {
    // Every non-fluid cell carries the velocity of its closest surface point (the ghost cells'
    // is their intercept's), so the field is a function of the placement alone.
    for (int j = 0; j < grid_.ny(); ++j)
      for (int i = 0; i < grid_.nx(); ++i) {
        if (ib_->kind(i, j) != CellKind::Solid) continue;
        const auto v = wall_velocity_2d(body_now_.closest(grid_.xc(i), grid_.yc(j)));
        for (int c = 0; c < 2; ++c) body_velocity_[static_cast<std::size_t>(c)](i, j, 0) = v[static_cast<std::size_t>(c)];
      }
    for (std::size_t n = 0; n < ib_->ghosts().size(); ++n) {
      const GhostCell& g = ib_->ghosts()[n];
      for (int c = 0; c < 2; ++c) body_velocity_[static_cast<std::size_t>(c)](g.i, g.j, 0) = ib_wall_[static_cast<std::size_t>(c)][n];
    }
  }
  // The pressure operator's face mask follows the body (the multigrid hierarchy is rebuilt); with
  // the cut-cell balance the faces are weighted by their fluid apertures instead.
  if (opt_.cut_cell_continuity) {
    if (moving_) {
      place_cut_cells(cut_faces(grid_, body_now_), polygon_box(body_now_), {}, [&](int d, const Vec3& x) {
        return moving_->velocity(body_state_, x[0], x[1])[static_cast<std::size_t>(d)];
      });
    } else {
      // The body's flux through its clipped edges. A body whose area changes has a net flux, which
      // would make the pressure equation incompatible; as for a triangulated body it is removed,
      // spread over the boundary by length (exact for an area-preserving motion, where it is 0).
      const auto pieces = deforming_->wall_flux(grid_, deforming_net_flux_);
      double length = 0;
      for (const auto& p : pieces) length += p.length;
      std::vector<std::pair<std::array<int, 3>, double>> flux;
      flux.reserve(pieces.size());
      for (const auto& p : pieces) flux.push_back({p.cell, p.flux - deforming_net_flux_ * p.length / length});
      place_cut_cells(cut_faces(grid_, body_now_), polygon_box(body_now_), flux, near_wall);
    }
  }
  setup_pressure_operator();
}

void FlowSolver::move_body(double t) {
  const GhostCellSet old = *ib_;
  place_body(t);
  fresh_.clear();
  for (int j = 0; j < grid_.ny(); ++j)
    for (int i = 0; i < grid_.nx(); ++i)
      if (old.solid(i, j) && ib_->kind(i, j) == CellKind::Fluid) fresh_.push_back({i, j, 0});
  if (opt_.fresh_cell_treatment && !fresh_.empty()) {
    // A cleared cell's centre x lies on the normal through its boundary intercept B at distance
    // d. Its value comes from the line B -> P, P = x + 1.5 h n (beyond the cell, so P's bilinear
    // stencil holds fluid and ghost cells, with B substituted for a solid node exactly as for a
    // ghost cell's image point):
    //     u(x) = u_B + (u(P) - u_B) d / (d + 1.5 h),     p(x) = p(P) - 1.5 h dp/dn(B).
    // (A bilinear fit through x's own neighbours and B extrapolates with unbounded weights when B
    // nears one of them.) The stencils may hold ghost cells and other cleared cells, so the
    // cleared values and the ghost values (new geometry) are iterated together in a fixed order; a
    // few rounds suffice as the weights are those of an interpolation.
    std::vector<ClearedCell> fs;
    fs.reserve(fresh_.size());
    for (const auto& f : fresh_) {
      const std::array<double, 2> x{grid_.xc(f[0]), grid_.yc(f[1])};
      const SurfacePoint b = body_now_.closest(x[0], x[1]);
      ClearedCell e;
      e.offset = 1.5 * std::max(grid_.dx(f[0]), grid_.dy(f[1]));
      e.fraction = b.distance / (b.distance + e.offset);
      const std::array<double, 2> P{x[0] + e.offset * b.normal[0], x[1] + e.offset * b.normal[1]};
      e.vel = ib_->stencil(P, b, BoundaryCondition::Dirichlet, {f[0], f[1]});
      e.pres = ib_->stencil(P, b, BoundaryCondition::Neumann, {f[0], f[1]});
      const auto v = wall_velocity_2d(b);
      e.ub = {v[0], v[1], 0.0};
      const auto a = wall_acceleration_2d(b);
      e.dpdn = -(a[0] * b.normal[0] + a[1] * b.normal[1]);
      fs.push_back(e);
    }
    settle_cleared_cells(old, fs);
  } else {
    settle_cleared_cells(old, {});
  }
}

}  // namespace finverse::cfd
