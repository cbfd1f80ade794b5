// The closed thin body that the immersed-boundary CFD sees (DESIGN.md section 5.1), at rest, for
// mesh.h5 /ibm: core/thin_body.hpp's construction around the planform mesh (the same one fin-cfd
// moves with the mid-surface), and its watertightness / self-intersection checks with CGAL.
#pragma once

#include <array>
#include <vector>

#include "core/thin_body.hpp"
#include "mesh/planform_mesher.hpp"

namespace finverse::mesh {

struct IbmSurface {
  ThinBody body;                              // triangles, source nodes, offset signs, thickness
  std::vector<std::array<double, 3>> points;  // metres; offset_sign +1 on the +y side
};

// The planform lies in y = 0 at rest and its triangles are counter-clockwise in (x, z), so the
// mid-surface normal is -y everywhere and the +1 side (normal_sign -1) is +y.
IbmSurface build_ibm_surface(const PlanformMesh& m, double thickness);

struct SurfaceCheck {
  bool closed = false;            // every edge has exactly two faces (CGAL::is_closed)
  bool self_intersecting = true;  // CGAL::Polygon_mesh_processing::does_self_intersect
  bool outward = false;           // CGAL::Polygon_mesh_processing::is_outward_oriented
  double volume = 0;              // enclosed volume, m^3
  double area = 0;                // surface area, m^2
};

// Checks a triangle surface with CGAL Polygon_mesh_processing.
SurfaceCheck check_surface(const std::vector<std::array<double, 3>>& points,
                           const std::vector<std::array<int, 3>>& triangles);

}  // namespace finverse::mesh
