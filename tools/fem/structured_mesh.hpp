// Structured mesh of nine-node quadrilaterals (Q9, plane_strain_solid.hpp) on a strip
// x_begin(y) <= x <= x_end, y0 <= y <= y1, and how it enters a Model.
//
// The strip is mapped from the unit square: x = x_begin(y) + s (x_end - x_begin(y)), y = y0 +
// t (y1 - y0). x_begin(y) may be curved (the Turek-Hron flag is clamped on the cylinder arc);
// the Q9 geometry then interpolates the curve quadratically per element. Along x the element
// lengths grow geometrically (grading = last / first length), so elements can be concentrated at
// a clamped end, where the stress has its corner singularity. Mid-side nodes sit at the parameter
// midpoint of their element, which keeps the straight part of the mesh affine (no distortion
// error from mid-side placement).
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "fem/material.hpp"
#include "fem/model.hpp"
#include "fem/nodal_state.hpp"

namespace finverse::fem {

struct StripSpec {
  std::function<double(double)> x_begin;  // left edge x(y); empty: the constant x0
  double x0 = 0;
  double x_end = 1;
  double y0 = 0, y1 = 1;
  int nx = 1, ny = 1;    // elements along x and y
  double grading_x = 1;  // length of the last element along x / length of the first
};

struct StructuredMeshQ9 {
  int nx = 0, ny = 0;
  std::vector<Vec3> nodes;                   // z = 0; (2 nx + 1) (2 ny + 1) of them
  std::vector<std::array<int, 9>> elements;  // Q9 node order (plane_strain_solid.hpp)
  // Node on grid line i = 0..2 nx (along x) and j = 0..2 ny (along y).
  int node(int i, int j) const { return j * (2 * nx + 1) + i; }
};

// Throws InvalidInput for nx, ny < 1, grading <= 0, or an edge x_begin(y) >= x_end.
StructuredMeshQ9 mesh_strip_q9(const StripSpec& spec);

// Adds the mesh's nodes and one PlaneStrainSolid per element (all with `material`) to the model;
// returns the model's node id of every mesh node (mesh index -> model node).
std::vector<int> add_plane_strain_mesh(Model& model, const StructuredMeshQ9& mesh,
                                       const Material& material, double thickness = 1.0);

}  // namespace finverse::fem
