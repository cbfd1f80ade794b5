// A thin rigid plate (a stadium of thickness t, chord 1, rounded ends so the leading edge has no
// corner) heaving y = h0 sin(omega t) in a stream, after a smooth start of the amplitude, as a 2-D
// moving ghost-cell body, against Garrick's theory (issue 30, item 3b; garrick_theory.hpp).
// The theory is inviscid, so the thrust compared is C_T = C_D(plate at rest) - <C_X(heaving)>,
// both on the same grid, step and Re (the plate at rest a moving body with zero motion), which
// leaves the motion's own change of friction and form drag, of order <alpha^2> C_f. The mean power
// is compared too (reported only). Set-up and numbers: docs/studies/garrick_heaving_plate.md.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "cfd/flow/flow_solver.hpp"

namespace finverse::cfd {

struct HeavingPlateSetup {
  double re = 1000;                           // U c / nu (why not 10^4: the study)
  double reduced_frequency = 2;               // k = pi f c / U
  std::vector<double> amplitudes = {0.025, 0.0375, 0.05};  // h0 / c, one run each (plus the plate at rest)
  double thickness = 0.03;                    // t / c
  int cells_per_chord = 100;                  // h = c / N in the box around the plate's path
  int periods = 6;                            // simulated; the last periods_averaged are averaged
  int periods_averaged = 3;
  double ramp_periods = 1;                    // the heave amplitude's smooth start [periods]
  double cfl = 0.5;                           // dt ~ cfl h / U (a whole number of steps per period)
  double box_behind = 0.5;                    // the uniform box's length behind the trailing edge [c]
  double box_margin = 0.1;                    // the box's margin around the plate's path [c]
  double upstream = 4, downstream = 10, half_height = 5;  // domain [c] from the leading edge / the axis
  double stretch_ratio = 1.08;                // cell growth outside the box
  int end_vertices = 24;                      // polygon vertices on each semicircular end
  std::function<void(const std::string& run, const StepStats&)> progress;

  double period() const;  // T = 1 / f = pi c / (k U)
};

struct HeavingPlateRun {
  double amplitude = 0;                           // h0 / c (0: the plate at rest)
  std::vector<double> cx, cy;                     // force coefficients on (1/2) rho U^2 c, per step
  double mean_cx = 0, mean_cx_pressure = 0, mean_cx_viscous = 0;  // over the averaged periods
  double mean_cp = 0;                             // <-F_y y'> / (1/2 rho U^3 c)
  double cx_period_spread = 0;                    // max - min of the per-period means of cx
  double max_cfl = 0, max_divergence = 0;
  double cpu_seconds = 0;
  // A heaving run that the solver stopped (finverse::Error: a blow-up, the CFL limit) is kept as
  // a result: the other amplitudes are still compared. Its histories end at the failed step.
  bool failed = false;
  std::string error;
};

struct HeavingPlateResult {
  std::vector<double> time;       // the step times, the same for every run
  HeavingPlateRun rest;
  std::vector<HeavingPlateRun> heaving;  // one per setup amplitude, in order
  long cells = 0, steps = 0, steps_per_period = 0;
  double dt = 0, h = 0;
};

// The plate as a polygon: leading edge at x = 0, trailing edge at x = c, centred on y = 0.
Polygon heaving_plate_polygon(double thickness, int end_vertices);

HeavingPlateResult run_heaving_plate(const HeavingPlateSetup& setup);

}  // namespace finverse::cfd
