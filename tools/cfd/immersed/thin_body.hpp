// The closed thin body around a fin's mid-surface (DESIGN.md section 5.1: "a fin is thin; it is
// represented as a closed thin body, the mid-surface offset by a thickness of a few cells"), as
// the 3-D immersed boundary sees it, rebuilt from the deforming mid-surface at every instant.
//
// Topology (fixed in time; the construction of tools/mesh/ibm_surface.cpp, so mesh.h5 /ibm is
// reproduced): every mid-surface node has a copy on either side (offset_sign +1 and -1) and every
// outline node a third copy on the mid-surface itself (offset_sign 0); the two faces are the
// mid-surface triangles on each side and the rim is a wall of four triangles per outline edge.
//
// Placement: surface vertex v of node s = source_node[v] sits at
//     x_v = X_s + offset_sign_v * normal_sign * (thickness / 2) * n_s,
// with n_s the area-weighted unit normal of the deformed mid-surface at node s (right-hand
// normal of the mid-surface triangles) and normal_sign = +1 when offset_sign +1 lies on the side
// n points to (fin-mesh: -1, its +1 side is +y while its planform triangles' normal is -y). The
// vertex velocity and acceleration are the exact first and second time derivatives of this map
// for given node velocities and accelerations (n = N/|N|, N = sum of (b-a) x (c-a), differentiated
// analytically), so the immersed boundary gets the kinematics consistent with the positions.
#pragma once

#include <array>
#include <string>
#include <vector>

#include "cfd/immersed/triangulated_surface.hpp"

namespace finverse::cfd {

using Vec3 = std::array<double, 3>;

struct ThinBody {
  std::vector<std::array<int, 3>> triangles;  // closed surface, outward normals
  std::vector<int> source_node;               // mid-surface node of each surface vertex
  std::vector<int> offset_sign;               // +1, -1, or 0 on the rim
  double thickness = 0;                       // [m]
  int normal_sign = -1;                       // see the header comment
  int node_count = 0;                         // mid-surface nodes
};

// The closed body around a mid-surface given by its triangles (consistently oriented, every edge
// in one or two triangles), built exactly as fin-mesh builds mesh.h5 /ibm: vertices [0, n) on the
// +1 side, [n, 2n) on the -1 side, then one rim vertex per outline node in node order; triangles
// per mid-surface triangle (the -1 face as it stands, the +1 face reversed), then the rim wall
// per outline edge in lexicographic order of its directed node pair. normal_sign = -1.
// `what` names the data in error messages.
ThinBody build_thin_body(const std::vector<std::array<int, 3>>& mid_triangles, int node_count, double thickness,
                         const std::string& what = "mid-surface");

// Throws finverse::Error (message starts with `what`) unless every edge of the triangles is shared
// by exactly two triangles that traverse it in opposite directions (closed, consistently oriented)
// and every index lies in [0, point_count).
void check_watertight(const std::vector<std::array<int, 3>>& triangles, int point_count, const std::string& what);

// Area-weighted unit vertex normals (right-hand normals of the triangles) and their first and
// second time derivatives for node velocities v and accelerations a (either may be empty: zero).
struct VertexNormals {
  std::vector<Vec3> n, dn, ddn;
};
VertexNormals vertex_normals(const std::vector<Vec3>& x, const std::vector<Vec3>& v, const std::vector<Vec3>& a,
                             const std::vector<std::array<int, 3>>& triangles);

// The body's surface state for mid-surface node positions x, velocities v and accelerations a
// (v, a may be empty: zero; the state then has empty velocity/acceleration only if both are).
SurfaceState place_thin_body(const ThinBody& body, const std::vector<Vec3>& x, const std::vector<Vec3>& v,
                             const std::vector<Vec3>& a, const std::vector<std::array<int, 3>>& mid_triangles);

}  // namespace finverse::cfd
