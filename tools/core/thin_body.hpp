// The closed thin body around a fin's mid-surface (DESIGN.md section 5.1: "a fin is thin; it is
// represented as a closed thin body, the mid-surface offset by a thickness of a few cells"): which
// vertices and triangles it has, how its rim is closed, where a vertex sits, and the check that a
// triangle surface is watertight. Written once for fin-mesh (mesh.h5 /ibm, at rest) and fin-cfd
// (the body around the deformed mid-surface at every instant, cfd/immersed/thin_body.hpp).
// Header-only: finverse_cfd uses tools/core's headers but links none of its compiled code.
//
// Topology: every mid-surface node has a copy on either side (offset_sign +1 and -1) and every
// outline node a third copy on the mid-surface itself (offset_sign 0). The two faces are the
// mid-surface triangles on each side; the rim is a wall of four triangles per outline edge through
// the third copies, so the body is closed for any triangulation (sharing the outline nodes between
// both faces instead would make an edge between two outline nodes non-manifold).
//
// Placement: vertex v of node s = source_node[v] sits at
//     x_v = X_s + offset_sign_v * normal_sign * (thickness / 2) * n_s,
// with n_s the unit right-hand normal of the mid-surface triangles at node s; normal_sign = +1
// when the +1 side is the side n points to. build_thin_body gives -1: fin-mesh's planform
// triangles are counter-clockwise in (x, z), so n = -y, and its +1 side is +y.
#pragma once

#include <array>
#include <cmath>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "core/error.hpp"

namespace finverse {

struct ThinBody {
  std::vector<std::array<int, 3>> triangles;  // closed surface, outward normals (right-hand rule)
  std::vector<int> source_node;               // mid-surface node of each surface vertex
  std::vector<int> offset_sign;               // +1, -1, or 0 on the rim
  double thickness = 0;                       // [m]
  int normal_sign = -1;                       // see the header comment
  int node_count = 0;                         // mid-surface nodes
};

namespace thin_body_detail {

inline void check_indices(const std::vector<std::array<int, 3>>& triangles, int count, const std::string& what) {
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      if (triangles[t][k] < 0 || triangles[t][k] >= count)
        throw Error(what + ": triangle " + std::to_string(t) + " has vertex index " + std::to_string(triangles[t][k]) +
                    ", expected 0.." + std::to_string(count - 1));
}

// How often each directed edge a->b is traversed; an ordered map, so the rim wall comes out in
// lexicographic order of the directed node pair (the order of mesh.h5 /ibm/triangles).
using DirectedEdges = std::map<std::pair<int, int>, int>;

}  // namespace thin_body_detail

// The closed body around a mid-surface given by its triangles (consistently oriented, every edge in
// one or two triangles): vertices [0, n) on the +1 side, [n, 2n) on the -1 side, then one rim
// vertex per outline node in node order; triangles per mid-surface triangle (the -1 face as it
// stands, the +1 face reversed), then the rim wall per outline edge. `what` names the data in
// error messages.
inline ThinBody build_thin_body(const std::vector<std::array<int, 3>>& mid, int n, double thickness,
                                const std::string& what = "mid-surface") {
  if (!(std::isfinite(thickness) && thickness > 0))
    throw Error(what + ": thin-body thickness " + std::to_string(thickness) + " m, expected > 0");
  thin_body_detail::check_indices(mid, n, what);
  thin_body_detail::DirectedEdges directed;
  for (const auto& t : mid)
    for (int k = 0; k < 3; ++k)
      if (++directed[{t[k], t[(k + 1) % 3]}] > 1)
        throw Error(what + ": edge " + std::to_string(t[k]) + "->" + std::to_string(t[(k + 1) % 3]) +
                    " is traversed twice in one direction: the mid-surface is not a consistently oriented manifold");
  // An outline edge is traversed in one direction only.
  std::vector<char> outline(static_cast<std::size_t>(n), 0);
  for (const auto& [e, c] : directed)
    if (!directed.count({e.second, e.first})) outline[e.first] = outline[e.second] = 1;

  ThinBody b;
  b.thickness = thickness;
  b.normal_sign = -1;
  b.node_count = n;
  std::vector<int> top(n), bottom(n), rim(n, -1);
  auto add = [&](int node, int sign) {
    b.source_node.push_back(node);
    b.offset_sign.push_back(sign);
    return static_cast<int>(b.source_node.size()) - 1;
  };
  for (int i = 0; i < n; ++i) top[i] = add(i, +1);
  for (int i = 0; i < n; ++i) bottom[i] = add(i, -1);
  for (int i = 0; i < n; ++i)
    if (outline[i]) rim[i] = add(i, 0);
  // The -1 side lies along the right-hand normal (normal_sign = -1): its face keeps the
  // mid-surface orientation, the +1 face is reversed.
  for (const auto& t : mid) {
    b.triangles.push_back({bottom[t[0]], bottom[t[1]], bottom[t[2]]});
    b.triangles.push_back({top[t[0]], top[t[2]], top[t[1]]});
  }
  // Rim wall of an outline edge a->c (as its triangle traverses it): the +1 face traverses c->a,
  // so the wall triangle on it traverses a->c, and so on down to the -1 face. Each wall triangle's
  // normal then points away from the triangle that owns the edge: outward.
  for (const auto& [e, count] : directed) {
    const auto [a, c] = e;
    if (directed.count({c, a})) continue;
    b.triangles.push_back({top[a], top[c], rim[c]});
    b.triangles.push_back({top[a], rim[c], rim[a]});
    b.triangles.push_back({rim[a], rim[c], bottom[c]});
    b.triangles.push_back({rim[a], bottom[c], bottom[a]});
  }
  return b;
}

// Throws finverse::Error (message starts with `what`) unless every edge of the triangles is shared
// by exactly two triangles that traverse it in opposite directions (closed, consistently oriented)
// and every index lies in [0, point_count).
inline void check_watertight(const std::vector<std::array<int, 3>>& triangles, int point_count,
                             const std::string& what) {
  thin_body_detail::check_indices(triangles, point_count, what);
  thin_body_detail::DirectedEdges directed;
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto& tri = triangles[t];
    if (tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2])
      throw Error(what + ": triangle " + std::to_string(t) + " repeats a vertex");
    for (int k = 0; k < 3; ++k)
      if (++directed[{tri[k], tri[(k + 1) % 3]}] > 1)
        throw Error(what + ": edge " + std::to_string(tri[k]) + "->" + std::to_string(tri[(k + 1) % 3]) +
                    " is traversed in the same direction by two triangles (inconsistent orientation or non-manifold)");
  }
  for (const auto& [e, count] : directed)
    if (!directed.count({e.second, e.first}))
      throw Error(what + ": edge " + std::to_string(e.first) + "-" + std::to_string(e.second) +
                  " belongs to one triangle only: the surface is not closed");
}

// Signed distance of surface vertex v from its node along the node's normal n:
// offset_sign * normal_sign * thickness / 2, and exactly 0 on the rim.
inline double offset_distance(const ThinBody& body, std::size_t v) {
  return body.offset_sign[v] == 0 ? 0.0 : body.offset_sign[v] * body.normal_sign * (0.5 * body.thickness);
}

// The body's vertex positions for mid-surface node positions x and unit normals n (right-hand
// normals of the mid-surface triangles). Rim vertices sit on their node exactly (no 0 * n).
inline std::vector<std::array<double, 3>> thin_body_points(const ThinBody& body,
                                                           const std::vector<std::array<double, 3>>& x,
                                                           const std::vector<std::array<double, 3>>& n) {
  std::vector<std::array<double, 3>> p(body.source_node.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    const auto src = static_cast<std::size_t>(body.source_node[i]);
    const double f = offset_distance(body, i);
    for (int d = 0; d < 3; ++d) p[i][d] = f == 0 ? x[src][d] : x[src][d] + f * n[src][d];
  }
  return p;
}

}  // namespace finverse
