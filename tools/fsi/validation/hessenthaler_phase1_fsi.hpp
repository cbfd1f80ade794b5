// Issue 49: the Hessenthaler et al. (2017) Phase I experiment in 3-D. The flow is a fin-cfd case
// file (the junction's walls, fluid inside, two parabolic inflows); the flap is fin-fit flap's shell
// strip, clamped at the floor (z = 0) along +z, width along x, net buoyancy along +y, seen by the
// flow as a zero-thickness sheet. Phase I is steady, so instead of a time-accurate run (several
// 2.4 s wet periods) the steady state is the root of tip(S(F(t))) - t: the sheet held at a
// first-mode shape of tip t, F the flow's time-mean load on it, S the static structure.
// Methods tried and why they failed: docs/studies/hessenthaler_flap.md, "Phase I in 3-D".
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/summary.hpp"
#include "fem/validation/hessenthaler_flap.hpp"

namespace finverse::fsi::validation {

struct HessenthalerPhaseIOptions {
  std::filesystem::path flow_case;   // fin-cfd case file of the junction (walls, inflows)
  std::filesystem::path reference;   // data/reference/hessenthaler2017.json
  std::filesystem::path centreline;  // the 59 MRI points (phaseI_centreline.csv: x_mm, y_mm, z_mm)
  double youngs_modulus = 0;         // [Pa], from fin-fit flap
  double h = 0;                      // > 0: the grid's cell width instead of the case file's [m]
  fem::validation::FlapMesh mesh{fem::validation::FlapModel::shell, 32, 4};
  double develop_time = 2.0;  // the flow's start (inflow ramp 0.5 s) with the flap held [s]
  double settle_time = 0.1;   // the flow's settling on a held sheet before each window [s]
  double window_time = 0.2;   // the load's averaging window [s]
  double move_time = 0.1;     // the sheet's step from one iterate to the next, at least [s]
  double move_speed = 0.1;    // ... and no faster on average than this [m/s]
  double omega = 0.5;         // the first step: this fraction of the way to the structure's answer
  int max_iterations = 15;
  double tolerance = 0.1e-3;  // steady: the answer's tip within this of the held tip, or the root
                              // bracketed this closely [m]
  bool start_straight = false;  // the start shape: straight, or (default) the no-flow buoyancy shape
  // Where to write the flow at the end (the held flap at the root) on the planes plane_z above the
  // clamp (flow_planes.hpp); empty: not written.
  std::filesystem::path planes_file;
  std::vector<double> plane_z{0.010, 0.030};  // [m]
  // Where to write every evaluation's held tip and time-mean nodal load (flap_loads.h5, the
  // structure's frame), fin-loop flap's 3-D Phase I frame; empty: not written.
  std::filesystem::path loads_file;
  // Flow-side perturbations for fin-loop flap's flow candidates: the case's viscosity and every
  // inflow's speed times these.
  double viscosity_factor = 1, inflow_factor = 1;
  std::function<void(const std::string&)> progress;
};

// Runs the fixed point and returns the summary (results/validation/flap_phase1/summary.json): tip
// deflection against 16.41 mm (1 mm), centreline RMS against the MRI points (1 mm), the iterates'
// history, grid, cost. A run that ends unconverged is graded (steady_state_reached = 0); a
// failing flow step or structure solve throws.
Summary run_hessenthaler_phase1(const HessenthalerPhaseIOptions& options);

// The centreline's RMS distance along y from the measured points (z, y) [m] at their z, the
// simulated centreline (z, y) [m] interpolated linearly in z (its z increasing from the clamp);
// measured points beyond the simulated tip's z are compared with the tip.
double centreline_rms(const std::vector<std::array<double, 2>>& simulated,
                      const std::vector<std::array<double, 2>>& measured);


}  // namespace finverse::fsi::validation
