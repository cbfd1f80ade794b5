// The 2-D decaying Taylor-Green vortex in the periodic box [0, 2 pi]^2, the first validation case
// of the flow solver (observed order of accuracy in space and in time):
//
//     u = -cos x sin y F(t),  v = sin x cos y F(t),  p = -(cos 2x + cos 2y) F(t)^2 / 4,
//     F(t) = exp(-2 nu t),
//
// an exact solution of the incompressible Navier-Stokes equations in which convection is balanced
// by the pressure gradient, so the discrete convective, pressure and viscous terms all contribute
// to the error. The grid is uniform (stretch = 0) or the smooth periodic non-uniform mapping
// x = xi + stretch sin(xi) in each direction (cell widths varying by (1+s)/(1-s)), sampled at
// xi = 2 pi i / n so refinements form a proper convergence family.
#pragma once

#include <vector>

#include "cfd/grid/stretched_grid.hpp"

namespace finverse::cfd {

struct TaylorGreenSetup {
  int n = 32;            // cells per direction
  double nu = 0.05;      // kinematic viscosity (Re = 1/nu with unit speed and wavenumber)
  double t_end = 1.0;
  double dt = 0.05;      // fixed; t_end / dt is rounded to a whole number of steps
  double stretch = 0.0;  // 0 <= stretch < 1
  // Pressure-coupling time of the face predictor (FlowOptions::coupling_time); a temporal study
  // keeps it fixed (<= the smallest dt) so that only dt changes between its runs.
  double coupling_time = 0.0;
};

struct TaylorGreenResult {
  TaylorGreenSetup setup;
  int steps = 0;
  double u_l2 = 0, u_linf = 0;  // velocity error (both components), volume-weighted RMS and max
  double p_l2 = 0;              // pressure error at t_end - dt/2 (where it lives), means removed
  double max_divergence = 0;    // of the face velocities, at the end
  double mean_poisson_iterations = 0;
  double mean_helmholtz_iterations = 0;
  double momentum_drift = 0;    // max |sum V u_c| over the run (zero initially)
  double cpu_seconds = 0;
  std::vector<double> u, v;     // final cell velocities (x fastest), for Richardson differences
  std::vector<double> volume;
};

StretchedGrid taylor_green_grid(int n, double stretch);
TaylorGreenResult run_taylor_green(const TaylorGreenSetup& setup);
// Volume-weighted RMS difference of the final velocities of two runs on the same grid.
double velocity_difference(const TaylorGreenResult& a, const TaylorGreenResult& b);

}  // namespace finverse::cfd
