// Builds the structural model of a fin from the stage files (DESIGN.md section 4): mesh.h5
// (shells on the triangles, one tapered corotational beam per ray edge, root node set),
// the materials file (material_spec.hpp), loads.h5 (nodal forces interpolated in time) and
// motion.h5 (prescribed root motion). Region ids: 0 = membrane, then one region per ray id, then
// one per further shell region.
#pragma once

#include <map>

#include "core/stage_files.hpp"
#include "fem/io/material_spec.hpp"
#include "fem/model.hpp"
#include "fem/root_motion.hpp"

namespace finverse::fem::io {

struct FinModel {
  Model model;
  int membrane_region = 0;
  std::map<int, int> ray_region;    // ray id -> model region
  std::map<int, int> shell_region;  // shell region id (> 0) -> model region
  std::vector<int> shell_element;   // model element of each /triangles row
  std::vector<int> beam_element;    // model element of each /beams/elements row
};

// source names the mesh file in messages. Root nodes are clamped; apply_root_motion replaces that
// with the tracked motion. Throws InvalidInput naming the dataset for inconsistent mesh data
// (indices out of range, degenerate elements, a shell region without a material, no root nodes).
FinModel build_fin_model(const stage::Mesh& mesh, const MaterialSpec& materials,
                         const std::string& source = "mesh.h5");

// Nodal forces of loads.h5 as the model's load history (ramping up over `ramp` s before the
// first sample). The node count must match the mesh. Returns the largest force component on a
// prescribed (root) DOF: such forces go into the support, not the structure (0 when none).
double apply_loads(Model& model, const stage::Loads& loads, double ramp, const std::string& source);

// Root-node positions of motion.h5 as prescribed root displacements and rotations; with
// RootRotation::fit the rotation is fitted to the root nodes and the nodes of the elements at the
// root (root_motion.hpp); with RootRotation::per_ray each ray's root node turns with that ray's
// tangent at the root and the membrane root nodes between rays interpolate.
void apply_root_motion(Model& model, const stage::Mesh& mesh, const stage::Motion& motion,
                       RootRotation rotation, double ramp, const std::string& source);

}  // namespace finverse::fem::io
