// Boundary conditions and solver options shared by the cylinder-in-a-channel benchmarks (DFG,
// Schaefer & Turek 1996, dfg_benchmark.hpp; the Turek & Hron 2006 rigid flag, turek_hron_cfd.hpp):
// parabolic inflow of centre-line speed Um ramped in over ramp_time, convective outflow, no-slip
// channel walls; the time step from the CFL number, capped at cfl h / Um for the start-up, and
// Helmholtz/Poisson tolerances tight enough that the forces are converged far below the
// benchmarks' bound intervals; and the grid they share (channel_grid).
#pragma once

#include "cfd/flow/velocity_boundary.hpp"
#include "cfd/flow/flow_solver.hpp"
#include "cfd/grid/stretched_grid.hpp"

namespace finverse::cfd {

// The grid of a body in the channel [0, length] x [0, height]: a uniform box of spacing ~h around
// the body and its near wake, optionally a finer uniform core of spacing ~h_core inside it (used
// when h_core < h), geometric growth with ratio <= ratio towards inlet and outlet and <= wall_ratio
// (0: ratio) towards the channel walls. Without a core the counts are rounded to multiples of 8,
// with one they are padded to multiples of 8: three multigrid halvings either way.
struct ChannelGridSpec {
  double length = 0, height = 0;
  double box_x0 = 0, box_x1 = 0, box_y0 = 0, box_y1 = 0, h = 0;
  double core_x0 = 0, core_x1 = 0, core_y0 = 0, core_y1 = 0, h_core = 0;
  double ratio = 1.05, wall_ratio = 0;
};
StretchedGrid channel_grid(const ChannelGridSpec& spec);
// A cell count n rounded to the nearest multiple of 8, at least 8 (three multigrid halvings).
int round8(double n);

FlowBoundary channel_benchmark_boundary(double um, double ramp_time);
FlowOptions channel_benchmark_options(double nu, double cfl, double h, double um);

}  // namespace finverse::cfd
