// A flat plate towed at constant speed through fluid at rest against the same plate fixed in a
// uniform stream (issue 44, goal 2; docs/studies/thin_surface.md): the two flows are the same in
// the plate's frame (a periodic box, so no inlet or wall breaks the Galilean equivalence), so the
// force histories must agree, and the towed plate's, whose surface crosses a cell every few steps,
// must have no step-to-step impulse. Both treatments of a thin body side by side: the
// zero-thickness sheet (sheet_forcing.hpp) and the closed body two cells thick of the ghost-cell
// method (rigid_motion.hpp), whose cells change kind as it moves.
#pragma once

#include <string>
#include <vector>

#include "cfd/immersed/sheet_forcing.hpp"

namespace finverse::cfd::validation {

struct TowedPlateSetup {
  double re = 100;            // U c / nu
  double incidence_deg = 10;  // the plate's angle to the stream
  int cells_per_chord = 32;   // h = c / N, uniform periodic box [0, 4c] x [-c, c]
  double cfl = 0.32;          // dt = cfl h / U
  double t_end = 1.2;         // [c / U]
  double t_compare = 0.3;     // the histories compared from here on (after the impulsive start)
  SheetForcingOptions sheet;  // kernel, marker spacing, projection passes
  bool closed = true;         // also the closed two-cell body (the ghost-cell method)
  static TowedPlateSetup coarse() {
    TowedPlateSetup s;
    s.cells_per_chord = 16;
    s.t_end = 0.8;
    return s;
  }
};

// Force histories (per unit depth, rho = 1, force coefficients 2F / (U^2 c)) and their comparison.
struct TowedPlatePair {
  std::vector<double> cd_fixed, cl_fixed, cd_towed, cl_towed;
  double max_difference = 0;       // max over t >= t_compare, both components, / max |C| of the fixed plate
  double max_departure_towed = 0;  // max |C_n - (C_{n-1} + C_{n+1}) / 2| / max |C| (one-step impulse)
  double max_departure_fixed = 0;
  double cd_fixed_end = 0, cl_fixed_end = 0;
  double seconds = 0;
};

struct TowedPlateResult {
  std::vector<double> time;
  TowedPlatePair sheet, closed;  // closed: empty without setup.closed
  long steps = 0;
  std::size_t cells = 0, markers = 0;
};

TowedPlateResult run_towed_plate(const TowedPlateSetup& s);

}  // namespace finverse::cfd::validation
