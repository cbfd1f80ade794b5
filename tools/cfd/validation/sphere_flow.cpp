// Sphere at Re = 100 with the triangulated ghost-cell boundary; see sphere_flow.hpp.
#include "cfd/validation/sphere_flow.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <numbers>

#include "cfd/forces/control_volume_force.hpp"
#include "cfd/immersed/surface_shapes.hpp"
#include "cfd/forces/surface_traction_3d.hpp"
#include "core/error.hpp"

namespace finverse::cfd {

namespace {
// Cell counts that are multiples of 8 keep three halvings for the multigrid.
int round8(double n) { return std::max(8, 8 * static_cast<int>(std::lround(n / 8))); }

Axis axis(double lo, double hi, double ulo, double uhi, double h, double ratio) {
  const int n = round8(Axis::stretched(lo, hi, ulo, uhi, h, ratio).size());
  return Axis::stretched_count(lo, hi, ulo, uhi, n, ratio);
}
}  // namespace

SphereFlowResult run_sphere_flow(const SphereFlowSetup& ss) {
  if (ss.cells_per_diameter < 4) throw Error("sphere_flow: need at least 4 cells per diameter");
  if (!(ss.t_end > 0)) throw Error("sphere_flow: t_end must be > 0");
  const auto t0 = std::chrono::steady_clock::now();
  const double D = 1, U = 1, h = D / ss.cells_per_diameter;
  const double H = ss.box_half_width, c = ss.core_half_width;
  const StretchedGrid grid(axis(ss.box_x[0], ss.box_x[1], ss.core_x[0], ss.core_x[1], h, ss.stretch_ratio),
                           axis(-H, H, -c, c, h, ss.stretch_ratio), axis(-H, H, -c, c, h, ss.stretch_ratio));
  FlowBoundary b;
  b[Side::XLo].type = FlowBcType::Inlet;
  b[Side::XLo].speed = U;
  b[Side::XHi].type = FlowBcType::ConvectiveOutlet;
  for (Side s : {Side::YLo, Side::YHi, Side::ZLo, Side::ZHi}) b[s].type = FlowBcType::Slip;
  FlowOptions opt;
  opt.nu = U * D / ss.re;
  opt.cfl = ss.cfl;
  opt.dt_max = ss.cfl * h / U;
  opt.helmholtz_rtol = 1e-8;
  opt.poisson.rtol = 1e-7;
  opt.viscous_wall_pressure = ss.viscous_wall_pressure;
  FlowSolver solver;
  solver.setup(grid, b, opt);
  const TriangulatedSurface sphere = icosphere({0, 0, 0}, 0.5 * D, ss.subdivisions, true);
  solver.immerse(sphere);
  solver.initialise([U](double, double, double, double) { return std::array<double, 3>{U, 0, 0}; });
  const SurfaceTraction3D traction(grid, *solver.immersed(), *solver.body_surface());
  const auto& cvb = ss.control_volume;
  const ControlVolumeForce control_volume(grid, *solver.immersed(), {cvb[0], cvb[1], -cvb[2], cvb[2], -cvb[2], cvb[2]});
  std::vector<ControlVolumeSample> cv;

  SphereFlowResult r;
  r.h = h;
  r.cells = {grid.nx(), grid.ny(), grid.nz()};
  r.ghost_cells = static_cast<long>(solver.immersed()->ghosts().size());
  r.surface_samples = static_cast<long>(traction.samples().size());
  r.triangles = static_cast<long>(sphere.triangles.size());
  const double scale = 2 / (U * U * std::numbers::pi * D * D / 4);
  long poisson = 0, momentum = 0;
  double cd = 0;
  while (solver.time() < ss.t_end - 1e-12) {
    const StepStats st = solver.step();
    poisson += st.poisson_iterations;
    momentum += st.helmholtz_iterations;
    r.max_divergence = st.max_divergence;
    ++r.steps;
    const bool last = solver.time() >= ss.t_end - 1e-12;
    if (r.steps % std::max(1, ss.force_every) == 0 || last) {
      const SurfaceForces F = traction.evaluate(solver.u(0), solver.u(1), solver.u(2), solver.p(), opt.nu, 1.0);
      cd = scale * F.total[0];
      cv.push_back(control_volume.evaluate(st.time, solver.u(0), solver.u(1), solver.u(2), solver.face_velocity(),
                                           solver.p(), opt.nu));
      r.time.push_back(st.time);
      r.cd_history.push_back(cd);
      if (last) {
        r.cd = cd;
        r.cd_pressure = scale * F.pressure_total[0];
        r.cd_viscous = scale * F.viscous_total[0];
        r.cl = scale * std::hypot(F.total[1], F.total[2]);
      }
    }
    if (ss.progress) ss.progress(st, cd);
  }
  if (cv.size() >= 2) r.cd_control_volume = scale * control_volume_forces(cv, 1.0).back()[0];
  for (std::size_t n = 0; n < r.time.size(); ++n)
    if (r.time[n] <= r.time.back() - 5.0) r.cd_drift = std::abs(r.cd - r.cd_history[n]);
  r.mean_poisson_iterations = static_cast<double>(poisson) / static_cast<double>(r.steps);
  r.mean_momentum_iterations = static_cast<double>(momentum) / static_cast<double>(r.steps);
  r.cpu_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  return r;
}

}  // namespace finverse::cfd
