// Closed thin immersed-boundary body from the planform mesh (DESIGN.md section 5.1) and its
// watertightness / self-intersection checks with CGAL Polygon_mesh_processing.
#include "mesh/ibm_surface.hpp"

#include <cmath>
#include <map>

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
  IbmSurface s;
  s.thickness = thickness;
  const double h = 0.5 * thickness;
  const int n = static_cast<int>(m.points.size());
  std::vector<int> top(n), bottom(n), rim(n, -1);
  auto add = [&](int node, double y, int sign) {
    s.points.push_back({m.points[node][0], y, m.points[node][1]});
    s.source_node.push_back(node);
    s.offset_sign.push_back(sign);
    return static_cast<int>(s.points.size()) - 1;
  };
  for (int i = 0; i < n; ++i) top[i] = add(i, h, +1);
  for (int i = 0; i < n; ++i) bottom[i] = add(i, -h, -1);
  for (int i = 0; i < n; ++i)
    if (m.on_boundary[i]) rim[i] = add(i, 0.0, 0);

  // A planform triangle counter-clockwise in (x, z) has its right-hand normal along -y: it is the
  // bottom face as it stands and the top face reversed.
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : m.triangles) {
    s.triangles.push_back({bottom[t[0]], bottom[t[1]], bottom[t[2]]});
    s.triangles.push_back({top[t[0]], top[t[2]], top[t[1]]});
    for (int k = 0; k < 3; ++k) ++directed[{t[k], t[(k + 1) % 3]}];
  }
  auto oriented = [&](std::array<int, 3> tri, double ox, double oz) {
    const auto& a = s.points[tri[0]];
    const auto& b = s.points[tri[1]];
    const auto& c = s.points[tri[2]];
    const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
    const double vx = c[0] - a[0], vy = c[1] - a[1], vz = c[2] - a[2];
    const double nx = uy * vz - uz * vy, nz = ux * vy - uy * vx;
    if (nx * ox + nz * oz < 0) std::swap(tri[1], tri[2]);
    return tri;
  };
  // Rim wall: an outline edge a->b of a counter-clockwise triangle has the interior on its left,
  // so the outward in-plane direction is to its right, (dz, -dx) in (x, z).
  for (const auto& [e, count] : directed) {
    const auto [a, b] = e;
    if (directed.count({b, a})) continue;  // interior edge
    const double ox = m.points[b][1] - m.points[a][1], oz = -(m.points[b][0] - m.points[a][0]);
    s.triangles.push_back(oriented({top[a], top[b], rim[b]}, ox, oz));
    s.triangles.push_back(oriented({top[a], rim[b], rim[a]}, ox, oz));
    s.triangles.push_back(oriented({rim[a], rim[b], bottom[b]}, ox, oz));
    s.triangles.push_back(oriented({rim[a], bottom[b], bottom[a]}, ox, oz));
  }
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
