// The DFG benchmark 3D-1Z of Schaefer & Turek (1996): steady flow (Re = 20) past a circular
// cylinder that spans a square channel from wall to wall, run with the fractional-step solver and
// the 3-D triangulated ghost-cell immersed boundary (issue 4 validation: cD within 2% of 6.185).
//
// Channel [0, 2.5] x [0, H] x [0, H], H = 0.41; cylinder D = 0.1, axis along z through
// (0.5, 0.2); nu = 1e-3, rho = 1; inflow U(0, y, z) = 16 Um y z (H - y)(H - z) / H^4 with
// Um = 0.45 (Ubar = 4 Um / 9 = 0.2, Re = Ubar D / nu = 20); no-slip walls y = 0, H and z = 0, H;
// convective outflow at x = 2.5. The run starts from the inflow profile everywhere (projected onto
// the divergence-free fields) and stops at steady state (below) or at t_end.
//
// The body crosses the domain: the triangulated cylinder (surface_shapes.hpp) is closed by end
// caps a distance `overhang` outside z = 0 and z = H, so that every cell centre of the span inside
// it is solid and every ghost cell's intercept lies on the lateral surface (its image point then
// stays in its own z plane, inside the grid); the surface traction is integrated over the part
// inside the channel only, with the z walls' no-slip condition between the last cell centres and
// the walls (SurfaceClip, surface_traction_3d.hpp).
//
// Grid: a uniform core of h = D / N over [0.4, 0.7] x [0.1, 0.3] (symmetric about the cylinder in
// y), geometric stretching (ratio <= stretch_ratio) outside it to the inlet, the outlet and the y
// walls; in z (no body edge to resolve) the cells cluster towards both walls by the mapping
// z(s) = H [(1 - b) s + b (1 - cos(pi s)) / 2], b = 1/2, s in [0, 1] (wall cells half, mid-span cells
// 1.29 times the mean width), with span_cells chosen so that the mid-span width is about h: the
// traction's probe length is the largest local cell width (surface_traction_3d.hpp), so a coarser
// span lengthens the probes of the whole cylinder (docs/studies/dfg_3d1z_span.md).
//
// Coefficients: cD = 2 Fx / (rho Ubar^2 D H), cL = 2 Fy / (rho Ubar^2 D H) from the surface traction;
// dp = p(0.45, 0.2, 0.205) - p(0.55, 0.2, 0.205), the wall pressures at the front and back of the
// cylinder at mid-span (extrapolated to the wall as the traction's pressure, 2 p(d) - p(2d)).
// Steady state: the relative change of cD over the last `steady_window` seconds, divided by the
// window, below steady_tolerance (per second).
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "cfd/flow/flow_solver.hpp"

namespace finverse::cfd {

struct Dfg3dSetup {
  int cells_per_diameter = 12;
  int span_cells = 0;          // cells along z; 0: from h (mid-span width about h), a multiple of 8
  int segments = 128;          // cylinder cross-section polygon (a vertex at the front and the back)
  double overhang = 0.05;      // end caps this far outside the z walls
  double stretch_ratio = 1.08;
  double cfl = 0.8;
  double t_end = 12;           // upper limit of the simulated time [s]
  double t_min = 2;            // no steady-state stop before this
  double steady_window = 1.0;  // [s]
  double steady_tolerance = 1e-4;  // relative cD change per second
  int force_every = 5;         // steps between force evaluations
  // The pressure ghosts impose the wall's momentum balance (FlowOptions::viscous_wall_pressure;
  // left at dp/dn = 0 where the fit's window crosses the channel walls).
  bool viscous_wall_pressure = false;
  std::function<void(const StepStats&, double cd)> progress;
};

struct Dfg3dSample {
  double t = 0, cd = 0, cl = 0, dp = 0;
};

struct Dfg3dResult {
  std::vector<Dfg3dSample> history;
  double cd = 0, cl = 0, dp = 0, cd_pressure = 0, cd_viscous = 0;
  double cd_drift = 0;  // relative cD change per second over the last steady_window
  bool steady = false;  // stopped by the steady-state criterion (not by t_end)
  std::array<int, 3> cells{};
  long ghost_cells = 0, surface_samples = 0, triangles = 0, steps = 0;
  double h = 0, mean_poisson_iterations = 0, mean_momentum_iterations = 0, max_divergence = 0;
  double cpu_seconds = 0;
};

Dfg3dResult run_dfg_3d1z(const Dfg3dSetup& setup);

}  // namespace finverse::cfd
