// The hybrid plate of the seed paper's section 3.4 (data/cases/hybrid_plate.json): a square
// plate of corotational shell triangles in the x-z plane with three corotational beams of
// different moduli lying on chordwise grid lines and sharing the plate's nodes (no eccentricity:
// beam axis on the plate mid-surface). The leading edge x = 0 has its rotations and x, z
// translations fixed; its y translation is either held (static case) or prescribed (heave).
// The same model is built by tools/scripts/calculix_hybrid_plate.py with S8R shells and B32R
// beams for the CalculiX reference.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

#include "fem/model.hpp"

namespace finverse::fem::validation {

struct HybridPlateBeam {
  std::string name;
  double z = 0;
  Material material;
  double width = 0;      // in the plate plane (z): the section's local y axis
  double thickness = 0;  // along the plate normal (y)
};

struct HybridPlateCase {
  double chord = 0, span = 0, thickness = 0;
  Material plate;
  std::vector<HybridPlateBeam> beams;
  double pressure = 0;  // static: dead load per unit area along -y
  int load_steps = 10;
  double heave_amplitude = 0, frequency = 0, periods = 0, time_step = 0;
  // y_LE(t) = A (1 - cos 2 pi f t): starts from rest.
  double heave(double t) const;
};

// Reads data/cases/hybrid_plate.json; throws InvalidInput naming the file and key.
HybridPlateCase read_hybrid_plate_case(const std::filesystem::path& path);

struct HybridPlateModel {
  Model model;
  std::vector<int> leading_edge;  // model nodes at x = 0
  std::vector<int> tips;          // trailing-edge node of each beam, in case order
  std::vector<std::vector<int>> beam_nodes;  // model nodes along each beam, x increasing
  int shell_elements = 0, beam_elements = 0;
};

// pressure: held leading edge, dead pressure (static case); heave: prescribed y_LE(t) (dynamic
// case); none: held leading edge and no load (the caller adds its own).
enum class HybridPlateLoad { pressure, heave, none };

// nx x nz grid cells (two triangles each); nz must put every beam on a grid line. Throws
// InvalidInput otherwise.
HybridPlateModel build_hybrid_plate(const HybridPlateCase& c, int nx, int nz, HybridPlateLoad load);

}  // namespace finverse::fem::validation
