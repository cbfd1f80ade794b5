// The flexible plate pitching about its leading edge in a uniform stream (seed paper section 3.2,
// after Dai et al. 2012; issue 32, validation 3): W = 0.54 L, alpha = 12 deg r(t) sin(2 pi f0 t),
// f0 L / U = 1, rho_s h / (rho_f L) = 0.1, K = D / (rho_f U^2 L^3) with D = E h^3 / (12 (1 - nu^2))
// (the fluid-density definition; the seed's rho_s would scale K by 10 h / L and move the
// resonance out of the 0.5-50 sweep). The 3-D flow around the closed thin body of the
// mid-surface and the shell plate, driven at its leading edge, coupled per step by
// SurfaceFlowStructureStep. Per K over the last period: trailing-edge A / L and phase against the
// rigid motion; graded: the stiffest K and the rigid run within 2 % of sin(alpha0), and the
// amplitude peak against f_wet = f_dry / sqrt(1 + pi W / (4 m L)) (modal analysis + strip-theory
// added mass, Newman 1977 sec. 4.13). Set-up, grid and numbers: docs/studies/fsi_pitching_plate.md.
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "core/summary.hpp"

namespace finverse::fsi::validation {

struct PitchingPlateOptions {
  double re = 100;                     // U L / nu
  double aspect = 0.54;                // W / L
  double pitch_amplitude_deg = 12;     // alpha0
  double frequency = 1;                // f0 L / U
  double mass_ratio = 0.1;             // rho_s h / (rho_f L)
  double poisson_ratio = 0.25;
  double shell_thickness = 0.01;       // h / L: sets rho_s (mass ratio) and E (K); thin enough
  std::vector<double> stiffness{0.5, 1, 2, 4, 10, 50};  // K values to run
  bool rigid = false;                  // also run the rigid plate
  int nx = 8, nz = 4;                  // shell grid (two triangles per cell); nz even
  // Plate in the x-z plane: x in [0, L], z in [-W/2, W/2]. Flow grid: uniform h = L / cells_per_chord around the plate's path, stretched outside.
  int cells_per_chord = 16;
  double thickness_cells = 2;          // closed thin body thickness [h]
  // "closed" (the closed thin body, ghost cells) or "sheet" (the zero-thickness mid-surface with
  // the default kernel and markers; docs/studies/thin_surface.md).
  std::string surface = "closed";
  bool band_correction = false;  // sheet: cfd::SheetForcingOptions::band_correction
  double stretch_ratio = 1.15;
  double upstream = 2, downstream = 5, half_height = 2, half_width = 2;  // domain [L]
  double box_half_height = 0.45;       // uniform box |y| <= this [L]
  int steps_per_period = 100;
  int periods = 3;                     // the last one is measured
  int ramp_periods = 1;
  std::string acceleration = "iqn-ils";
  double omega = 0.1;
  double tolerance = 1e-3;             // relative interface residual
  double absolute_tolerance = 1e-5;    // ... or |x_out - x_in| [L]
  int max_iterations = 15;
  double spectral_radius = 0.8;
  // The shell's Newton residual and increment tolerance (generalized-alpha): 1e-9 stalls at
  // round-off (3.8e-9) for the stiff plates (K = 50, E ~ 6e8 rho_f U^2) under the flow loads.
  double structure_tolerance = 1e-7;
  std::function<void(const std::string&)> progress;
};

struct PitchingPlateCaseResult {
  double stiffness = 0;  // K (0 for the rigid run)
  bool rigid = false;
  double amplitude = 0;              // A / L, half peak-to-peak of y_TE over the last period
  double phase_deg = 0;              // phase of y_TE's fundamental against the rigid TE motion's
  double mean_thrust = 0, lift_amplitude = 0;  // C_T = -<F_x> / (U^2 L W / 2), C_L fundamental
  double coupling_iterations_mean = 0, coupling_iterations_max = 0;
  long steps_at_cap = 0;
  double transfer_mismatch = 0;
  double wall_seconds = 0;
  long flow_cells = 0;
  std::vector<double> time, te_y;    // per step
  std::string error;                 // non-empty: the run failed (then nothing above is measured)
};

// The plate's first natural frequency in vacuum per sqrt(K) (f ~ sqrt(K) at fixed mass; in f0
// units U / L) from fem::modal_analysis, and the wet one with the strip added mass (see above).
struct PitchingPlateModes {
  double dry_per_sqrt_k = 0, added_mass_ratio = 0, wet_per_sqrt_k = 0;
  double resonant_stiffness = 0;  // K with f_wet = f0
};
PitchingPlateModes pitching_plate_modes(const PitchingPlateOptions& options);

// One run (rigid: the prescribed rigid pitching, stiffness ignored). Throws finverse::Error on
// bad options, the coupling's errors naming the step.
PitchingPlateCaseResult run_pitching_plate_case(const PitchingPlateOptions& options, double stiffness, bool rigid);

struct PitchingPlateRun {
  Summary summary{"validation", "fsi_pitching_plate", ""};
  PitchingPlateModes modes;
  std::vector<PitchingPlateCaseResult> cases;
  double wall_seconds = 0;
};

// Every K of the options (and the rigid run), graded; a run that fails is recorded with its error
// (graded metric failed_runs) and the others go on.
PitchingPlateRun run_pitching_plate(const PitchingPlateOptions& options);

}  // namespace finverse::fsi::validation
