// The zero-thickness immersed surface in the time step (DESIGN.md section 5.1; flow_solver.hpp,
// sheet_forcing.hpp): set-up, the sheet's state at the new time level, and the direct forcing of
// the predicted velocity u* between the momentum predictor and the pressure correction
// (Uhlmann 2005, J. Comput. Phys. 209:448, section 2.2, with the markers' coupling solved
// exactly). The projection that follows moves the velocity at the markers by O(dt grad phi), the
// usual slip of the method, which vanishes with dt at a fixed grid.
#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "cfd/flow/flow_solver.hpp"
#include "core/error.hpp"
#include "core/printf_format.hpp"

namespace finverse::cfd {

namespace {

std::string num(double v) { return printf_format("%.6g", v); }

// The sheet state's sizes and values: a one-line error naming t.
void check_sheet_state(const SheetState& s, std::size_t nodes, double t) {
  const std::string at = "flow solver: sheet state at t = " + num(t) + ": ";
  if (s.position.size() != nodes)
    throw Error(at + std::to_string(s.position.size()) + " node positions, expected " + std::to_string(nodes));
  if (!s.velocity.empty() && s.velocity.size() != nodes)
    throw Error(at + std::to_string(s.velocity.size()) + " node velocities, expected " + std::to_string(nodes));
  for (const auto* v : {&s.position, &s.velocity})
    for (const Vec3& p : *v)
      if (!(std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])))
        throw Error(at + "a node position or velocity is not finite");
}

}  // namespace

void FlowSolver::immerse_sheet(const SheetTopology& topology, const std::vector<Vec3>& rest,
                               const SheetForcingOptions& options, SheetMotion motion) {
  // A fixed ghost-cell body may share the grid (a flag's sheet on a cylinder; a flap clamped to the
  // walls of a pipe junction, 3-D): the forcing acts on u* after the predictor, and the body's
  // ghost cells take their wall condition again after the projection, as without a sheet. A moving
  // one would change cells' kinds under the markers.
  if (moving_ || deforming_ || surface_motion_)
    throw Error("flow solver: a sheet shares the grid only with fixed ghost-cell bodies");
  if (topology.dim != dim())
    throw Error("flow solver: a " + std::to_string(topology.dim) + "-D sheet in a " + std::to_string(dim()) +
                "-D grid");
  if (!(options.spacing > 0 && options.spacing <= 4))
    throw Error("flow solver: sheet marker spacing " + num(options.spacing) + " cells, expected in (0, 4]");
  // The markers' spacing in metres: the finest cell where the sheet sits at rest (a fine cell
  // elsewhere, e.g. at a box's edge, must not crowd the markers: M turns near-singular).
  double h = std::numeric_limits<double>::infinity();
  for (const Vec3& x : rest)
    for (int d = 0; d < dim(); ++d) {
      const Axis& a = grid_.axis(d);
      if (x[d] >= a.lo() && x[d] <= a.hi()) h = std::min(h, a.width_at(x[d]));
    }
  if (!std::isfinite(h)) throw Error("flow solver: sheet: no node inside the domain at rest");
  // On a periodic axis the markers see the sheet's images (a sheet across the whole period).
  std::array<double, 3> period{0, 0, 0};
  for (int d = 0; d < dim(); ++d)
    if (bnd_.periodic(d)) period[static_cast<std::size_t>(d)] = grid_.axis(d).hi() - grid_.axis(d).lo();
  sheet_.emplace(topology, rest, options.spacing * h, "flow solver: sheet", period);
  sheet_opt_ = options;
  sheet_motion_ = std::move(motion);
  sheet_state_ = {rest, {}};
  next_sheet_.reset();
  sheet_impulse_.assign(sheet_->size(), Vec3{0, 0, 0});
  // Every marker must be inside the domain at rest (a stencil that fails names the boundary).
  RegularizedStencils(grid_, {bnd_.periodic(0), bnd_.periodic(1), dim() == 3 && bnd_.periodic(2)},
                      sheet_->positions_at_markers(rest), sheet_opt_.kernel, "flow solver: sheet at rest");
}

void FlowSolver::set_sheet_state(SheetState next) {
  if (!sheet_) throw Error("flow solver: set_sheet_state without a sheet");
  check_sheet_state(next, sheet_->topology().nodes, time_ + next_dt());
  next_sheet_ = std::move(next);
}

void FlowSolver::force_sheet(double dt, SheetState next) {
  const double t = time_ + dt;
  check_sheet_state(next, sheet_->topology().nodes, t);
  const std::string what = "flow solver: step " + std::to_string(step_ + 1) + " (t = " + num(t) + "): sheet";
  const std::vector<Vec3> X = sheet_->positions_at_markers(next.position);
  // The markers' acceleration over the step, from the node velocities at t^n and t^{n+1} (the
  // band correction of sheet_loads; from the states, so that a restart needs nothing more).
  const auto velocity_at_markers = [&](const SheetState& st) {
    return st.velocity.empty() ? std::vector<Vec3>(X.size(), Vec3{0, 0, 0}) : sheet_->at_markers(st.velocity);
  };
  const std::vector<Vec3> before = velocity_at_markers(sheet_state_);
  sheet_marker_velocity_ = velocity_at_markers(next);
  sheet_marker_acceleration_.assign(X.size(), Vec3{0, 0, 0});
  for (std::size_t m = 0; m < X.size(); ++m)
    for (int d = 0; d < 3; ++d) sheet_marker_acceleration_[m][d] = (sheet_marker_velocity_[m][d] - before[m][d]) / dt;
  sheet_marker_position_ = X;
  sheet_stencils_.emplace(grid_,
                          std::array<bool, 3>{bnd_.periodic(0), bnd_.periodic(1), dim() == 3 && bnd_.periodic(2)}, X,
                          sheet_opt_.kernel, what);
  sheet_impulse_.assign(X.size(), Vec3{0, 0, 0});
  sheet_stats_ = {};
  sheet_state_ = std::move(next);
  add_sheet_impulse(dt);
}

// The initial field (in ustar_, before initialise()'s projection) forced to the sheet's velocity
// at t0, with a unit step; the impulses are not kept as loads.
void FlowSolver::force_initial_sheet(double t0) {
  const std::string what = "flow solver: initial sheet at t = " + num(t0);
  const std::vector<Vec3> X = sheet_->positions_at_markers(sheet_state_.position);
  sheet_marker_velocity_ = sheet_state_.velocity.empty() ? std::vector<Vec3>(X.size(), Vec3{0, 0, 0})
                                                         : sheet_->at_markers(sheet_state_.velocity);
  sheet_stencils_.emplace(grid_,
                          std::array<bool, 3>{bnd_.periodic(0), bnd_.periodic(1), dim() == 3 && bnd_.periodic(2)}, X,
                          sheet_opt_.kernel, what);
  sheet_impulse_.assign(X.size(), Vec3{0, 0, 0});
  add_sheet_impulse(1.0);
  for (int c = 0; c < dim(); ++c) copy_interior(ustar_[static_cast<std::size_t>(c)], u_[static_cast<std::size_t>(c)]);
  sheet_impulse_.assign(X.size(), Vec3{0, 0, 0});
  sheet_stats_ = {};
}

// One forcing pass on ustar_: the impulses that bring u* to the sheet's velocity at every marker,
// added to the step's impulses so far.
void FlowSolver::add_sheet_impulse(double dt) {
  const RegularizedStencils& st = *sheet_stencils_;
  const std::string what = "flow solver: step " + std::to_string(step_ + 1) + " (t = " + num(time_ + dt) + "): sheet";
  const std::size_t n = st.markers();
  std::vector<double> ui, b(n), g;
  for (int c = 0; c < dim(); ++c) {
    Field& us = ustar_[static_cast<std::size_t>(c)];
    st.interpolate(us, ui);
    for (std::size_t m = 0; m < n; ++m) b[m] = (sheet_marker_velocity_[m][c] - ui[m]) / dt;
    const SheetSolveStats s = solve_marker_system(st, b, g, sheet_opt_, what);
    sheet_stats_.iterations = std::max(sheet_stats_.iterations, s.iterations);
    sheet_stats_.relative_residual = std::max(sheet_stats_.relative_residual, s.relative_residual);
    st.spread(g, dt, us);
    for (std::size_t m = 0; m < n; ++m) sheet_impulse_[m][c] += g[m];
  }
}

SheetLoads FlowSolver::sheet_loads(double rho) const {
  SheetLoads l;
  if (!sheet_) return l;
  l.marker.resize(sheet_impulse_.size());
  for (std::size_t m = 0; m < sheet_impulse_.size(); ++m)
    for (int d = 0; d < 3; ++d) l.marker[m][d] = -rho * sheet_impulse_[m][d];
  // Only after a step of this run (a restored run has no acceleration until it steps).
  if (sheet_opt_.band_correction && sheet_stencils_ && sheet_marker_acceleration_.size() == sheet_impulse_.size()) {
    const std::vector<Vec3> c = sheet_band_correction();
    for (std::size_t m = 0; m < c.size(); ++m)
      for (int d = 0; d < 3; ++d) l.marker[m][d] += rho * c[m][d];
  }
  for (const Vec3& f : l.marker)
    for (int d = 0; d < 3; ++d) l.total[d] += f[d];
  l.nodal = sheet_->to_nodes(l.marker);
  return l;
}

// The band correction per marker and unit density, V_m a_m: the regularized force moves a band of
// fluid about the kernel's width with the sheet, and the force the markers feel is the force on
// that band less the band's inertia, an added mass that a zero-thickness surface does not have.
// V_m = (M^{-1} 1)_m is the fluid volume that a unit velocity demanded at every marker moves.
// (The band's Froude-Krylov force, V grad_s p along the sheet, is left in: next to an edge the
// sheet's pressure is singular and that term depended on the markers' sub-cell placement, 3 % of
// C_T between the 2-D and 3-D runs of one flow; docs/studies/thin_surface.md, "The entrained band".)
std::vector<Vec3> FlowSolver::sheet_band_correction() const {
  const RegularizedStencils& st = *sheet_stencils_;
  const std::size_t n = st.markers();
  std::vector<double> V;
  solve_marker_system(st, std::vector<double>(n, 1.0), V, sheet_opt_, "flow solver: sheet band volume");
  std::vector<Vec3> c(n, Vec3{0, 0, 0});
  for (std::size_t m = 0; m < n; ++m)
    for (int d = 0; d < 3; ++d) c[m][d] = V[m] * sheet_marker_acceleration_[m][d];
  return c;
}

}  // namespace finverse::cfd
