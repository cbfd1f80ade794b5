// The materials file of a file-driven structural run (fin-fem run --materials materials.json):
// region materials of the fin (membrane, every ray separately), a softer distal part of the rays,
// periodic modulation E(t) = E0 (1 + a sin(2 pi f t + phi)) and Rayleigh damping -- exactly the
// quantities the inverse fit and the effect tracing vary (issue 3). SI units throughout.
//
//   {
//     "membrane": {"E": 2.5e6, "nu": 0.45, "density": 1050},
//     "rays":     {"E": 1.0e9, "nu": 0.3,  "density": 1100},   // default of every ray
//     "ray":      {"1": {"E": 2.0e9}, "3": {"E": 5.0e8}},     // per ray id (mesh.h5 beams/ray)
//     "shell_region": {"2": {"E": 1e7, "nu": 0.4, "density": 1000}},  // shell regions other than 0
//     "distal":   {"s_from": 0.7, "E_factor": 0.5},  // ray elements with mid arc length >= s_from
//     "modulation": [{"target": "rays", "amplitude": 0.2, "frequency": 5.0, "phase": 0.0}],
//     "rayleigh": {"mass": 0.0, "stiffness": 1e-4}   // C = mass M + stiffness K (K on the corotated rate)
//   }
// A ray entry inherits the fields it omits from "rays"; a top-level "description" string is
// allowed for the file's provenance and otherwise ignored. Modulation targets: "membrane", "rays",
// "ray <id>", "shell_region <id>". Unknown keys are rejected (a typo must not silently fall back
// to a default).
#pragma once

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "fem/material.hpp"
#include "fem/stiffness_field.hpp"

namespace finverse::fem::io {

struct ModulationSpec {
  std::string target;
  ModulusModulation modulation;
};

struct MaterialSpec {
  Material membrane;
  Material rays;
  std::map<int, Material> ray;           // by ray id
  std::map<int, Material> shell_region;  // by shell region id (> 0)
  double distal_s_from = 1.0;            // no distal softening by default
  double distal_factor = 1.0;
  std::vector<ModulationSpec> modulations;
  double rayleigh_mass = 0, rayleigh_stiffness = 0;
  std::string source = "materials";  // the file it came from, for messages

  Material ray_material(int id) const;  // "ray" entry or the "rays" default, named "ray<id>"
};

// Throws InvalidInput naming `source` and the key for anything missing, unknown or outside the
// physical range (E <= 0, nu outside (-1, 0.5), density <= 0, |a| >= 1, negative damping).
MaterialSpec parse_material_spec(const nlohmann::json& j, const std::string& source);
MaterialSpec read_material_spec(const std::filesystem::path& path);

}  // namespace finverse::fem::io
