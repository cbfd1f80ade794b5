// Closed triangulated test bodies for the 3-D immersed boundary (triangulated_surface.hpp): a
// sphere as a subdivided icosahedron and an axis-aligned box, both with counter-clockwise
// (outward) triangles.
#pragma once

#include <array>

#include "cfd/triangulated_surface.hpp"

namespace finverse::cfd {

// Icosahedron with every triangle split into four `subdivisions` times (20 * 4^s triangles), the
// vertices projected onto the sphere. With volume_preserving the radius is scaled so that the
// polyhedron encloses the sphere's volume (the inscribed polyhedron is smaller by O(h^2)).
TriangulatedSurface icosphere(const std::array<double, 3>& centre, double radius, int subdivisions,
                              bool volume_preserving = false);

// The box [lo, hi] as 12 triangles.
TriangulatedSurface box_surface(const std::array<double, 3>& lo, const std::array<double, 3>& hi);

}  // namespace finverse::cfd
