// Triangle meshes for the shell validation cases (Sze, Liu & Lo 2004 benchmarks, elastica strip)
// and how they enter a Model as corotational shell triangles.
#pragma once

#include <array>
#include <vector>

#include "fem/material.hpp"
#include "fem/model.hpp"

namespace finverse::fem::validation {

struct TriangleMesh {
  std::vector<Vec3> nodes;
  std::vector<std::array<int, 3>> triangles;  // counter-clockwise seen from the intended normal
  int nx = 0, ny = 0;
  int node(int i, int j) const { return j * (nx + 1) + i; }  // structured grid index
};

// Rectangle [0, length] x [0, width] in the plane z = 0 (normal +z): nx x ny cells, each split
// into two triangles with alternating diagonals, so that the mesh has no preferred direction.
TriangleMesh rectangle_mesh(double length, double width, int nx, int ny);

// Quarter of a hemisphere of radius R (pole on +z) with a hole of half-angle hole_deg around the
// pole, x >= 0, y >= 0: grid i = 0..n_meridian from the equator (i = 0) to the hole edge,
// j = 0..n_circumference from the xz plane (j = 0) to the yz plane. The triangle normals point
// inwards; a flat shell's response does not depend on that sign.
TriangleMesh quarter_hemisphere_mesh(double radius, double hole_deg, int n_meridian,
                                     int n_circumference);

// Adds the nodes and one CorotationalShell per triangle; returns the model node of every mesh
// node.
std::vector<int> add_shell_mesh(Model& model, const TriangleMesh& mesh, const Material& material,
                                double thickness);

}  // namespace finverse::fem::validation
