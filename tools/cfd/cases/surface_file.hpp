// A body's closed surface from a file, as the 3-D immersed boundary takes it (TriangulatedSurface):
// the user's own geometry as STL (ASCII or binary), Wavefront OBJ or VTK XML PolyData (.vtp), read
// through VTK (coincident vertices merged, polygons split into triangles), or the closed thin body
// of a fin-mesh mesh.h5 at rest (its /ibm group). The surface is oriented outward (its signed
// volume made positive); a surface that is not closed is refused later, by the solver's checks.
#pragma once

#include <array>
#include <filesystem>

#include "cfd/immersed/triangulated_surface.hpp"

namespace finverse::cfd::cases {

// By the file's extension: .stl, .obj, .vtp or .h5 (mesh.h5). Throws finverse::Error naming the file.
TriangulatedSurface read_surface_file(const std::filesystem::path& file);

// x -> scale x + translate, for a surface given in other units or another frame.
void transform(TriangulatedSurface& s, double scale, const std::array<double, 3>& translate);

// The enclosed volume (positive when the triangles are counter-clockwise seen from outside).
double signed_volume(const TriangulatedSurface& s);

}  // namespace finverse::cfd::cases
