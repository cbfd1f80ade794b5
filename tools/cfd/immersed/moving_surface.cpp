// The flow solver's triangulated immersed body in 3-D, fixed or moving/deforming (issue 4;
// Mittal et al. 2008, J. Comput. Phys. 227:4825, sections 2.2-2.4): immersing it, placing it at a
// time level (hierarchy, classification, ghost data, the masked pressure operator), the step
// from one placement to the next with the freshly-cleared-cell treatment of moving_body.cpp, and
// the per-triangle surface forces; see flow_solver.hpp.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "cfd/flow/flow_solver.hpp"
#include "cfd/forces/surface_traction_3d.hpp"
#include "cfd/immersed/vec3.hpp"
#include "core/error.hpp"

namespace finverse::cfd {

void FlowSolver::immerse(const TriangulatedSurface& body) {
  if (dim() != 3) throw Error("flow solver: an immersed triangulated body needs a 3-D grid");
  moving_.reset();
  deforming_.reset();
  next_polygon_.reset();
  next_surface_.reset();
  caller_surface_ = false;
  wall_dpdn_.reset();
  wall_dpdn_3d_.reset();
  cut_.reset();
  surface_motion_ = nullptr;
  fresh_.clear();
  surface_.emplace(body, "immersed triangulated body");
  surface_state_ = SurfaceState{body, {}, {}};
  ib_.emplace(grid_, *surface_);
  index_body_faces();
  ib_dpdn_.clear();
  if (opt_.viscous_wall_pressure) wall_dpdn_3d_.emplace(grid_, *ib_, *surface_);
  for (auto& w : ib_wall_) w.clear();
  setup_pressure_operator();
  ib_momentum_.setup(grid_);
}

void FlowSolver::immerse(const SurfaceMotion& motion) {
  if (dim() != 3) throw Error("flow solver: an immersed triangulated body needs a 3-D grid");
  if (!motion) throw Error("flow solver: the moving triangulated body has no motion");
  moving_.reset();
  deforming_.reset();
  next_polygon_.reset();
  next_surface_.reset();
  caller_surface_ = false;
  wall_dpdn_.reset();
  wall_dpdn_3d_.reset();
  cut_.reset();
  surface_.reset();
  surface_motion_ = motion;
  fresh_.clear();
  for (auto& b : body_velocity_) b = Field(grid_);
  ib_momentum_.setup(grid_);
  place_surface(time_, motion(time_));
}

void FlowSolver::place_surface(double t, SurfaceState st) {
  const std::string at = "flow solver: moving triangulated body at t = " + std::to_string(t) + ": ";
  const std::size_t nv = st.surface.points.size();
  if ((!st.velocity.empty() && st.velocity.size() != nv) || (!st.acceleration.empty() && st.acceleration.size() != nv))
    throw Error(at + "velocity/acceleration need one entry per vertex");
  try {
    if (!surface_) {
      surface_.emplace(st.surface, "moving triangulated body");
    } else {
      if (st.surface.triangles != surface_->surface().triangles) throw Error("the connectivity changed");
      surface_->move_to(st.surface.points);
    }
    // A body that leaves the domain is not always caught by the ghost cells (a ghost cell's image
    // point can still lie inside the grid), and one entirely outside has no cells at all.
    // Along an axis of surface_crosses the body may reach through both sides, slip walls: there
    // the flow is the mirror image of itself, and the parts outside carry neither flux
    // (surface_pieces clips them) nor traction (surface_forces).
    const Vec3 lo = surface_->lower(), hi = surface_->upper();
    for (int d = 0; d < 3; ++d) {
      const Axis& ax = grid_.axis(d);
      const auto D = static_cast<std::size_t>(d);
      if (opt_.surface_crosses[D]) {
        for (int side = 0; side < 2; ++side)
          if (bnd_.side[static_cast<std::size_t>(2 * d + side)].type != FlowBcType::Slip)
            throw Error(std::string("surface_crosses along ") + "xyz"[d] + " needs slip walls on both sides");
        continue;
      }
      if (!(lo[D] > ax.lo() && hi[D] < ax.hi())) {
        char b[160];
        std::snprintf(b, sizeof b, "the body (%c from %.6g to %.6g m) leaves the domain (%.6g to %.6g m)", "xyz"[d],
                      lo[D], hi[D], ax.lo(), ax.hi());
        throw Error(b);
      }
    }
    ib_.emplace(grid_, *surface_);
  } catch (const Error& e) {
    throw Error(at + e.what());
  }
  index_body_faces();
  surface_state_ = std::move(st);
  for (auto& w : ib_wall_) w.clear();
  ib_dpdn_.clear();
  for (const GhostCell& g : ib_->ghosts()) {
    SurfaceHit h;
    h.triangle = g.triangle;
    h.barycentric = g.barycentric;
    const Vec3 v = surface_->interpolate(surface_state_.velocity, h);
    const Vec3 a = surface_->interpolate(surface_state_.acceleration, h);
    for (int c = 0; c < 3; ++c) {
      ib_wall_[static_cast<std::size_t>(c)].push_back(v[static_cast<std::size_t>(c)]);
      body_velocity_[static_cast<std::size_t>(c)](g.i, g.j, g.k) = v[static_cast<std::size_t>(c)];
    }
    // Normal momentum balance at the no-slip wall (kinematic pressure): dp/dn = -a_B . n.
    ib_dpdn_.push_back(-dot(a, g.normal));
  }
  // Solid cells (and, above, ghost cells): the velocity of their closest surface point (the last
  // resort of a cleared cell, and the flux of faces inside the body, which the cut-cell balance
  // needs where such a face has fluid on it).
  for (int k = 0; k < grid_.nz(); ++k)
    for (int j = 0; j < grid_.ny(); ++j)
      for (int i = 0; i < grid_.nx(); ++i) {
        if (ib_->kind(i, j, k) != CellKind::Solid) continue;
        const Vec3 v = surface_->interpolate(surface_state_.velocity, surface_->closest({grid_.xc(i), grid_.yc(j), grid_.zc(k)}));
        for (int c = 0; c < 3; ++c) body_velocity_[static_cast<std::size_t>(c)](i, j, k) = v[static_cast<std::size_t>(c)];
      }
  if (opt_.cut_cell_continuity_3d) place_surface_cut_cells();
  setup_pressure_operator();
}

// The cut-cell balance of the placed surface: apertures, the cells it splits (split_cells), and the
// body's flux G_c through its pieces in each cell, with u_B interpolated linearly over the piece's
// triangle at the piece's centroid (exact for the linear vertex interpolation). A body whose
// volume changes (a thin body bending, to second order) would make the pressure equation
// incompatible; as with the staircase balance (body_face_velocities) the net flux is removed,
// spread over the pieces by area.
void FlowSolver::place_surface_cut_cells() {
  const std::vector<SurfacePiece> pieces = surface_pieces(grid_, *surface_);
  const auto& pts = surface_->surface().points;
  const auto& tris = surface_->surface().triangles;
  const auto& vel = surface_state_.velocity;
  std::vector<std::pair<std::array<int, 3>, double>> flux;
  flux.reserve(pieces.size());
  std::vector<double> area(pieces.size());
  double net = 0, total = 0;
  for (std::size_t n = 0; n < pieces.size(); ++n) {
    const SurfacePiece& p = pieces[n];
    const Vec3& A = p.area_vector;
    area[n] = std::sqrt(dot(A, A));
    double g = 0;
    if (!vel.empty()) {
      const auto& t = tris[static_cast<std::size_t>(p.triangle)];
      const Vec3 &a = pts[static_cast<std::size_t>(t[0])], &b = pts[static_cast<std::size_t>(t[1])],
                 &c = pts[static_cast<std::size_t>(t[2])];
      const Vec3 N = cross(sub(b, a), sub(c, a));
      const double nn = dot(N, N);
      const double la = dot(cross(sub(b, p.centroid), sub(c, p.centroid)), N) / nn;
      const double lb = dot(cross(sub(c, p.centroid), sub(a, p.centroid)), N) / nn;
      const double lc = 1 - la - lb;
      const Vec3 &va = vel[static_cast<std::size_t>(t[0])], &vb = vel[static_cast<std::size_t>(t[1])],
                 &vc = vel[static_cast<std::size_t>(t[2])];
      const Vec3 v{la * va[0] + lb * vb[0] + lc * vc[0], la * va[1] + lb * vb[1] + lc * vc[1],
                   la * va[2] + lb * vb[2] + lc * vc[2]};
      g = dot(v, A);
    }
    flux.push_back({p.cell, g});
    net += g;
    total += area[n];
  }
  if (total > 0)
    for (std::size_t n = 0; n < flux.size(); ++n) flux[n].second -= net * area[n] / total;
  const Vec3 lo = surface_->lower(), hi = surface_->upper();
  const std::vector<std::array<int, 3>> split = split_cells(pieces, *surface_);
  place_cut_cells(
      cut_faces(grid_, *surface_), {lo[0], hi[0], lo[1], hi[1], lo[2], hi[2]}, flux,
      [&](int d, const Vec3& x) { return surface_->interpolate(vel, surface_->closest(x))[static_cast<std::size_t>(d)]; },
      &split);
}

void FlowSolver::move_surface(double t, SurfaceState st) {
  const GhostCellSet old = *ib_;
  place_surface(t, std::move(st));
  fresh_.clear();
  for (int k = 0; k < grid_.nz(); ++k)
    for (int j = 0; j < grid_.ny(); ++j)
      for (int i = 0; i < grid_.nx(); ++i)
        if (old.solid(i, j, k) && ib_->kind(i, j, k) == CellKind::Fluid) fresh_.push_back({i, j, k});
  if (opt_.fresh_cell_treatment && !fresh_.empty()) {
    // As in 2-D (moving_body.cpp): a cleared cell's value from the line from its boundary
    // intercept B along the normal to P = x + 1.5 h n, with P's trilinear stencil substituted.
    std::vector<ClearedCell> fs;
    fs.reserve(fresh_.size());
    for (const auto& f : fresh_) {
      const Vec3 x{grid_.xc(f[0]), grid_.yc(f[1]), grid_.zc(f[2])};
      const SurfaceHit b = surface_->closest(x);
      ClearedCell e;
      e.offset = 1.5 * std::max({grid_.dx(f[0]), grid_.dy(f[1]), grid_.dz(f[2])});
      e.fraction = b.distance / (b.distance + e.offset);
      const Vec3 P{x[0] + e.offset * b.normal[0], x[1] + e.offset * b.normal[1], x[2] + e.offset * b.normal[2]};
      e.vel = ib_->stencil(P, b.point, b.normal, BoundaryCondition::Dirichlet, f);
      e.pres = ib_->stencil(P, b.point, b.normal, BoundaryCondition::Neumann, f);
      e.ub = surface_->interpolate(surface_state_.velocity, b);
      e.dpdn = -dot(surface_->interpolate(surface_state_.acceleration, b), b.normal);
      fs.push_back(e);
    }
    settle_cleared_cells(old, fs);
  } else {
    settle_cleared_cells(old, {});
  }
}

SurfaceForces FlowSolver::surface_forces(double rho) const {
  if (!surface_ || !ib_) throw Error("flow solver: surface_forces needs an immersed triangulated body");
  SurfaceClip clip;
  clip.enabled = opt_.surface_crosses[0] || opt_.surface_crosses[1] || opt_.surface_crosses[2];
  for (std::size_t s = 0; s < 6; ++s) clip.no_slip[s] = bnd_.side[s].type == FlowBcType::NoSlip;
  const SurfaceTraction3D traction(grid_, *ib_, *surface_, clip);
  return traction.evaluate(u_[0], u_[1], u_[2], p_, opt_.nu, rho, surface_state_.velocity);
}

}  // namespace finverse::cfd
