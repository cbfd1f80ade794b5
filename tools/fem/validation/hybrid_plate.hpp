// Hybrid plate of the seed paper's section 3.4 against CalculiX (run by `fin-fem <case>`):
//   hybrid_plate_static   dead uniform pressure, leading edge clamped: y displacement of the three
//                         beam tips against CalculiX (S8R + B32R, NLGEOM, its converged mesh).
//   hybrid_plate_dynamic  in vacuo heave of the leading edge y_LE = A (1 - cos 2 pi f t) from rest,
//                         generalized-alpha with rho_inf = 1 (the trapezoidal rule, as ccx's
//                         *DYNAMIC with ALPHA = 0) and the same time step: tip deflection relative
//                         to the leading edge, w(t) = u_y,tip(t) - y_LE(t), over the whole history.
// The reference data/reference/hybrid_plate_calculix.json is written by
// tools/scripts/calculix_hybrid_plate.py --reference-out (mesh study included).
#pragma once

#include <filesystem>

#include "fem/sparse_solver.hpp"
#include "report.hpp"

namespace finverse::fem::validation {

struct HybridPlateOptions {
  std::filesystem::path case_file;  // data/cases/hybrid_plate.json
  std::filesystem::path reference;  // data/reference/hybrid_plate_calculix.json
  int nx = 16, nz = 16;             // grid cells (two triangles each)
  double tolerance = 0.02;
  double periods = 0;               // dynamic: simulated periods, 0 = the case's (CI: fewer)
  SolverBackend backend = SolverBackend::cholmod;
};
Report run_hybrid_plate_static(const HybridPlateOptions& options);
Report run_hybrid_plate_dynamic(const HybridPlateOptions& options);

}  // namespace finverse::fem::validation
