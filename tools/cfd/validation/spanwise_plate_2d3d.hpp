// A spanwise-uniform heaving and pitching plate through the fin's 3-D paths against the 2-D solver
// on its section, in both of the fin's treatments:
//  - closed (issue 30, item 3a): the plate two cells thick spans a slab between two slip walls and
//    reaches beyond both (FlowOptions::surface_crosses): a slip wall is a symmetry plane, so the
//    slab holds the section's 2-D flow. The 2-D reference is the section as a polygon with the
//    same blunt ends;
//  - sheet (issue 44, goal 5): the zero-thickness mid-surface spans a z-periodic slab from seam to
//    seam (its markers see the periodic images, sheet_markers.hpp); the 2-D reference is the
//    section as a sheet polyline.
// Same rigid motion (pitch leading heave by 90 degrees, feathering, after a smooth start), x-y
// grid, step, Re and stream throughout. Compared over the last period per unit span: mean C_T,
// C_L's fundamental amplitude and mean (docs/studies/spanwise_plate_2d3d.md, thin_surface.md).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "cfd/flow/flow_solver.hpp"

namespace finverse::cfd {

struct SpanwisePlateSetup {
  double re = 100;                    // U c / nu
  double period = 2;                  // T [c/U] (k = pi c / (U T) = pi/2, as thin_plate_loads)
  double heave = 0.25;                // h0 / c
  double pitch = 0.2;                 // theta0 [rad]
  double pivot = 0.25;                // pitch axis x / c
  int cells_per_chord = 20;           // h = c / N in the box around the plate's path
  double thickness_cells = 2;         // t = thickness_cells h (0.1 c at c/20)
  int span_cells = 8;                 // slab cells along z (width h each)
  int overhang_cells = 3;             // the plate's reach beyond each slip wall [cells]
  int periods = 2;                    // simulated; the last one compared
  double ramp_periods = 0.5;          // the smooth start
  // dt ~ cfl h / U, a whole number of steps per period; at 0.5 both runs blew up (CFL > 2) near
  // the end of the first period (docs/studies/spanwise_plate_2d3d.md).
  double cfl = 0.25;
  // Both runs with the staircase mass balance instead of the cut-cell one (FlowOptions::
  // cut_cell_continuity, cut_cell_continuity_3d), to separate the balances' share of a difference.
  bool staircase = false;
  int frames_per_period = 200;        // the 3-D motion's samples (spline knots)
  bool closed = true, sheet = true;   // which treatments run (each a 2-D and a 3-D run)
  bool raw_sheet_force = false;       // the sheet's force without the band correction (to compare)
  double box_margin = 0.15, box_behind = 0.5;             // uniform box around the path [c]
  double upstream = 2, downstream = 4, half_height = 2;  // domain [c]
  double stretch_ratio = 1.1;
  std::function<void(const std::string& run, const StepStats&)> progress;
};

struct SpanwisePlateRun {
  std::vector<double> cx, cy;  // on (1/2) rho U^2 c per unit span, per step
  double mean_ct = 0, cl_amplitude = 0, mean_cl = 0;  // over the last period
  double cx_noise = 0, cy_noise = 0;  // rms above the 10th harmonic over the last period
  double max_cfl = 0, max_divergence = 0, seconds = 0;
  long cells = 0;
  bool ran = false, failed = false;
  std::string error;
};

struct SpanwisePlateResult {
  std::vector<double> time;
  SpanwisePlateRun flat, slab;              // closed: 2-D polygon, 3-D thin body
  SpanwisePlateRun flat_sheet, slab_sheet;  // sheet: 2-D polyline, 3-D periodic slab
  long steps = 0, steps_per_period = 0;
  double dt = 0, h = 0, thickness = 0, span = 0;
};

SpanwisePlateResult run_spanwise_plate(const SpanwisePlateSetup& setup);

}  // namespace finverse::cfd
