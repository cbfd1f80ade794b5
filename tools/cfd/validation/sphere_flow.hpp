// Steady flow past a sphere at Re = 100 (issue 4 validation of the 3-D triangulated immersed
// boundary): a sphere of diameter D = 1 (an icosphere, surface_shapes.hpp) in a uniform stream
// U = 1 in the box [-8, 16] x [-8, 8]^2, uniform inlet, convective outlet, free-slip sides; a
// uniform grid of spacing D/N in a core around the sphere and its near wake, geometric stretching
// outside (Axis::stretched_count). The drag coefficient CD = 2 F_x / (rho U^2 pi D^2 / 4), from
// the traction on the true surface (surface_traction_3d.hpp), is compared with the steady
// axisymmetric value of Johnson & Patel (1999, J. Fluid Mech. 378:19), CD = 1.087.
#pragma once

#include <functional>
#include <vector>

#include "cfd/flow/flow_solver.hpp"

namespace finverse::cfd {

struct SphereFlowSetup {
  int cells_per_diameter = 20;
  double re = 100;
  double t_end = 20;
  double cfl = 0.8;  // target of dt sum_d |u_d| / h_d
  // The run starts from the uniform stream projected onto the discretely divergence-free fields
  // (potential flow around the body); the vorticity then develops from the impulsive start.
  std::array<double, 2> box_x{-8, 16};
  double box_half_width = 8;
  std::array<double, 2> core_x{-0.75, 1.75};  // uniform core in x (and [-0.75, 0.75] across)
  double core_half_width = 0.75;
  double stretch_ratio = 1.12;
  int subdivisions = 5;  // icosphere: 20 * 4^s triangles
  int force_every = 10;  // steps between force evaluations
  // The pressure ghosts impose the wall's momentum balance dp/dn = -nu n . curl(omega)
  // (wall_pressure_gradient_3d.hpp) instead of dp/dn = 0 (FlowOptions::viscous_wall_pressure).
  bool viscous_wall_pressure = false;
  // Control volume for the independent drag (control_volume_force.hpp): x from, x to, half width.
  // Measured (traction / control volume): D/20 1.08023 / 1.07828, D/32 (t = 15) 1.09194 / 1.08779.
  std::array<double, 3> control_volume{-1.0, 2.0, 1.0};
  std::function<void(const StepStats&, double cd)> progress;
};

struct SphereFlowResult {
  double cd = 0, cd_pressure = 0, cd_viscous = 0, cl = 0;  // at t_end (cl: |lateral| coefficient)
  double cd_drift = 0;                                     // |CD(t_end) - CD(t_end - 5)| (steadiness)
  double cd_control_volume = 0;                            // at t_end, from the momentum balance of the control volume
  std::vector<double> time, cd_history;
  std::array<int, 3> cells{};
  long ghost_cells = 0, surface_samples = 0, triangles = 0, steps = 0;
  double mean_poisson_iterations = 0, mean_momentum_iterations = 0, max_divergence = 0;
  double h = 0, cpu_seconds = 0;
};

SphereFlowResult run_sphere_flow(const SphereFlowSetup& setup);

// The set-up as a data-driven flow case (cases/flow_case.hpp), which run_sphere_flow runs.
namespace cases {
struct FlowCaseSpec;
}
cases::FlowCaseSpec sphere_flow_case(const SphereFlowSetup& setup);

}  // namespace finverse::cfd
