// Closed triangulated test bodies for the 3-D immersed boundary (triangulated_surface.hpp): a
// sphere as a subdivided icosahedron, an axis-aligned box and a circular cylinder, all
// with counter-clockwise (outward) triangles.
#pragma once

#include <array>

#include "cfd/immersed/triangulated_surface.hpp"

namespace finverse::cfd {

// Icosahedron with every triangle split into four `subdivisions` times (20 * 4^s triangles), the
// vertices projected onto the sphere. With volume_preserving the radius is scaled so that the
// polyhedron encloses the sphere's volume (the inscribed polyhedron is smaller by O(h^2)).
TriangulatedSurface icosphere(const std::array<double, 3>& centre, double radius, int subdivisions,
                              bool volume_preserving = false);

// The box [lo, hi] as 12 triangles.
TriangulatedSurface box_surface(const std::array<double, 3>& lo, const std::array<double, 3>& hi);

// Closed circular cylinder with its axis along z through (xc, yc), from z0 to z1: `segments`
// vertices on each of layers + 1 rings (the first vertex of a ring at angle 0, i.e. at
// (xc + radius, yc)), the lateral surface in `layers` bands of two triangles per segment, and each
// end cap a fan around its centre.
TriangulatedSurface cylinder_surface(double xc, double yc, double radius, double z0, double z1, int segments,
                                     int layers);

// The closed circular cylinder from point `from` to point `to` on its axis (a pipe's wall, with
// fluid: inside): `segments` vertices per ring, rings about one segment's length apart so that the
// lateral triangles are about as long as they are wide.
TriangulatedSurface cylinder_between(const std::array<double, 3>& from, const std::array<double, 3>& to, double radius,
                                     int segments);

}  // namespace finverse::cfd
