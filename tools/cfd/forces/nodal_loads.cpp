// Surface-triangle forces of the closed thin body to mid-surface nodal forces and shell pressure
// jumps (see nodal_loads.hpp).
#include "cfd/forces/nodal_loads.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "core/error.hpp"

namespace finverse::cfd {

namespace {

void check_sizes(const ThinBody& body, const SurfaceForces& f) {
  if (f.pressure.size() != body.triangles.size() || f.viscous.size() != body.triangles.size())
    throw Error("nodal loads: forces on " + std::to_string(f.pressure.size()) + " / " +
                std::to_string(f.viscous.size()) + " triangles (pressure / viscous) for a body of " +
                std::to_string(body.triangles.size()) + " triangles");
}

std::array<int, 3> sorted(std::array<int, 3> t) {
  std::sort(t.begin(), t.end());
  return t;
}

}  // namespace

std::vector<Vec3> nodal_forces(const ThinBody& body, const SurfaceForces& f) {
  check_sizes(body, f);
  std::vector<Vec3> out(static_cast<std::size_t>(body.node_count), Vec3{});
  for (std::size_t t = 0; t < body.triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      auto& node = out[static_cast<std::size_t>(body.source_node[static_cast<std::size_t>(body.triangles[t][k])])];
      for (int d = 0; d < 3; ++d) node[d] += (f.pressure[t][d] + f.viscous[t][d]) / 3.0;
    }
  return out;
}

Vec3 triangle_force_sum(const SurfaceForces& f) {
  Vec3 s{};
  for (std::size_t t = 0; t < f.pressure.size(); ++t)
    for (int d = 0; d < 3; ++d) s[d] += f.pressure[t][d] + (t < f.viscous.size() ? f.viscous[t][d] : 0.0);
  return s;
}

std::vector<double> pressure_jump(const ThinBody& body, const std::vector<std::array<int, 3>>& mid,
                                  const TriangulatedSurface& surface, const SurfaceForces& f) {
  check_sizes(body, f);
  if (surface.triangles.size() != body.triangles.size() || surface.points.size() != body.source_node.size())
    throw Error("pressure jump: the surface state does not match the thin body");
  const std::size_t nt = body.triangles.size(), nn = static_cast<std::size_t>(body.node_count);
  // Mean pressure and area of every surface triangle; the side of the faces (rim: 0).
  std::vector<double> p(nt, 0.0), area(nt, 0.0);
  std::vector<int> side(nt, 0);
  std::map<std::pair<std::array<int, 3>, int>, std::size_t> facing;  // (sorted source nodes, side) -> triangle
  for (std::size_t t = 0; t < nt; ++t) {
    const auto& tri = surface.triangles[t];
    const Vec3 &a = surface.points[tri[0]], &b = surface.points[tri[1]], &c = surface.points[tri[2]];
    const Vec3 e1{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
    const Vec3 av{0.5 * (e1[1] * e2[2] - e1[2] * e2[1]), 0.5 * (e1[2] * e2[0] - e1[0] * e2[2]),
                  0.5 * (e1[0] * e2[1] - e1[1] * e2[0])};
    const double a2 = av[0] * av[0] + av[1] * av[1] + av[2] * av[2];
    area[t] = std::sqrt(a2);
    if (a2 > 0) p[t] = -(f.pressure[t][0] * av[0] + f.pressure[t][1] * av[1] + f.pressure[t][2] * av[2]) / a2;
    const int s0 = body.offset_sign[tri[0]];
    if (s0 != 0 && body.offset_sign[tri[1]] == s0 && body.offset_sign[tri[2]] == s0) {
      side[t] = s0;
      const std::array<int, 3> src{body.source_node[tri[0]], body.source_node[tri[1]], body.source_node[tri[2]]};
      facing.emplace(std::make_pair(sorted(src), s0), t);
    }
  }
  // Fallback: area-weighted side pressure at each node.
  std::array<std::vector<double>, 2> node_p{std::vector<double>(nn, 0.0), std::vector<double>(nn, 0.0)};
  std::array<std::vector<double>, 2> node_w{std::vector<double>(nn, 0.0), std::vector<double>(nn, 0.0)};
  for (std::size_t t = 0; t < nt; ++t) {
    if (side[t] == 0) continue;
    const int s = side[t] > 0 ? 0 : 1;
    for (int k = 0; k < 3; ++k) {
      const auto node = static_cast<std::size_t>(body.source_node[surface.triangles[t][k]]);
      node_p[s][node] += area[t] * p[t];
      node_w[s][node] += area[t];
    }
  }
  auto side_pressure = [&](const std::array<int, 3>& tri, int sign) {
    const auto it = facing.find({sorted(tri), sign});
    if (it != facing.end()) return p[it->second];
    const int s = sign > 0 ? 0 : 1;
    double sum = 0;
    for (int k = 0; k < 3; ++k) {
      const auto node = static_cast<std::size_t>(tri[k]);
      sum += node_w[s][node] > 0 ? node_p[s][node] / node_w[s][node] : 0.0;
    }
    return sum / 3;
  };
  // Front: the offset sign whose copies lie along the right-hand normal (offset_sign * normal_sign = +1).
  const int front = body.normal_sign, back = -body.normal_sign;
  std::vector<double> jump(mid.size());
  for (std::size_t e = 0; e < mid.size(); ++e) jump[e] = side_pressure(mid[e], back) - side_pressure(mid[e], front);
  return jump;
}

}  // namespace finverse::cfd
