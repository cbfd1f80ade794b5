// Sphere at Re = 100 with the triangulated ghost-cell boundary; see sphere_flow.hpp.
#include "cfd/validation/sphere_flow.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "cfd/cases/flow_case.hpp"
#include "cfd/immersed/surface_shapes.hpp"
#include "core/error.hpp"

namespace finverse::cfd {

// The sphere as a data-driven flow case (cases/flow_case.hpp), which a user's own body runs through
// too (data/cases/cfd/sphere_re100_stl.yaml gives this sphere as an STL file).
cases::FlowCaseSpec sphere_flow_case(const SphereFlowSetup& ss) {
  const double D = 1, U = 1, h = D / ss.cells_per_diameter;
  const double H = ss.box_half_width, c = ss.core_half_width;
  cases::FlowCaseSpec s;
  s.name = "sphere_re100";
  s.domain = {ss.box_x[0], ss.box_x[1], -H, H, -H, H};
  s.core = {ss.core_x[0], ss.core_x[1], -c, c, -c, c};
  s.h = h;
  s.stretch_ratio = ss.stretch_ratio;
  s.nu = U * D / ss.re;
  s.rho = 1;
  s.sides[0].type = FlowBcType::Inlet;
  s.sides[0].velocity = {U, 0, 0};
  s.sides[1].type = FlowBcType::ConvectiveOutlet;
  for (int k = 2; k < 6; ++k) s.sides[k].type = FlowBcType::Slip;
  s.initial_velocity = {U, 0, 0};
  cases::CaseBody sphere;
  sphere.name = "sphere";
  sphere.surface = icosphere({0, 0, 0}, 0.5 * D, ss.subdivisions, true);
  sphere.source = "icosphere";
  s.bodies.push_back(sphere);
  s.t_end = ss.t_end;
  s.cfl = ss.cfl;
  s.dt_max = ss.cfl * h / U;
  s.helmholtz_rtol = 1e-8;
  s.poisson_rtol = 1e-7;
  s.wall_momentum_balance = ss.viscous_wall_pressure;
  s.force_every = ss.force_every;
  s.reference_speed = U;
  s.reference_area = std::numbers::pi * D * D / 4;
  const auto& cvb = ss.control_volume;
  s.control_volume = true;
  s.control_volume_box = {cvb[0], cvb[1], -cvb[2], cvb[2], -cvb[2], cvb[2]};
  return s;
}

SphereFlowResult run_sphere_flow(const SphereFlowSetup& ss) {
  if (ss.cells_per_diameter < 4) throw Error("sphere_flow: need at least 4 cells per diameter");
  if (!(ss.t_end > 0)) throw Error("sphere_flow: t_end must be > 0");
  const cases::FlowCaseSpec spec = sphere_flow_case(ss);
  const cases::FlowCaseResult f = cases::run_flow_case(spec, ss.progress);
  const double scale = 2 / (spec.reference_speed * spec.reference_speed * spec.reference_area);
  SphereFlowResult r;
  r.h = spec.h;
  r.cells = f.cells;
  r.ghost_cells = f.ghost_cells;
  r.surface_samples = f.surface_samples;
  r.triangles = f.triangles;
  r.steps = f.steps;
  r.time = f.time;
  for (const auto& F : f.force) r.cd_history.push_back(scale * F[0][0]);
  const auto& F = f.force.back()[0];
  r.cd = r.cd_history.back();
  r.cd_pressure = scale * f.pressure.back()[0][0];
  r.cd_viscous = scale * f.viscous.back()[0][0];
  r.cl = scale * std::hypot(F[1], F[2]);
  if (!f.control_volume_force.empty()) r.cd_control_volume = scale * f.control_volume_force.back()[0];
  for (std::size_t n = 0; n < r.time.size(); ++n)
    if (r.time[n] <= r.time.back() - 5.0) r.cd_drift = std::abs(r.cd - r.cd_history[n]);
  r.mean_poisson_iterations = f.mean_poisson_iterations;
  r.mean_momentum_iterations = f.mean_momentum_iterations;
  r.max_divergence = f.max_divergence;
  r.cpu_seconds = f.cpu_seconds;
  return r;
}

}  // namespace finverse::cfd
