// Closed thin immersed-boundary body from the planform mesh (DESIGN.md section 5.1; the
// construction is core/thin_body.hpp's) and its checks with CGAL Polygon_mesh_processing.
#include "mesh/ibm_surface.hpp"

#include <cmath>
#include <string>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Polygon_mesh_processing/measure.h>
#include <CGAL/Polygon_mesh_processing/orientation.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>
#include <CGAL/Surface_mesh.h>

#include "core/error.hpp"

namespace finverse::mesh {

IbmSurface build_ibm_surface(const PlanformMesh& m, double thickness) {
  if (!(std::isfinite(thickness) && thickness > 0))
    throw Error("--ibm-thickness: " + std::to_string(thickness) + " m, expected > 0");
  const int n = static_cast<int>(m.points.size());
  IbmSurface s;
  s.body = build_thin_body(m.triangles, n, thickness, "planform mesh");
  // At rest the mid-surface is the planform in y = 0; its right-hand normal is -y at every node.
  std::vector<std::array<double, 3>> rest(m.points.size()), normal(m.points.size(), {0.0, -1.0, 0.0});
  for (std::size_t i = 0; i < m.points.size(); ++i) rest[i] = {m.points[i][0], 0.0, m.points[i][1]};
  s.points = thin_body_points(s.body, rest, normal);
  return s;
}

SurfaceCheck check_surface(const std::vector<std::array<double, 3>>& points,
                           const std::vector<std::array<int, 3>>& triangles) {
  namespace PMP = CGAL::Polygon_mesh_processing;
  using K = CGAL::Exact_predicates_inexact_constructions_kernel;
  using SM = CGAL::Surface_mesh<K::Point_3>;
  std::vector<K::Point_3> pts;
  pts.reserve(points.size());
  for (const auto& p : points) pts.emplace_back(p[0], p[1], p[2]);
  std::vector<std::vector<std::size_t>> polys;
  polys.reserve(triangles.size());
  for (const auto& t : triangles)
    polys.push_back({static_cast<std::size_t>(t[0]), static_cast<std::size_t>(t[1]), static_cast<std::size_t>(t[2])});
  SurfaceCheck c;
  if (!PMP::is_polygon_soup_a_polygon_mesh(polys)) return c;  // non-manifold or inconsistently oriented
  SM sm;
  PMP::polygon_soup_to_polygon_mesh(pts, polys, sm);
  c.closed = CGAL::is_closed(sm);
  c.self_intersecting = PMP::does_self_intersect(sm);
  c.area = PMP::area(sm);
  if (c.closed) {
    c.outward = PMP::is_outward_oriented(sm);
    c.volume = PMP::volume(sm);
  }
  return c;
}

}  // namespace finverse::mesh
