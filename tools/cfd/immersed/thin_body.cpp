// Closed thin body around a deforming mid-surface: topology, watertightness, vertex normals with
// their time derivatives, and placement (see thin_body.hpp).
#include "cfd/immersed/thin_body.hpp"

#include <cmath>
#include <map>
#include <utility>

#include "cfd/immersed/vec3.hpp"
#include "core/error.hpp"

namespace finverse::cfd {

namespace {

void add_to(Vec3& s, const Vec3& a, double f = 1.0) {
  for (int d = 0; d < 3; ++d) s[d] += f * a[d];
}

void check_indices(const std::vector<std::array<int, 3>>& triangles, int count, const std::string& what) {
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k)
      if (triangles[t][k] < 0 || triangles[t][k] >= count)
        throw Error(what + ": triangle " + std::to_string(t) + " has vertex index " + std::to_string(triangles[t][k]) +
                    ", expected 0.." + std::to_string(count - 1));
}

}  // namespace

void check_watertight(const std::vector<std::array<int, 3>>& triangles, int point_count, const std::string& what) {
  check_indices(triangles, point_count, what);
  std::map<std::pair<int, int>, int> directed;
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

ThinBody build_thin_body(const std::vector<std::array<int, 3>>& mid, int n, double thickness, const std::string& what) {
  if (!(std::isfinite(thickness) && thickness > 0))
    throw Error(what + ": thin-body thickness " + std::to_string(thickness) + " m, expected > 0");
  check_indices(mid, n, what);
  std::map<std::pair<int, int>, int> directed;
  for (const auto& t : mid)
    for (int k = 0; k < 3; ++k)
      if (++directed[{t[k], t[(k + 1) % 3]}] > 1)
        throw Error(what + ": edge " + std::to_string(t[k]) + "->" + std::to_string(t[(k + 1) % 3]) +
                    " is traversed twice in one direction: the mid-surface is not a consistently oriented manifold");
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
  // Rim wall of an outline edge a->b (as its triangle traverses it): the +1 face traverses b->a,
  // so the wall triangle on it traverses a->b, and so on down to the -1 face; this is fin-mesh's
  // wall with the orientation its geometric test picks for a planar, counter-clockwise planform.
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

VertexNormals vertex_normals(const std::vector<Vec3>& x, const std::vector<Vec3>& v, const std::vector<Vec3>& a,
                             const std::vector<std::array<int, 3>>& triangles) {
  const std::size_t n = x.size();
  const bool moving = !v.empty(), accelerating = !a.empty();
  // The sums N, N', N'' accumulate in the output arrays and are normalised in place.
  VertexNormals out;
  out.n.resize(n);
  out.dn.resize(n);
  out.ddn.resize(n);
  const Vec3 zero{};
  for (const auto& t : triangles) {
    const Vec3 e1 = sub(x[t[1]], x[t[0]]), e2 = sub(x[t[2]], x[t[0]]);
    // N = e1 x e2, dN = de1 x e2 + e1 x de2, ddN = dde1 x e2 + 2 de1 x de2 + e1 x dde2.
    const Vec3 c = cross(e1, e2);
    const Vec3 de1 = moving ? sub(v[t[1]], v[t[0]]) : zero, de2 = moving ? sub(v[t[2]], v[t[0]]) : zero;
    const Vec3 dde1 = accelerating ? sub(a[t[1]], a[t[0]]) : zero, dde2 = accelerating ? sub(a[t[2]], a[t[0]]) : zero;
    Vec3 dc = cross(de1, e2), ddc = cross(dde1, e2);
    add_to(dc, cross(e1, de2));
    add_to(ddc, cross(de1, de2), 2.0);
    add_to(ddc, cross(e1, dde2));
    for (int k = 0; k < 3; ++k) {
      const auto j = static_cast<std::size_t>(t[k]);
      add_to(out.n[j], c);
      add_to(out.dn[j], dc);
      add_to(out.ddn[j], ddc);
    }
  }
  std::size_t bad = n;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 N = out.n[i], dN = out.dn[i], ddN = out.ddn[i];
    const double r = std::sqrt(dot(N, N));
    if (!(r > 0) || !std::isfinite(r)) {
      bad = std::min(bad, i);
      continue;
    }
    // n = N/r;  r' = n.N';  n' = (N' - n r')/r;  r'' = (|N'|^2 + N.N'')/r - r'^2/r;
    // n'' = (N'' - 2 n' r' - n r'')/r.
    Vec3 nn, dn, ddn;
    for (int d = 0; d < 3; ++d) nn[d] = N[d] / r;
    const double dr = dot(nn, dN);
    for (int d = 0; d < 3; ++d) dn[d] = (dN[d] - nn[d] * dr) / r;
    const double ddr = (dot(dN, dN) + dot(N, ddN)) / r - dr * dr / r;
    for (int d = 0; d < 3; ++d) ddn[d] = (ddN[d] - 2 * dn[d] * dr - nn[d] * ddr) / r;
    out.n[i] = nn;
    out.dn[i] = dn;
    out.ddn[i] = ddn;
  }
  if (bad < n)
    throw Error("mid-surface node " + std::to_string(bad) + ": no normal (no triangle or only degenerate triangles)");
  return out;
}

SurfaceState place_thin_body(const ThinBody& body, const std::vector<Vec3>& x, const std::vector<Vec3>& v,
                             const std::vector<Vec3>& a, const std::vector<std::array<int, 3>>& mid) {
  if (static_cast<int>(x.size()) != body.node_count || (!v.empty() && v.size() != x.size()) ||
      (!a.empty() && a.size() != x.size()))
    throw Error("thin body: " + std::to_string(x.size()) + " node positions for a body around " +
                std::to_string(body.node_count) + " nodes");
  const VertexNormals nrm = vertex_normals(x, v, a, mid);
  const std::size_t nv = body.source_node.size();
  SurfaceState s;
  s.surface.triangles = body.triangles;
  s.surface.points.resize(nv);
  const bool kinematics = !v.empty() || !a.empty();
  if (kinematics) {
    s.velocity.assign(nv, Vec3{});
    s.acceleration.assign(nv, Vec3{});
  }
  const double h = 0.5 * body.thickness;
  for (std::size_t i = 0; i < nv; ++i) {
    const int src = body.source_node[i];
    // Rim vertices (sign 0) sit on the node exactly, as in fin-mesh (no 0 * n round-off games).
    const double f = body.offset_sign[i] == 0 ? 0.0 : body.offset_sign[i] * body.normal_sign * h;
    for (int d = 0; d < 3; ++d) {
      s.surface.points[i][d] = f == 0 ? x[src][d] : x[src][d] + f * nrm.n[src][d];
      if (kinematics) {
        s.velocity[i][d] = (v.empty() ? 0.0 : v[src][d]) + f * nrm.dn[src][d];
        s.acceleration[i][d] = (a.empty() ? 0.0 : a[src][d]) + f * nrm.ddn[src][d];
      }
    }
  }
  return s;
}

}  // namespace finverse::cfd
