// The DFG flow-around-a-cylinder benchmarks 2D-1 (Re = 20, steady), 2D-2 (Re = 100, periodic) and
// 2D-3 (Um = 1.5 sin(pi t / 8) on t in [0, 8]: the shedding starts and dies within one run) of
// Schaefer & Turek (1996), run with the fractional-step solver and the ghost-cell immersed
// cylinder: channel [0, 2.2] x [0, 0.41], cylinder D = 0.1 centred at (0.2, 0.2), nu = 1e-3,
// parabolic inflow with centreline speed Um (0.3, 1.5 or the sine), convective outflow, no-slip
// walls. 2D-3 has high-precision reference values (John 2004) for the largest drag and lift and
// their times, where 2D-2 has only the 1996 bounds; it runs from rest with a fixed time step that
// ends on t_end (8) and no start-up ramp (the sine is its own).
// Grid: a uniform box of h = D / N over [0.1, box_x1] x [0.1, 0.3] (symmetric about the cylinder
// in y) and geometric stretching (ratio <= stretch_ratio) outside it, to the inlet, outlet and walls.
// Optionally a finer core of h = D / N_core around the cylinder, [xc - 0.75 D, xc + D/2 + core_wake D] x
// [yc - 0.75 D, yc + 0.75 D], joined to the box by geometric growth (ratio <= 1.1; Axis::nested):
// at Re = 100 the boundary layer is about a fifth of D thick and the drag and lift amplitude
// converge with the cells across it, while the wake needs only the box's spacing.
//
// Coefficients (rho = 1, Ubar = 2 Um / 3, for 2D-3 that of the sine's peak, 1): CD = 2 Fx / (Ubar^2 D), CL = 2 Fy / (Ubar^2 D), from the
// surface traction (surface_traction.hpp); dp = p(0.15, 0.2) - p(0.25, 0.2), the wall pressures at
// the front and back of the cylinder; St = f D / Ubar from the mean period of the lift.
// The same coefficients from a control-volume momentum balance (control_volume_force.hpp) are
// recorded alongside, as an independent check of the traction evaluation.
#pragma once

#include <array>
#include <functional>
#include <limits>
#include <vector>

#include "cfd/flow/flow_solver.hpp"
#include "cfd/forces/surface_traction.hpp"

namespace finverse::cfd {

struct DfgSetup {
  int variant = 1;            // 1: 2D-1, 2: 2D-2, 3: 2D-3 (the benchmark's t_end is 8)
  int cells_per_diameter = 32;
  int core_cells_per_diameter = 0;  // > cells_per_diameter: the finer core around the cylinder
  double core_wake = 0.75;    // the core ends this many diameters behind the cylinder's rear
  int polygon_vertices = 512;
  double t_end = 10;          // simulated time [s]
  double window = 3;          // 2D-2: the analysis window at the end [s]
  double cfl = 0.5;
  double ramp_time = 1.0;     // inflow ramp (1 - cos) / 2 [s]
  double box_x1 = 0.6;        // downstream end of the uniform box [m]
  double stretch_ratio = 1.05;  // largest ratio of neighbouring cell widths outside the box
  // The same between the box and the channel walls (y); 0: stretch_ratio. 1 keeps the box's
  // spacing out to the walls, whose unsteady (Stokes) layers under the passing vortices are about
  // sqrt(2 nu / omega) ~ D/10 thick at Re 100.
  double wall_stretch_ratio = 0;
  // The cut-cell mass balance for the fixed cylinder (FlowOptions::cut_cell_continuity_fixed);
  // false: the staircase balance, to compare (the cut-cell balance's own effect on each number is
  // in the comment of that option).
  bool cut_cell_continuity = true;
  // The pressure ghosts carry the wall's momentum balance dp/dn = -nu d(omega)/ds
  // (FlowOptions::viscous_wall_pressure); false: dp/dn = 0, to compare.
  bool viscous_wall_pressure = true;
  // How the surface traction and dp reach the wall from their probes (surface_traction.hpp);
  // Quadratic, to compare.
  WallExtrapolation wall_extrapolation = WallExtrapolation::Linear;
  // Control volume [x0, x1] x [y0, y1] of the independent momentum-balance force
  // (control_volume_force.hpp); two cells clear of the body, so the default needs N >= 8.
  std::array<double, 4> control_volume{0.11, 0.45, 0.11, 0.29};
  std::function<void(const StepStats&)> progress;  // called after every step
};

struct DfgSample {
  double t = 0, cd = 0, cl = 0, dp = 0;
  double cd_pressure = 0, cl_pressure = 0;  // the pressure parts of cd, cl
  double cd_cv = 0, cl_cv = 0;              // from the control-volume momentum balance
};

struct DfgResult {
  std::vector<DfgSample> history;
  // 2D-1: the final values; 2D-2: maxima over the window, Strouhal number, lift periods counted;
  // 2D-3: maxima over the run and their times, dp at the end (t = 8).
  double cd = 0, cl = 0, dp = 0;
  double cd_max = 0, cl_max = 0, st = 0;
  double t_cd_max = 0, t_cl_max = 0;
  // 2D-2 window: CD mean, CL min; the same maxima from the control-volume force.
  double cd_mean = 0, cl_min = 0, cd_max_cv = 0, cl_max_cv = 0;
  int periods = 0;
  // 2D-2: dp at t0 + 1/(2f), t0 the time of a lift maximum in the window (Schaefer & Turek's
  // fourth 2D-2 quantity); NaN when the window holds no full period.
  double dp_half_period = std::numeric_limits<double>::quiet_NaN(), t_lift_peak = 0;
  double cd_drift = 0;  // 2D-1: |CD(t_end) - CD(t_end - 1 s)|, the distance from steady state
  long steps = 0, cells = 0, ghost_cells = 0;
  double mean_poisson_iterations = 0, max_poisson_iterations = 0, mean_momentum_iterations = 0;
  double cpu_seconds = 0;
};

// The benchmark's grid: a uniform box of h = D / cells_per_diameter (and the finer core, when set)
// around the cylinder, geometric growth to the inlet and outlet (stretch_ratio) and to the channel
// walls (wall_stretch_ratio).
StretchedGrid dfg_grid(const DfgSetup& setup);

DfgResult run_dfg(const DfgSetup& setup);

// 2D-2's statistics over the last `window` seconds of r.history: CD_max, CL_max, CL_min, CD mean,
// the control-volume maxima, St from the lift's period and dp at t0 + 1/(2f).
void dfg_periodic_statistics(DfgResult& r, double window);

}  // namespace finverse::cfd
