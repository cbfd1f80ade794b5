// Boundary conditions and solver options shared by the cylinder-in-a-channel benchmarks (DFG,
// Schaefer & Turek 1996, dfg_benchmark.hpp; the Turek & Hron 2006 rigid flag, turek_hron_cfd.hpp):
// parabolic inflow of centre-line speed Um ramped in over ramp_time, convective outflow, no-slip
// channel walls; the time step from the CFL number, capped at cfl h / Um for the start-up, and
// Helmholtz/Poisson tolerances tight enough that the forces are converged far below the
// benchmarks' bound intervals.
#pragma once

#include "cfd/flow_boundary.hpp"
#include "cfd/flow_solver.hpp"

namespace finverse::cfd {

FlowBoundary channel_benchmark_boundary(double um, double ramp_time);
FlowOptions channel_benchmark_options(double nu, double cfl, double h, double um);

}  // namespace finverse::cfd
