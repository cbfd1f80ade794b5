// Fit validation on the uniform plate of the seed paper's sections 3.2-3.3 (issue 31, validation
// 1; the paper's Table 2): a twin whose truth is the motion fin-fem computes with E/(rho U^2) =
// 6e6, nu = 0.25 (uniform_plate_twin.hpp: W/L = 0.54, pitch alpha0 = 12 deg about the leading
// edge at f = 1 with a smooth start, mass ratio 0.1, K = 0.5) under the thin-airfoil loads of the
// rigid pitching plate (thin_airfoil_loads.hpp), fitted back by eq. (1) (dynamic, compared over
// the last period) with log10 E over three decades around the truth (placed off-centre, as
// hybrid_plate_fit.hpp) and nu in [0.15, 0.45]. Goals: E within 0.5 %, nu within 5 % (the
// paper: -1.8 % and 11.7 %).
#pragma once

#include "core/summary.hpp"
#include "fit/fit_driver.hpp"

namespace finverse::fit::validation {

struct UniformPlateFitOptions {
  // Plate grid (chord x span cells, two triangles each): 8 x 4 keeps the cells square (W/L =
  // 0.54) and an evaluation under a second (10 x 6 costs 2.4x as much).
  int nx = 8, nz = 4;
  double periods = 2;      // simulated from rest (the first is the pitch's ramp); the last is compared
  // The truth runs at the fit's own time step, so that the twin measures the fit and not the
  // time-discretisation error.
  int steps_per_period = 100;
  int compared_frames = 20;  // eq. (1): frames compared over the last period
  // Fluid density of the thin-airfoil loads relative to the case's (1). The loads of the rigid
  // pitch do not relax as the plate deflects, and the plate in vacuo (first bending frequency
  // 1.25 f, no fluid added mass or damping) is driven near resonance: at full density the
  // trailing edge swings beyond +-0.8 chord within the first period and Newton stalls at T/100
  // (t = 1.0-1.1 T); at 0.3 it stalls at t = 1.3-1.8 T. At 0.1 the truth runs (trailing edge
  // +-0.86 chord) and so do evaluations at the corners of the search box on the 8 x 4 grid
  // (on 10 x 6, E = truth, nu = 0.45 stalls: the optimiser scores such a point +infinity).
  double load_scale = 0.1;
  // log10 E bounds, decades below and above the truth: three decades off centre (so that a fit
  // cannot win by returning the middle). A short test may narrow them: the basin of eq. (1) is
  // only about +-0.1 decade wide (the period-long comparison of a lightly damped, near-resonant
  // motion is multimodal in E).
  double decades_below = 1.3, decades_above = 1.7;
  FitOptions fit;  // runs, population, generations, seed, threads
};

// Metrics: E and nu relative to the truth (tolerances 0.005 and 0.05), and as info the objective,
// evaluations, wall time, evaluations per second, the truth's trailing-edge amplitude and its
// deflection from the rigid pitch over the chord.
Summary run_uniform_plate_fit(const UniformPlateFitOptions& options);

}  // namespace finverse::fit::validation
