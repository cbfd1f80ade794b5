// Hybrid plate of the seed paper's section 3.4 against CalculiX (run by `fin-fem <case>`):
//   hybrid_plate_static   dead uniform pressure, leading edge clamped: y displacement of the three
//                         beam tips against CalculiX (S8R + B32R, NLGEOM, its converged mesh).
//   hybrid_plate_dynamic  in vacuo heave of the leading edge y_LE = A (1 - cos 2 pi f t) from rest
//                         (data/cases/hybrid_plate_small_heave.json: A small enough for the
//                         linear range), generalized-alpha with rho_inf = 1: tip deflection
//                         relative to the leading edge, w(t) = u_y,tip(t) - y_LE(t), over the whole
//                         history against CalculiX's eigenmodes superposed exactly in time: max
//                         history error / peak-to-peak range, the range itself, and amplitude and
//                         phase of the component at the drive frequency.
// The reference data/reference/hybrid_plate_calculix.json is written by
// tools/scripts/calculix_hybrid_plate.py --reference-out (mesh study included).
#pragma once

#include <filesystem>

#include "core/summary.hpp"
#include "fem/sparse_solver.hpp"

namespace finverse::fem::validation {

struct HybridPlateOptions {
  std::filesystem::path case_file;  // data/cases/hybrid_plate.json
  std::filesystem::path reference;  // data/reference/hybrid_plate_calculix.json
  int nx = 16, nz = 16;             // grid cells (two triangles each)
  double tolerance = 0.02;
  double periods = 0;               // dynamic: simulated periods, 0 = the case's (CI: fewer)
  double time_step = 0;             // dynamic: 0 = the case's (time-step study: smaller)
  std::filesystem::path history;    // dynamic: if set, CSV of t and every tip's w (ours, ccx)
  SolverBackend backend = SolverBackend::cholmod;
};
Summary run_hybrid_plate_static(const HybridPlateOptions& options);
Summary run_hybrid_plate_dynamic(const HybridPlateOptions& options);

}  // namespace finverse::fem::validation
