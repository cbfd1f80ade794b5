// The flow solver's deforming body whose surface the caller sets (issue 32, the FSI coupling; seed
// paper section 2.3): immersing it with its reference state, taking its state at the next time
// level from the caller (set_body_state, 2-D polygon or 3-D triangulated surface, the same
// contract), and the 2-D traction samples by edge for the structure's loads. Placing and stepping
// are those of the moving bodies (moving_body.cpp, moving_surface.cpp); see flow_solver.hpp.
#include <cmath>
#include <string>

#include "cfd/flow/flow_solver.hpp"
#include "core/error.hpp"

namespace finverse::cfd {

namespace {
// "flow solver: deforming body at t = ..." for the state of the next time level.
std::string at_time(double t) { return "flow solver: deforming body at t = " + std::to_string(t); }
}  // namespace

void FlowSolver::immerse_deforming(const PolygonState& reference) {
  if (dim() != 2) throw Error("flow solver: a deforming polygon needs a 2-D grid");
  deforming_.emplace(reference, at_time(time_));
  next_polygon_.reset();
  kinds_polygon_.reset();
  next_kinds_.reset();
  moving_.reset();
  wall_dpdn_.reset();
  wall_dpdn_3d_.reset();
  surface_.reset();
  surface_motion_ = nullptr;
  caller_surface_ = false;
  next_surface_.reset();
  fresh_.clear();
  for (auto& b : body_velocity_) b = Field(grid_);
  ib_momentum_.setup(grid_);
  place_body(time_);
}

void FlowSolver::set_body_state(const PolygonState& next, const PolygonState* kinds_at) {
  if (!deforming_) throw Error("flow solver: set_body_state(PolygonState) needs immerse_deforming(PolygonState) first");
  const double t = time_ + next_dt();
  // Validated now, so that a bad state names the caller's call; the step re-checks the placement.
  const DeformingPolygon checked(next, at_time(t), deforming_->state().position.size());
  if ((checked.signed_area() > 0) != (deforming_->signed_area() > 0))
    throw Error(at_time(t) + ": the polygon's orientation flipped (the body turned inside out)");
  next_polygon_ = next;
  next_kinds_.reset();
  if (kinds_at) next_kinds_ = DeformingPolygon(*kinds_at, at_time(t) + " (kinds)", checked.state().position.size()).polygon();
}

void FlowSolver::immerse_deforming(const SurfaceState& reference) {
  if (dim() != 3) throw Error("flow solver: a deforming triangulated body needs a 3-D grid");
  // The moving triangulated body's machinery with the states the caller sets; its motion function
  // is never called (caller_surface_).
  immerse(SurfaceMotion([reference](double) { return reference; }));
  caller_surface_ = true;
}

void FlowSolver::set_body_state(const SurfaceState& next) {
  if (!caller_surface_)
    throw Error("flow solver: set_body_state(SurfaceState) needs immerse_deforming(SurfaceState) first");
  const double t = time_ + next_dt();
  const std::size_t n = surface_state_.surface.points.size();
  if (next.surface.points.size() != n || next.surface.triangles != surface_state_.surface.triangles)
    throw Error(at_time(t) + ": the surface's vertex count or connectivity changed (" + std::to_string(n) +
                " vertices expected, got " + std::to_string(next.surface.points.size()) + ")");
  if ((!next.velocity.empty() && next.velocity.size() != n) || (!next.acceleration.empty() && next.acceleration.size() != n))
    throw Error(at_time(t) + ": velocity/acceleration need one entry per vertex (or none)");
  for (const auto* q : {&next.surface.points, &next.velocity, &next.acceleration})
    for (std::size_t k = 0; k < q->size(); ++k)
      for (double x : (*q)[k])
        if (!std::isfinite(x)) throw Error(at_time(t) + ": vertex " + std::to_string(k) + " has a non-finite value");
  next_surface_ = next;
}

EdgeTraction FlowSolver::edge_traction(double rho) const {
  if (!deforming_ || !ib_) throw Error("flow solver: edge_traction needs a deforming polygon (immerse_deforming)");
  const SurfaceTraction traction(grid_, *ib_, body_now_);
  const SurfaceLoads L = traction.evaluate_deforming(u_[0], u_[1], p_, opt_.nu, rho, deforming_->stored_velocity());
  EdgeTraction out;
  out.samples.reserve(traction.samples().size());
  for (std::size_t n = 0; n < traction.samples().size(); ++n) {
    const SurfaceSample& s = traction.samples()[n];
    EdgeTractionSample e;
    e.point = s.point;
    const auto [edge, xi] = deforming_->caller_edge(s.edge, s.edge_t);
    e.edge = edge;
    e.xi = xi;
    e.force = {L.traction[n][0] * s.ds, L.traction[n][1] * s.ds};
    out.samples.push_back(e);
  }
  out.pressure_force = L.pressure_force;
  out.viscous_force = L.viscous_force;
  out.force = L.force;
  return out;
}

}  // namespace finverse::cfd
