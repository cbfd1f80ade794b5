// The Turek-Hron elastic flag (Turek & Hron 2006, LNCSE 53, sec. 2-3) as a structure: the part of
// the 0.35 x 0.02 rectangle behind the cylinder outside the cylinder, meshed with Q9 St. Venant-
// Kirchhoff plane-strain solids (plane_strain_solid.hpp), clamped (ux = uy = 0) on the cylinder
// arc. Used by the CSM benchmarks (turek_hron_csm.hpp) and, with its wet-surface node list, as the
// structure of the FSI benchmarks (issue 32; coupled_structure.hpp).
//
// Wet surface: the flag's boundary nodes that touch the fluid, corner and mid-side nodes, in the
// counter-clockwise order of tools/cfd/validation/turek_hron_cfd.cpp's body polygon (turek_hron_body:
// the cylinder arc from its upper flag corner counter-clockwise round to the lower one, then the
// flag's lower edge to the tip, the tip upwards, the upper edge back). So the list runs: lower clamp
// corner, the lower edge to the tip, up the tip, the upper edge back to the upper clamp corner.
// Its first and last nodes are the clamped corners, which coincide with the arc's end vertices
// (to round-off): the flow polygon is the arc's vertices without its two ends, counter-clockwise,
// followed by the wet nodes' current positions. 4 nx + 2 ny + 1 nodes; point A is the
// (2 nx + ny)-th (0-based). Clamped nodes do not move, so the polygon's arc part stays fixed.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "fem/model.hpp"

namespace finverse::fem::validation {

struct FlagMesh {
  int nx = 20;           // Q9 elements along the flag
  int ny = 2;            // through the thickness
  double grading = 3.0;  // last / first element length along the flag (finer at the clamp)
};

struct TurekHronFlagSpec {
  // Geometry [m] (turek_hron.json /geometry): cylinder centre and radius, flag thickness, and x
  // of the tip centre, point A = (x_tip, yc) (the flag's length is x_tip - xc - radius).
  double xc = 0.2, yc = 0.2, radius = 0.05, thickness = 0.02, x_tip = 0.6;
  double youngs_modulus = 1.4e6;  // [Pa]
  double poisson_ratio = 0.4;
  double density = 1000;          // [kg/m^3]
  double gravity = 0;             // downward acceleration [m/s^2] (CSM: 2; FSI: 0)
  // Gravity as nodal loads scaled by the load factor (statics with load stepping) instead of the
  // model's gravity (applied at full value at every time: dynamics).
  bool gravity_as_load = false;
  FlagMesh mesh;
  // Clamp cut straight at the arc's corner abscissa instead of along the arc (a 1 mm sliver).
  bool straight_clamp = false;

  // x of the clamped left end at height y.
  double clamp_x(double y) const;
};

// Geometry from /geometry and E, rho_s (and g if present, else 0) from /cases/<case_name> of
// turek_hron.json (e.g. "CSM1", "FSI3"). Throws InvalidInput naming the file and key.
TurekHronFlagSpec turek_hron_flag_spec(const std::filesystem::path& reference,
                                       const std::string& case_name);

struct TurekHronFlag {
  Model model;
  std::vector<int> wet_nodes;    // counter-clockwise (see above)
  std::vector<int> clamp_nodes;  // the clamped left edge, bottom to top
  int point_a = 0;               // tip centre
  double mass = 0;               // per metre depth
};

// Throws InvalidInput for a bad mesh or material, or a thickness not below the diameter.
TurekHronFlag build_turek_hron_flag(const TurekHronFlagSpec& spec);

}  // namespace finverse::fem::validation
