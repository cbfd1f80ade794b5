// Geometry queries on a closed triangulated surface for the 3-D sharp-interface immersed boundary
// (Mittal et al. 2008, J. Comput. Phys. 227:4825, section 2.2): the closest surface point of a
// cell centre with the outward normal and the signed distance (the boundary intercept of a ghost
// cell's probe), and inside/outside of a point.
//
// Closest point: a bounding-volume hierarchy of axis-aligned boxes over the triangles (median
// split along the longest axis of the centroids' box, four triangles per leaf), searched
// depth-first with the nearer child first and pruned by the box distance. Written here rather
// than taken from CGAL's AABB tree: finverse_cfd depends on Eigen and OpenMP only, the query is
// short, and a deforming body rebuilds its tree every time step (O(n log n), no allocation per
// query), which the hand-written tree does in place.
//
// Inside/outside: the sign of (x - c) . n_pseudo, where c is the closest surface point and
// n_pseudo the angle-weighted pseudo-normal of the feature c lies on (the triangle's normal in its
// interior, the sum of the two triangles' normals on an edge, the angle-weighted sum around a
// vertex; Baerentzen & Aanaes 2005, IEEE TVCG 11:243). For a closed, consistently oriented
// surface this sign is exact for every point off the surface, with no ray and no tie-breaking; a
// point on the surface (distance 0, e.g. a cell centre exactly on a face) counts as outside.
//
// Watertightness is checked on construction: every edge is shared by exactly two triangles that
// traverse it in opposite directions (consistent orientation), no triangle is degenerate, and the
// enclosed volume is positive (outward normals), or negative for a surface that encloses the fluid
// (TriangulatedSurface::encloses_fluid, normals into the fluid, the solid unbounded: then every
// point far from the surface is inside); otherwise a one-line finverse::Error.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "cfd/immersed/triangulated_surface.hpp"
#include "cfd/immersed/vec3.hpp"

namespace finverse::cfd {

// The point of the surface closest to a query point.
struct SurfaceHit {
  Vec3 point{};        // closest surface point c
  Vec3 normal{};       // outward unit normal at c (the direction of x - c for a point off the surface)
  double distance = 0; // signed: > 0 outside, < 0 inside
  int triangle = -1;   // triangle holding c
  Vec3 barycentric{};  // of c in that triangle (weights of its vertices 0, 1, 2)
};

class SurfaceGeometry {
 public:
  SurfaceGeometry() = default;
  // Validates the surface (what names it in error messages) and builds the hierarchy.
  explicit SurfaceGeometry(TriangulatedSurface surface, const std::string& what = "triangulated surface");

  // The same connectivity at new vertex positions (a moving or deforming body): normals and the
  // hierarchy are rebuilt, the topology (edge adjacency) is reused; the orientation is re-checked.
  void move_to(const std::vector<Vec3>& points);

  SurfaceHit closest(const Vec3& x) const;
  bool inside(const Vec3& x) const { return closest(x).distance < 0; }

  const TriangulatedSurface& surface() const { return s_; }
  int triangles() const { return static_cast<int>(s_.triangles.size()); }
  const Vec3& triangle_normal(int t) const { return face_normal_[static_cast<std::size_t>(t)]; }
  double triangle_area(int t) const { return face_area_[static_cast<std::size_t>(t)]; }
  // The triangle across edge e (from vertex e to vertex e + 1 mod 3) of triangle t.
  int neighbour(int t, int e) const {
    return edge_triangle_[static_cast<std::size_t>(t)][static_cast<std::size_t>(e)];
  }
  Vec3 lower() const { return nodes_.empty() ? Vec3{} : nodes_[0].lo; }
  Vec3 upper() const { return nodes_.empty() ? Vec3{} : nodes_[0].hi; }
  double volume() const;  // enclosed volume (divergence theorem); negative when it encloses the fluid
  bool encloses_fluid() const { return s_.encloses_fluid; }
  double area() const;

  // Linear interpolation of per-vertex data (velocity, acceleration) at a hit; empty data: zero.
  Vec3 interpolate(const std::vector<Vec3>& vertex_data, const SurfaceHit& hit) const;

 private:
  struct Node {
    Vec3 lo{}, hi{};
    int left = -1, right = -1;  // children (internal node) or -1
    int first = 0, count = 0;   // range in order_ (leaf)
  };
  void compute_normals(const std::string& what);
  void build();
  int build_node(int first, int count, const std::vector<Vec3>& centroid);

  TriangulatedSurface s_;
  std::vector<Vec3> face_normal_, vertex_normal_;
  std::vector<double> face_area_;
  std::vector<std::array<int, 3>> edge_triangle_;  // per triangle and edge (v_e, v_{e+1}): the neighbour
  std::vector<Node> nodes_;
  std::vector<int> order_;
};

}  // namespace finverse::cfd
