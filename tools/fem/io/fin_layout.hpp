// The fin's layout for the candidate effects (fem/effects/structural_effect.hpp) from mesh.h5:
// ray elements with their arc lengths, ray groups (by the rank of each ray's root along z, as the
// root drive's eta), root nodes and the fin's axes; and the two steps an app takes to run a fin
// with effects: rest shapes into the mesh before the model is built, the rest after.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "core/stage_files.hpp"
#include "fem/effects/structural_effect.hpp"
#include "fem/io/fin_model.hpp"

namespace finverse::fem::io {

using Effects = std::vector<std::unique_ptr<StructuralEffect>>;

// Element indices follow build_fin_model (shells in /triangles order, then the beams); the
// timing (beat_frequency, start_time, ramp) is left for the caller. Throws InvalidInput naming
// the mesh for a mesh without rays or root nodes.
FinLayout make_fin_layout(const stage::Mesh& mesh, const std::string& source = "mesh.h5");

// Moves mesh.points (and the IBM points with their source nodes) by the rest-shape effects.
void reshape_mesh(stage::Mesh& mesh, const Effects& effects, const FinLayout& layout);

// Applies every effect to a model built from the mesh (after its loads and root motion); throws
// InvalidInput when the model's elements do not match the layout.
void apply_effects(Model& model, const Effects& effects, const FinLayout& layout);

}  // namespace finverse::fem::io
