// Closed thin body around a deforming mid-surface: vertex normals with their time derivatives, and
// the placement of core/thin_body.hpp's body with its velocities and accelerations (see thin_body.hpp).
#include "cfd/immersed/thin_body.hpp"

#include <algorithm>
#include <cmath>

#include "cfd/immersed/vec3.hpp"
#include "core/error.hpp"

namespace finverse::cfd {

namespace {

void add_to(Vec3& s, const Vec3& a, double f = 1.0) {
  for (int d = 0; d < 3; ++d) s[d] += f * a[d];
}

}  // namespace

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
  SurfaceState s;
  s.surface.triangles = body.triangles;
  s.surface.points = thin_body_points(body, x, nrm.n);
  if (v.empty() && a.empty()) return s;
  const std::size_t nv = body.source_node.size();
  s.velocity.assign(nv, Vec3{});
  s.acceleration.assign(nv, Vec3{});
  for (std::size_t i = 0; i < nv; ++i) {
    const int src = body.source_node[i];
    const double f = offset_distance(body, i);
    for (int d = 0; d < 3; ++d) {
      s.velocity[i][d] = (v.empty() ? 0.0 : v[src][d]) + f * nrm.dn[src][d];
      s.acceleration[i][d] = (a.empty() ? 0.0 : a[src][d]) + f * nrm.ddn[src][d];
    }
  }
  return s;
}

}  // namespace finverse::cfd
