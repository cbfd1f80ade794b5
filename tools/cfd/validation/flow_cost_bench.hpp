// The cost benchmark of the flow solver: wall time per cell per time step of the full fractional
// step (predictor with AB2/CN Helmholtz solves, face predictor, MG-PCG pressure correction, update)
// on the 3-D Taylor-Green vortex at Re = 1600 (Brachet et al. 1983; the common CFD cost case),
//
//     u = sin x cos y cos z,  v = -cos x sin y cos z,  w = 0,
//     p = (cos 2x + cos 2y)(cos 2z + 2) / 16,
//
// in the periodic box [0, 2 pi]^3 on the smoothly non-uniform grid x = xi + s sin(xi) per axis
// (widths varying by (1+s)/(1-s)), so the pressure solve works on a stretched operator. The vortex
// transitions over t ~ 1-10, so every step has a nontrivial pressure correction.
// A solver whose work is O(cells) gives a flat cost per cell per step over grid sizes.
#pragma once

namespace finverse::cfd {

struct FlowCostResult {
  int n = 0;                    // cells per axis
  int steps = 0;                // timed steps
  double setup_s = 0;           // setup + initial projection
  double seconds_per_step = 0;  // wall, mean over the timed steps
  double ns_per_cell_step = 0;  // 1e9 * seconds_per_step / cells
  double mean_poisson_iterations = 0;
  double mean_helmholtz_iterations = 0;  // summed over the three components
  double max_divergence = 0;             // after the last step
};

// Sets up the case on n^3 cells (n a multiple of 4), runs `warmup` untimed steps (the first step is
// explicit Euler and the pressure warm start builds up), then times `steps` steps.
FlowCostResult run_flow_cost_bench(int n, int warmup, int steps, double stretch = 0.3);

}  // namespace finverse::cfd
