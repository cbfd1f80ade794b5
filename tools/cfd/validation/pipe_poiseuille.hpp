// Poiseuille flow in a round pipe whose fluid is inside the immersed wall (issue 49's inside flows;
// docs/studies/pipe_flow.md), set up exactly as a user's case file would be (cases/flow_case.hpp:
// a cylinder with fluid: inside crossing the domain's z sides, the parabola on its inlet
// cross-section, a zero-gradient outlet), at the Hessenthaler flap's inlet pipe (D 21.9 mm, the
// aqueous glycerol, Re 1283 on the centreline speed). Against u = U (1 - r^2 / R^2): the
// centreline speed, the wall shear 2 mu U / R and the pressure gradient -4 mu U / R^2, each over
// the pipe's middle, away from the inlet and the outlet.
#pragma once

#include <array>
#include <functional>

#include "cfd/flow/flow_solver.hpp"

namespace finverse::cfd::validation {

struct PipePoiseuilleSetup {
  double diameter = 21.9e-3;       // [m]
  double rho = 1163.3, mu = 0.0125;  // [kg/m^3], [Pa s]
  double reynolds = 1283;          // rho U D / mu, U the centreline speed
  int cells_per_diameter = 22;     // h = D / N
  double length_diameters = 5;     // the pipe inside the domain
  double t_end = 0;                // [s]; 0: three times the pipe's length over the mean speed
  double cfl = 0.5;
  std::function<void(const StepStats&)> progress;
};

struct PipePoiseuilleResult {
  double centreline_speed = 0, centreline_reference = 0;  // [m/s]
  double wall_shear = 0, wall_shear_reference = 0;        // [Pa]
  double pressure_gradient = 0, pressure_gradient_reference = 0;  // [Pa/m]
  double profile_rms = 0;          // RMS of u_z - exact over the middle's fluid cells, / U
  double inflow_rate_error = 0;    // the discrete inflow against pi R^2 U / 2
  double wall_drag_drift = 0;      // relative change of the wall's axial drag over the last fifth of the run
  double h = 0, t_end = 0;
  std::array<int, 3> cells{};
  long steps = 0, ghost_cells = 0, wall_samples = 0;
  double mean_poisson_iterations = 0, max_divergence = 0, cpu_seconds = 0;
};

PipePoiseuilleResult run_pipe_poiseuille(const PipePoiseuilleSetup& setup);

}  // namespace finverse::cfd::validation
