// A quasi-steady hydrodynamic load on the fin under its analytic root drive (issue 34's cheap
// virtual fish): no flow solve, a load that the loop can also be given as its "measured loads".
// Per shell triangle, from the rigid motion the drive gives its centroid (RootDrive::
// rigid_position, the drive's steady state: no ramp), strip-theory pressure on the plate:
//   p = -( 1/2 rho C_D |w_n| w_n + C_a rho c a_n ),
// w_n the normal velocity of the plate relative to the water (the free stream U along +x
// included, so a pitched plate meets it at an angle), a_n its normal acceleration, C_D the
// resistive (normal flat plate) coefficient, C_a rho c the added mass per unit area (C_a = pi/4:
// a 2-D plate of chord c, rho pi c^2 / 4 per unit span, spread over the chord). The force
// p A n goes a third to each corner (loads.h5's pressure_jump and nodal_force agree). The
// fin's own flex is not fed back (the load of a rigid fin carried by the drive).
#pragma once

#include <filesystem>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/stage_files.hpp"
#include "fem/root_drive.hpp"

namespace finverse::fem::io {

struct QuasiSteadyLoadOptions {
  double density = 1000;                 // rho, kg m-3 (water)
  double speed = 0.1;                    // U, m/s along +x (the free stream past the swimming fin)
  double drag_coefficient = 2.0;         // C_D of a plate normal to the flow
  double added_mass_coefficient = 0.7853981633974483;  // C_a (pi / 4)
  double chord = 0.01;                   // c, m: the added mass's length scale
  double scale = 1.0;                    // multiplies the whole load (a stated sizing knob)
};

// The loads at `times` (finverse/loads: nodal_force, pressure_jump, force_total, coefficients
// on the fin's rest area). `drive` should have no ramp. Throws InvalidInput for a mesh without
// triangles or options out of range.
stage::Loads quasi_steady_loads(const stage::Mesh& mesh, const RootDrive& drive, const std::vector<double>& times,
                                const QuasiSteadyLoadOptions& options);

struct FileLoadsOptions {
  std::filesystem::path mesh, root_drive, out;
  double start_periods = 0;  // first time, in periods of the drive
  double periods = 2;
  int frames_per_period = 20;
  QuasiSteadyLoadOptions load;  // speed and chord: from the mesh and the drive file when <= 0
  double reynolds = 1000, viscosity = 1e-6;
};
// Body of `fin-fem loads`: times start_periods T + k T / frames_per_period, k = 0 .. periods
// frames_per_period; writes loads.h5 with T. Returns the largest nodal force magnitude (N).
double write_quasi_steady_loads(const FileLoadsOptions& options, const nlohmann::json& config);

}  // namespace finverse::fem::io
