// The hybrid-plate twin as the fit validations (hybrid_plate_fit.cpp) and the fit benchmark
// (fit_bench.cpp) set it up: the case's leading-edge heave and the thin-airfoil loads of the
// rigid heave, the truth motion at each objective's own time step (eq. (1): steps_per_period;
// eq. (2): the paper's T/400), modulus bounds of three decades placed off-centre around the
// truth, eq. (1)'s compared frames over the last period and eq. (2)'s mid-swing instants.
#pragma once

#include <filesystem>
#include <memory>
#include <vector>

#include "fem/validation/hybrid_plate_model.hpp"
#include "fit/parameter_space.hpp"
#include "fit/target_motion.hpp"
#include "fit/validation/hybrid_plate_twin.hpp"

namespace finverse::fit::validation {

struct HybridPlateSetup {
  std::filesystem::path case_file;  // data/cases/hybrid_plate_small_heave.json
  int nx = 8, nz = 8;               // plate grid (the beams must lie on grid lines)
  double periods = 2;               // simulated from rest; the last one is compared by eq. (1)
  // Each objective is compared with a truth computed at its own time step, so that the twin
  // measures the fit and not the time-discretisation error.
  int steps_per_period = 100;
  int qs_steps_per_period = 400;
  int compared_frames = 20;         // eq. (1): frames compared over the last period
  int instants = 1;                 // eq. (2): mid-swing instants (1: the paper's one)
  // Fluid density of the thin-airfoil loads relative to the case's (1). The loads of the rigid
  // heave do not relax as the plate deflects (no flow feedback): with the case's A = 0.1 c the
  // soft middle beam would deflect tens of chords and Newton stalls at full density, so the fit
  // cases run data/cases/hybrid_plate_small_heave.json (A = 0.001 c) at full density, where the
  // loads dominate the plate's own inertia as eq. (2) assumes.
  double load_scale = 1;
};

struct HybridPlateTwinRun {
  fem::validation::HybridPlateCase plate;
  std::shared_ptr<HybridPlateTwin> factory;
  TargetMotion truth;     // every step of dt, from dt to the end (eq. (1))
  TargetMotion qs_truth;  // every step of qs_dt (eq. (2)'s increments)
  double period = 0, dt = 0, qs_dt = 0;
};

// with_loads false: the heave alone (the identifiability check).
HybridPlateTwinRun make_hybrid_plate_twin(const HybridPlateSetup& setup, bool with_loads);
ParameterSpace hybrid_plate_space(const HybridPlateTwin& twin);
// The last period's compared_frames equally spaced frames; *substeps: time steps between them.
TargetMotion last_period_frames(const HybridPlateTwinRun& twin, const HybridPlateSetup& setup, int* substeps);
std::vector<double> mid_swing_instants(const HybridPlateTwinRun& twin, const HybridPlateSetup& setup);

}  // namespace finverse::fit::validation
