// The closed thin body that the immersed-boundary CFD sees (DESIGN.md section 5.1: "a fin is
// thin; it is represented as a closed thin body, the mid-surface offset by a thickness of a few
// cells"). Each mid-surface node gets a copy on either side (offset +-thickness/2 along the
// mid-surface normal); the rim is closed by a wall through a third copy of every outline node on
// the mid-surface, so the body is watertight for any triangulation of the planform (sharing the
// outline nodes between both sides instead would make an edge between two outline nodes
// non-manifold). The CFD moves the body with the mesh by re-offsetting from source_node.
#pragma once

#include <array>
#include <vector>

#include "mesh/planform_mesher.hpp"

namespace finverse::mesh {

struct IbmSurface {
  std::vector<std::array<double, 3>> points;  // metres
  std::vector<std::array<int, 3>> triangles;  // outward normals (right-hand rule)
  std::vector<int> source_node;               // mid-surface node each vertex is offset from
  std::vector<int> offset_sign;               // +1 (+y side at rest), -1, or 0 on the rim wall
  double thickness = 0;
};

// The planform lies in y = 0 at rest, so the mid-surface normal is +y everywhere.
IbmSurface build_ibm_surface(const PlanformMesh& m, double thickness);

struct SurfaceCheck {
  bool closed = false;             // every edge has exactly two faces (CGAL::is_closed)
  bool self_intersecting = true;   // CGAL::Polygon_mesh_processing::does_self_intersect
  bool outward = false;            // CGAL::Polygon_mesh_processing::is_outward_oriented
  double volume = 0;               // enclosed volume, m^3
  double area = 0;                 // surface area, m^2
};

// Checks a triangle surface with CGAL Polygon_mesh_processing.
SurfaceCheck check_surface(const std::vector<std::array<double, 3>>& points,
                           const std::vector<std::array<int, 3>>& triangles);

}  // namespace finverse::mesh
