// A spanwise-uniform heaving and pitching plate through the 3-D thin-body path against the 2-D
// solver on its section (issue 30, item 3a): the fin's path (make_thin_plate's mid-surface, the
// closed thin body, FinSurfaceMotion's spline of sampled node positions, immerse(SurfaceMotion),
// surface_forces) must give the 2-D force per unit span.
//
// The plate (chord c = 1, closed-body thickness t, its rim blunt: the rim wall of core/thin_body.hpp
// is the flat end x = 0 or x = c of the section) spans a slab of span_cells uniform cells in z
// between two slip walls and reaches beyond both (FlowOptions::surface_crosses). A slip wall is a
// symmetry plane: a flow that is uniform in z satisfies it, so the slab holds the 2-D flow of the
// section and no periodic boundary is needed. The 2-D reference is the section as a polygon (the
// rectangle [0, c] x [-t/2, t/2], blunt ends as the rim), moved rigidly (immerse(MovingBody)) on
// the same x-y grid with the same time step, Re and stream.
//
// Motion (both): heave y = h0 r(t) sin(omega t), pitch theta = -theta0 r(t) cos(omega t)
// counter-clockwise about x = pivot, i.e. nose up while the plate rises: the pitch leads the heave
// by 90 degrees in the feathering sense (it lowers the heave-induced angle of attack).
// r(t) = (1 - cos(pi t / T_r)) / 2 for t < T_r (a smooth start), then 1.
// Compared over the last period: mean C_T = -<C_X>, the fundamental amplitude and the mean of C_L,
// all on (1/2) rho U^2 c per unit span.
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
  bool failed = false;
  std::string error;
};

struct SpanwisePlateResult {
  std::vector<double> time;
  SpanwisePlateRun flat, slab;  // 2-D polygon, 3-D thin body
  long steps = 0, steps_per_period = 0;
  double dt = 0, h = 0, thickness = 0, span = 0;
};

SpanwisePlateResult run_spanwise_plate(const SpanwisePlateSetup& setup);

}  // namespace finverse::cfd
