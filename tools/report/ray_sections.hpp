// The second moment of area of every fin ray at its root, I = w t^3 / 12 of the most proximal beam
// section in mesh.h5 (bending about the ray's width axis, the flapping direction), so that the
// fitted modulus E becomes the flexural rigidity EI of the seed paper's Fig. 11 (its panels: E,
// I, EI per ray; the paper's trout: proximal EI about 3.9e-6 N m^2).
#pragma once

#include <map>

#include "core/stage_files.hpp"

namespace finverse::report {

// Ray id (as in mesh.h5 beams/ray) -> I [m^4]. Throws finverse::Error for a mesh without beams.
std::map<int, double> root_second_moments(const stage::Mesh& mesh);

}  // namespace finverse::report
