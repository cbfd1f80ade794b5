// The data-driven 3-D flow case; see flow_case.hpp. The order of operations is that of the sphere
// validation (validation/sphere_flow.cpp), so the built-in sphere gives its numbers bit for bit.
#include "cfd/cases/flow_case.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "cfd/cases/enclosed_fluid.hpp"
#include "cfd/forces/control_volume_force.hpp"
#include "cfd/forces/surface_traction.hpp"
#include "cfd/forces/surface_traction_3d.hpp"
#include "cfd/immersed/immersed_polygon.hpp"
#include "cfd/immersed/rigid_motion.hpp"
#include "core/error.hpp"

namespace finverse::cfd::cases {

namespace {

// Cell counts that are multiples of 8 keep three halvings for the multigrid.
int round8(double n) { return std::max(8, 8 * static_cast<int>(std::lround(n / 8))); }

// A core that fills a side (a periodic box) leaves no outer cells to round with: its own count
// must then be a multiple of 8.
Axis axis(double lo, double hi, double ulo, double uhi, double h, double ratio) {
  const int n = round8(Axis::stretched(lo, hi, ulo, uhi, h, ratio).size());
  try {
    return Axis::stretched_count(lo, hi, ulo, uhi, n, ratio);
  } catch (const std::invalid_argument& e) {
    if (ulo > lo && uhi < hi) throw Error(std::string("grid: ") + e.what());
    throw Error(
        "grid: the core [" + std::to_string(ulo) + ", " + std::to_string(uhi) + "] fills the domain, so its " +
        "cell count (length / h) must be a multiple of 8 for the multigrid; it is not with h = " + std::to_string(h));
  }
}

}  // namespace

// (A plane sheet's segments {a, b, -1} keep their -1.)
TriangulatedSurface merged_bodies(const std::vector<CaseBody>& bodies, std::vector<std::size_t>& first_triangle,
                                  std::vector<std::size_t>* first_node) {
  TriangulatedSurface all;
  for (const CaseBody& b : bodies) {
    all.encloses_fluid = all.encloses_fluid || b.encloses_fluid;
    first_triangle.push_back(all.triangles.size());
    if (first_node) first_node->push_back(all.points.size());
    const int offset = static_cast<int>(all.points.size());
    all.points.insert(all.points.end(), b.surface.points.begin(), b.surface.points.end());
    for (const auto& t : b.surface.triangles)
      all.triangles.push_back({t[0] + offset, t[1] + offset, t[2] < 0 ? t[2] : t[2] + offset});
  }
  first_triangle.push_back(all.triangles.size());
  if (first_node) first_node->push_back(all.points.size());
  return all;
}

namespace {

bool any_moves(const std::vector<CaseBody>& bodies) {
  return std::any_of(bodies.begin(), bodies.end(), [](const CaseBody& b) { return b.motion && b.motion->moves(); });
}

// The nodes of every body at time t, placed by its motion (fixed bodies: at rest).
struct NodeKinematics {
  std::vector<Vec3> position, velocity, acceleration;
};
NodeKinematics place_nodes(const std::vector<CaseBody>& bodies, const std::vector<Vec3>& rest,
                           const std::vector<std::size_t>& first_node, double t) {
  NodeKinematics k{rest, std::vector<Vec3>(rest.size(), Vec3{0, 0, 0}), std::vector<Vec3>(rest.size(), Vec3{0, 0, 0})};
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (!bodies[b].motion) continue;
    const PrescribedRigidMotion& m = *bodies[b].motion;
    const RigidPose pose = m.pose(t);
    for (std::size_t i = first_node[b]; i < first_node[b + 1]; ++i) {
      const PointKinematics q = m.point(pose, rest[i]);
      k.position[i] = q.position;
      k.velocity[i] = q.velocity;
      k.acceleration[i] = q.acceleration;
    }
  }
  return k;
}

// A pose table must cover the simulated time.
void check_motion_span(const FlowCaseSpec& s) {
  for (const CaseBody& b : s.bodies) {
    if (!b.motion) continue;
    if (const auto span = b.motion->span(); span && ((*span)[0] > 1e-12 || (*span)[1] < s.t_end - 1e-12))
      throw Error(s.name + ": body " + b.name + ": the pose table covers t = " + std::to_string((*span)[0]) + " .. " +
                  std::to_string((*span)[1]) + " s, not 0 .. time.t_end = " + std::to_string(s.t_end) +
                  " s (or give motion.period)");
  }
}

std::vector<std::array<double, 3>> per_body(const std::vector<std::array<double, 3>>& per_triangle,
                                            const std::vector<std::size_t>& first) {
  std::vector<std::array<double, 3>> out(first.size() - 1, {0, 0, 0});
  for (std::size_t b = 0; b + 1 < first.size(); ++b)
    for (std::size_t t = first[b]; t < first[b + 1]; ++t)
      for (int c = 0; c < 3; ++c) out[b][c] += per_triangle[t][c];
  return out;
}

// The time loop both dimensions share: steps to t_end; at every force_every-th step and the last,
// record(t) appends the forces (and the control-volume sample) and returns the first body's C_x.
template <class Record>
void march(FlowSolver& solver, const FlowCaseSpec& s, FlowCaseResult& r,
           const std::function<void(const StepStats&, double)>& progress, Record record) {
  long poisson = 0, momentum = 0;
  double cx = 0;
  while (solver.time() < s.t_end - 1e-12) {
    const StepStats st = solver.step();
    poisson += st.poisson_iterations;
    momentum += st.helmholtz_iterations;
    r.max_divergence = st.max_divergence;
    ++r.steps;
    const bool last = solver.time() >= s.t_end - 1e-12;
    if (r.steps % std::max(1, s.force_every) == 0 || last) cx = record(st.time);
    if (progress) progress(st, cx);
  }
  r.mean_poisson_iterations = static_cast<double>(poisson) / static_cast<double>(r.steps);
  r.mean_momentum_iterations = static_cast<double>(momentum) / static_cast<double>(r.steps);
}

// The control-volume force from its samples (at least two, for the time derivative) and the run's time.
void finish(const FlowCaseSpec& s, const std::vector<ControlVolumeSample>& cv, FlowCaseResult& r,
            std::chrono::steady_clock::time_point t0) {
  if (cv.size() >= 2)
    for (const auto& f : control_volume_forces(cv, s.rho)) r.control_volume_force.push_back(f);
  r.cpu_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// The plane flow past one polygon: the 2-D traction (surface_traction.hpp) and control volume.
FlowCaseResult run_plane(const FlowCaseSpec& s, const StretchedGrid& grid, FlowSolver& solver,
                         const std::function<void(const StepStats&, double)>& progress,
                         std::chrono::steady_clock::time_point t0) {
  if (s.bodies.size() != 1) throw Error(s.name + ": a 2-D case takes one closed body (a polygon)");
  const Polygon body(s.bodies[0].outline);
  const bool moving = any_moves(s.bodies);
  if (moving && s.control_volume) throw Error(s.name + ": outputs.control_volume: not available with a moving body");
  if (moving) {
    const PrescribedRigidMotion m = *s.bodies[0].motion;
    solver.immerse(MovingBody{body, {m.pivot()[0], m.pivot()[1]}, [m](double t) { return m.plane_state(t); }});
  } else {
    solver.immerse(body);
  }
  const auto u0 = s.initial_velocity;
  solver.initialise([u0](double, double, double, double) { return u0; });
  std::optional<SurfaceTraction> fixed_traction;
  if (!moving) fixed_traction.emplace(grid, *solver.immersed(), body);
  std::optional<ControlVolumeForce> control_volume;
  const auto& cvb = s.control_volume_box;
  if (s.control_volume) control_volume.emplace(grid, *solver.immersed(), cvb[0], cvb[1], cvb[2], cvb[3]);
  std::vector<ControlVolumeSample> cv;
  FlowCaseResult r;
  r.cells = {grid.nx(), grid.ny(), 1};
  r.ghost_cells = static_cast<long>(solver.immersed()->ghosts().size());
  if (fixed_traction) r.surface_samples = static_cast<long>(fixed_traction->samples().size());
  const double scale = 2 / (s.reference_speed * s.reference_speed * s.reference_area);
  const double nu = s.nu;
  march(solver, s, r, progress, [&](double t) {
    SurfaceLoads L;
    if (moving) {
      // The traction's samples follow the body; the wall moves with the body's rigid velocity.
      const MovingBody* mb = solver.moving_body();
      const SurfaceTraction tr(grid, *solver.immersed(), solver.body_polygon());
      L = tr.evaluate(solver.u(0), solver.u(1), solver.p(), nu, 1.0,
                      [&](double x, double y) { return mb->velocity(solver.body_state(), x, y); });
      r.surface_samples = static_cast<long>(tr.samples().size());
    } else {
      L = fixed_traction->evaluate(solver.u(0), solver.u(1), solver.p(), nu, 1.0);
    }
    if (control_volume)
      cv.push_back(control_volume->evaluate(t, solver.u(0), solver.u(1), solver.face_velocity(), solver.p(), nu));
    const auto per_depth = [&](const std::array<double, 2>& f) {
      return std::vector<std::array<double, 3>>{{s.rho * f[0], s.rho * f[1], 0.0}};
    };
    r.time.push_back(t);
    r.force.push_back(per_depth(L.force));
    r.pressure.push_back(per_depth(L.pressure_force));
    r.viscous.push_back(per_depth(L.viscous_force));
    return scale * L.force[0];
  });
  finish(s, cv, r, t0);
  return r;
}

// Zero-thickness sheets, fixed or moving, beside fixed closed bodies (3-D; walls that enclose the
// fluid, a cylinder a flag hangs from): each sheet's force from its markers, each closed body's
// from the traction on its surface; per body in the case's order.
FlowCaseResult run_sheets(const FlowCaseSpec& s, const StretchedGrid& grid, FlowSolver& solver,
                          const std::function<void(const StepStats&, double)>& progress,
                          const std::function<void(const FlowSolver&)>& finished,
                          std::chrono::steady_clock::time_point t0) {
  if (s.control_volume) throw Error(s.name + ": outputs.control_volume: not available with sheet bodies");
  std::vector<CaseBody> sheets, walls;
  std::vector<std::size_t> sheet_of, wall_of;  // each one's place in s.bodies
  for (std::size_t b = 0; b < s.bodies.size(); ++b) {
    (s.bodies[b].sheet ? sheets : walls).push_back(s.bodies[b]);
    (s.bodies[b].sheet ? sheet_of : wall_of).push_back(b);
  }
  if (!walls.empty() && s.dim == 2)
    throw Error(s.name + ": bodies: a plane flow's sheet cannot share it with a closed body yet");
  if (any_moves(walls))
    throw Error(s.name + ": bodies: a closed body beside a sheet must be fixed (leave out its motion:)");
  std::vector<std::size_t> first, first_node, wall_first;
  const TriangulatedSurface all = merged_bodies(sheets, first, &first_node);
  const TriangulatedSurface wall = merged_bodies(walls, wall_first, nullptr);
  if (!walls.empty()) solver.immerse(wall);
  std::vector<Vec3> rest(all.points.begin(), all.points.end());
  SheetMotion motion = [rest](double) { return SheetState{rest, {}}; };
  if (any_moves(sheets))
    motion = [sheets, rest, first_node](double t) {
      NodeKinematics k = place_nodes(sheets, rest, first_node, t);
      return SheetState{std::move(k.position), std::move(k.velocity)};
    };
  solver.immerse_sheet(SheetTopology{s.dim, rest.size(), all.triangles}, rest, s.sheet, motion);
  const auto u0 = s.initial_velocity;
  if (s.initial_field)
    solver.initialise(s.initial_field);
  else
    solver.initialise([u0](double, double, double, double) { return u0; });
  std::optional<SurfaceTraction3D> traction;
  if (!walls.empty()) {
    SurfaceClip clip;  // walls that enclose the fluid cross the domain's sides
    clip.enabled = wall.encloses_fluid;
    for (std::size_t k = 0; k < 6; ++k) clip.no_slip[k] = s.sides[k].type == FlowBcType::NoSlip;
    traction.emplace(grid, *solver.immersed(), *solver.body_surface(), clip);
  }
  FlowCaseResult r;
  r.cells = {grid.nx(), grid.ny(), s.dim == 3 ? grid.nz() : 1};
  r.triangles = static_cast<long>(all.triangles.size() + wall.triangles.size());
  r.surface_samples = static_cast<long>(solver.sheet()->size());
  if (traction) {
    r.ghost_cells = static_cast<long>(solver.immersed()->ghosts().size());
    r.surface_samples += static_cast<long>(traction->samples().size());
  }
  const double U = s.reference_speed;
  const double scale = 2 / (U * U * s.reference_area);
  using Forces = std::vector<std::array<double, 3>>;
  march(solver, s, r, progress, [&](double t) {
    Forces force(s.bodies.size(), {0, 0, 0}), pressure = force, viscous = force;
    const SheetLoads L = solver.sheet_loads(s.rho);
    for (std::size_t m = 0; m < L.marker.size(); ++m) {
      const auto e = static_cast<std::size_t>(solver.sheet()->element(m));
      const auto b = static_cast<std::size_t>(std::upper_bound(first.begin(), first.end(), e) - first.begin()) - 1;
      // A sheet's force is the jump across it: pressure and shear are not told apart.
      for (int c = 0; c < 3; ++c) force[sheet_of[b]][c] += L.marker[m][c], pressure[sheet_of[b]][c] += L.marker[m][c];
    }
    if (traction) {
      const SurfaceForces F = traction->evaluate(solver.u(0), solver.u(1), solver.u(2), solver.p(), s.nu, s.rho);
      const Forces wp = per_body(F.pressure, wall_first), wv = per_body(F.viscous, wall_first);
      for (std::size_t w = 0; w < walls.size(); ++w)
        for (int c = 0; c < 3; ++c) {
          pressure[wall_of[w]][c] = wp[w][c];
          viscous[wall_of[w]][c] = wv[w][c];
          force[wall_of[w]][c] = wp[w][c] + wv[w][c];
        }
    }
    r.time.push_back(t);
    r.force.push_back(force);
    r.pressure.push_back(pressure);
    r.viscous.push_back(viscous);
    return scale * force[0][0] / s.rho;
  });
  std::vector<ControlVolumeSample> none;
  finish(s, none, r, t0);
  if (finished) finished(solver);
  return r;
}

}  // namespace

StretchedGrid flow_case_grid(const FlowCaseSpec& s) {
  const auto& d = s.domain;
  const auto& c = s.core;
  if (s.dim == 2)
    return StretchedGrid(axis(d[0], d[1], c[0], c[1], s.h, s.stretch_ratio),
                         axis(d[2], d[3], c[2], c[3], s.h, s.stretch_ratio));
  return StretchedGrid(axis(d[0], d[1], c[0], c[1], s.h, s.stretch_ratio),
                       axis(d[2], d[3], c[2], c[3], s.h, s.stretch_ratio),
                       axis(d[4], d[5], c[4], c[5], s.h, s.stretch_ratio));
}

FlowBoundary flow_case_boundary(const FlowCaseSpec& s) {
  FlowBoundary b;
  for (int k = 0; k < 6; ++k) {
    const SideCondition& sc = s.sides[k];
    b[static_cast<Side>(k)].type = sc.type;
    b[static_cast<Side>(k)].local_convection = sc.local_convection;
    if (sc.type == FlowBcType::Inlet) {
      const int normal = k / 2;
      auto& side = b[static_cast<Side>(k)];
      side.speed = sc.velocity[normal];
      side.profile = sc.parabolic ? InletProfile::Parabolic : InletProfile::Uniform;
      side.ramp_time = sc.ramp_time;
      if (!sc.pipes.empty()) {
        side.profile = InletProfile::Function;
        side.function = pipe_inflow(sc.pipes, k);
      }
    }
  }
  return b;
}

FlowOptions flow_case_options(const FlowCaseSpec& s) {
  FlowOptions opt;
  opt.nu = s.nu;
  opt.cfl = s.cfl;
  opt.dt_max = s.dt_max > 0 ? s.dt_max : s.cfl * s.h / s.reference_speed;
  opt.helmholtz_rtol = s.helmholtz_rtol;
  opt.poisson.rtol = s.poisson_rtol;
  opt.viscous_wall_pressure = s.wall_momentum_balance;
  opt.near_wall_closed_faces = s.near_wall_closed_faces;
  return opt;
}

FlowCaseResult run_flow_case(const FlowCaseSpec& s, const std::function<void(const StepStats&, double)>& progress,
                             const std::function<void(const FlowSolver&)>& finished) {
  if (!(s.h > 0)) throw Error(s.name + ": grid.h must be > 0");
  if (!(s.t_end > 0)) throw Error(s.name + ": time.t_end must be > 0");
  if (s.bodies.empty()) throw Error(s.name + ": no bodies");
  const auto t0 = std::chrono::steady_clock::now();
  const StretchedGrid grid = flow_case_grid(s);
  const FlowBoundary b = flow_case_boundary(s);
  FlowOptions opt = flow_case_options(s);
  check_motion_span(s);
  FlowSolver solver;
  const bool sheets = std::any_of(s.bodies.begin(), s.bodies.end(), [](const CaseBody& c) { return c.sheet; });
  if (s.dim == 2) {
    opt.cut_cell_continuity_fixed = s.cut_cells && !any_moves(s.bodies);
    solver.setup(grid, b, opt);
    if (sheets) return run_sheets(s, grid, solver, progress, finished, t0);
    return run_plane(s, grid, solver, progress, t0);
  }
  solver.setup(grid, b, opt);
  if (sheets) return run_sheets(s, grid, solver, progress, finished, t0);
  std::vector<std::size_t> first, first_node;
  const TriangulatedSurface body = merged_bodies(s.bodies, first, &first_node);
  const bool moving = any_moves(s.bodies);
  if (moving && s.control_volume) throw Error(s.name + ": outputs.control_volume: not available with moving bodies");
  if (moving) {
    const std::vector<Vec3> rest(body.points.begin(), body.points.end());
    solver.immerse(SurfaceMotion([&bodies = s.bodies, rest, first_node, body](double t) {
      NodeKinematics k = place_nodes(bodies, rest, first_node, t);
      SurfaceState st{body, std::move(k.velocity), std::move(k.acceleration)};
      for (std::size_t i = 0; i < rest.size(); ++i) st.surface.points[i] = k.position[i];
      return st;
    }));
  } else {
    solver.immerse(body);
  }
  const auto u0 = s.initial_velocity;
  if (s.initial_field)
    solver.initialise(s.initial_field);
  else
    solver.initialise([u0](double, double, double, double) { return u0; });
  std::optional<SurfaceTraction3D> fixed_traction;
  // Walls that enclose the fluid cross the domain's sides: only their part inside carries traction.
  SurfaceClip clip;
  clip.enabled = body.encloses_fluid;
  for (std::size_t k = 0; k < 6; ++k) clip.no_slip[k] = s.sides[k].type == FlowBcType::NoSlip;
  if (!moving) fixed_traction.emplace(grid, *solver.immersed(), *solver.body_surface(), clip);
  std::optional<ControlVolumeForce> control_volume;
  if (s.control_volume) control_volume.emplace(grid, *solver.immersed(), s.control_volume_box);
  std::vector<ControlVolumeSample> cv;

  FlowCaseResult r;
  r.cells = {grid.nx(), grid.ny(), grid.nz()};
  r.ghost_cells = static_cast<long>(solver.immersed()->ghosts().size());
  r.triangles = static_cast<long>(body.triangles.size());
  if (fixed_traction) r.surface_samples = static_cast<long>(fixed_traction->samples().size());
  const double U = s.reference_speed;
  const double scale = 2 / (U * U * s.reference_area);
  march(solver, s, r, progress, [&](double t) {
    // Per unit density (the solver's pressure is kinematic); times rho below. A moving body's
    // traction is sampled where the body is now.
    const SurfaceForces F =
        moving ? solver.surface_forces(1.0)
               : fixed_traction->evaluate(solver.u(0), solver.u(1), solver.u(2), solver.p(), opt.nu, 1.0);
    if (control_volume)
      cv.push_back(control_volume->evaluate(t, solver.u(0), solver.u(1), solver.u(2), solver.face_velocity(),
                                            solver.p(), opt.nu));
    std::vector<std::array<double, 3>> force(F.pressure.size());
    for (std::size_t k = 0; k < force.size(); ++k)
      for (int c = 0; c < 3; ++c) force[k][c] = F.pressure[k][c] + F.viscous[k][c];
    auto bodies = first.size() == 2 ? std::vector<std::array<double, 3>>{F.total} : per_body(force, first);
    auto pressure =
        first.size() == 2 ? std::vector<std::array<double, 3>>{F.pressure_total} : per_body(F.pressure, first);
    auto viscous = first.size() == 2 ? std::vector<std::array<double, 3>>{F.viscous_total} : per_body(F.viscous, first);
    const double cx = scale * bodies[0][0];
    for (auto* set : {&bodies, &pressure, &viscous})
      for (auto& f : *set)
        for (double& c : f) c *= s.rho;
    r.time.push_back(t);
    r.force.push_back(bodies);
    r.pressure.push_back(pressure);
    r.viscous.push_back(viscous);
    return cx;
  });
  finish(s, cv, r, t0);
  if (finished) finished(solver);
  return r;
}

}  // namespace finverse::cfd::cases
