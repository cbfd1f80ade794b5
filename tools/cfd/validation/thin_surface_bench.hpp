// The cost of a thin body in the flow (issue 44's benchmark, results/bench/thin_surface.json): the
// wall time of a time step of the heaving and pitching plate of thin_plate_loads (c/20, Re 100,
// fin-cfd fin's grid and step) as the zero-thickness sheet and as the closed two-cell body, each
// against the same grid and step with no body, measured in one run.
#pragma once

namespace finverse::cfd::validation {

struct ThinSurfaceBench {
  double sheet_s_per_step = 0, closed_s_per_step = 0, empty_s_per_step = 0;
  long steps = 0, cells = 0, markers = 0;
};

// `periods` of the plate's motion (the steps timed include the set-up of the body at every step).
ThinSurfaceBench run_thin_surface_bench(double periods, int cells_per_chord);

}  // namespace finverse::cfd::validation
