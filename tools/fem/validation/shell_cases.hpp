// Validation cases of the corotational shell triangle (corotational_shell.hpp), run by
// `fin-fem <case>`; references from structures.json.
//   sze_end_shear   Sze, Liu & Lo (2004), Finite Elem. Anal. Des. 40:1551, sec. 3.1: cantilever
//                   strip under an end shear force, 10 load levels, w_tip and -u_tip.
//   sze_end_moment  the same paper: strip under an end moment that rolls it into a full circle
//                   at M_max = 2 pi EI / L; -u_tip and w_tip at M/M_max = 1/4 ... 1.
//   sze_hemisphere  the same paper: open hemisphere (18 deg hole) under alternating radial point
//                   loads, quarter model; outward / inward displacement of the loaded points.
//   elastica_shell  the elastica (dead tip load perpendicular to the undeformed axis) computed
//                   with a shell strip instead of beams, PL^2/EI = 1 ... 20.
#pragma once

#include <filesystem>

#include "core/summary.hpp"
#include "fem/sparse_solver.hpp"

namespace finverse::fem::validation {

struct SzeEndShearOptions {
  std::filesystem::path reference;  // structures.json
  int nx = 32, ny = 2;              // cells along / across the strip (2 triangles each)
  int steps_per_level = 2;          // initial Newton load steps between reference levels
  double tolerance = 0.01;
  SolverBackend backend = SolverBackend::cholmod;
};
Summary run_sze_end_shear(const SzeEndShearOptions& options);

struct SzeEndMomentOptions {
  std::filesystem::path reference;
  int nx = 32, ny = 2;
  int steps_per_level = 8;  // a quarter of a circle per level
  double tolerance = 0.01;
  SolverBackend backend = SolverBackend::cholmod;
};
Summary run_sze_end_moment(const SzeEndMomentOptions& options);

struct SzeHemisphereOptions {
  std::filesystem::path reference;
  // Cells of the quarter model (2 triangles each). Flat facets converge from the stiff side:
  // inward displacement at P_max -8.1 % (16), -3.0 % (24), -1.4 % (32 x 32).
  int n_meridian = 32, n_circumference = 32;
  int steps_per_level = 10;
  double tolerance = 0.02;
  SolverBackend backend = SolverBackend::cholmod;
};
Summary run_sze_hemisphere(const SzeHemisphereOptions& options);

struct ElasticaShellOptions {
  std::filesystem::path reference;
  int nx = 32, ny = 1;
  int load_steps_per_unit = 4;  // initial Newton load steps per unit of PL^2/EI
  double tolerance = 0.005;
  SolverBackend backend = SolverBackend::cholmod;
};
Summary run_elastica_shell(const ElasticaShellOptions& options);

}  // namespace finverse::fem::validation
