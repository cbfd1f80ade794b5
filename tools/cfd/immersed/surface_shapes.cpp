// Triangulated sphere and box; see surface_shapes.hpp.
#include "cfd/immersed/surface_shapes.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <utility>

#include "cfd/immersed/surface_geometry.hpp"
#include "core/error.hpp"

namespace finverse::cfd {

TriangulatedSurface icosphere(const std::array<double, 3>& centre, double radius, int subdivisions,
                              bool volume_preserving) {
  if (!(radius > 0) || subdivisions < 0 || subdivisions > 8) throw Error("icosphere: need radius > 0 and 0 <= subdivisions <= 8");
  const double g = (1 + std::sqrt(5.0)) / 2;
  std::vector<std::array<double, 3>> p = {{-1, g, 0}, {1, g, 0}, {-1, -g, 0}, {1, -g, 0}, {0, -1, g}, {0, 1, g},
                                          {0, -1, -g}, {0, 1, -g}, {g, 0, -1}, {g, 0, 1}, {-g, 0, -1}, {-g, 0, 1}};
  std::vector<std::array<int, 3>> t = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                                       {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
                                       {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  const auto unit = [](std::array<double, 3> v) {
    const double n = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    return std::array<double, 3>{v[0] / n, v[1] / n, v[2] / n};
  };
  for (auto& v : p) v = unit(v);
  for (int s = 0; s < subdivisions; ++s) {
    std::map<std::pair<int, int>, int> mid;
    const auto midpoint = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      const auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      const auto& A = p[static_cast<std::size_t>(a)];
      const auto& B = p[static_cast<std::size_t>(b)];
      p.push_back(unit({A[0] + B[0], A[1] + B[1], A[2] + B[2]}));
      return mid[key] = static_cast<int>(p.size()) - 1;
    };
    std::vector<std::array<int, 3>> next;
    next.reserve(4 * t.size());
    for (const auto& tri : t) {
      const int a = midpoint(tri[0], tri[1]), b = midpoint(tri[1], tri[2]), c = midpoint(tri[2], tri[0]);
      next.push_back({tri[0], a, c});
      next.push_back({tri[1], b, a});
      next.push_back({tri[2], c, b});
      next.push_back({a, b, c});
    }
    t = std::move(next);
  }
  double r = radius;
  if (volume_preserving) {
    const double v = SurfaceGeometry(TriangulatedSurface{p, t}, "icosphere").volume();
    r *= std::cbrt(4 * std::numbers::pi / 3 / v);
  }
  TriangulatedSurface s;
  s.triangles = t;
  for (const auto& v : p) s.points.push_back({centre[0] + r * v[0], centre[1] + r * v[1], centre[2] + r * v[2]});
  return s;
}

TriangulatedSurface box_surface(const std::array<double, 3>& lo, const std::array<double, 3>& hi) {
  TriangulatedSurface s;
  for (int c = 0; c < 8; ++c)
    s.points.push_back({(c & 1) ? hi[0] : lo[0], (c & 2) ? hi[1] : lo[1], (c & 4) ? hi[2] : lo[2]});
  // Two triangles per face, counter-clockwise seen from outside.
  s.triangles = {{0, 2, 3}, {0, 3, 1},   // z = lo
                 {4, 5, 7}, {4, 7, 6},   // z = hi
                 {0, 1, 5}, {0, 5, 4},   // y = lo
                 {2, 6, 7}, {2, 7, 3},   // y = hi
                 {0, 4, 6}, {0, 6, 2},   // x = lo
                 {1, 3, 7}, {1, 7, 5}};  // x = hi
  return s;
}

TriangulatedSurface cylinder_surface(double xc, double yc, double radius, double z0, double z1, int segments,
                                     int layers) {
  if (!(radius > 0) || !(z1 > z0) || segments < 3 || layers < 1)
    throw Error("cylinder_surface: need radius > 0, z1 > z0, at least 3 segments and 1 layer");
  TriangulatedSurface s;
  for (int l = 0; l <= layers; ++l) {
    const double z = l == layers ? z1 : z0 + (z1 - z0) * l / layers;
    for (int k = 0; k < segments; ++k) {
      const double phi = 2 * std::numbers::pi * k / segments;
      s.points.push_back({xc + radius * std::cos(phi), yc + radius * std::sin(phi), z});
    }
  }
  const int bottom = static_cast<int>(s.points.size());
  s.points.push_back({xc, yc, z0});
  s.points.push_back({xc, yc, z1});
  const auto ring = [segments](int l, int k) { return l * segments + (k % segments); };
  for (int l = 0; l < layers; ++l)
    for (int k = 0; k < segments; ++k) {  // counter-clockwise seen from outside (increasing angle, then up)
      s.triangles.push_back({ring(l, k), ring(l, k + 1), ring(l + 1, k + 1)});
      s.triangles.push_back({ring(l, k), ring(l + 1, k + 1), ring(l + 1, k)});
    }
  for (int k = 0; k < segments; ++k) {
    s.triangles.push_back({bottom, ring(0, k + 1), ring(0, k)});               // normal -z
    s.triangles.push_back({bottom + 1, ring(layers, k), ring(layers, k + 1)});  // normal +z
  }
  return s;
}

TriangulatedSurface cylinder_between(const std::array<double, 3>& from, const std::array<double, 3>& to, double radius,
                                     int segments) {
  const Vec3 axis = sub(to, from);
  const double length = norm(axis);
  if (!(length > 0) || !(radius > 0)) throw Error("cylinder_between: need a positive length and radius");
  const int layers = std::max(1, static_cast<int>(std::lround(length / (2 * std::numbers::pi * radius / segments))));
  TriangulatedSurface s = cylinder_surface(0, 0, radius, 0, length, segments, layers);
  // A right-handed frame (u, v, w) with w along the axis keeps the triangles counter-clockwise.
  const Vec3 w{axis[0] / length, axis[1] / length, axis[2] / length};
  int least = 0;
  for (int d = 1; d < 3; ++d)
    if (std::abs(w[static_cast<std::size_t>(d)]) < std::abs(w[static_cast<std::size_t>(least)])) least = d;
  Vec3 e{0, 0, 0};
  e[static_cast<std::size_t>(least)] = 1;
  const double ew = dot(e, w);
  Vec3 u{e[0] - ew * w[0], e[1] - ew * w[1], e[2] - ew * w[2]};
  const double nu = norm(u);
  u = {u[0] / nu, u[1] / nu, u[2] / nu};
  const Vec3 v = cross(w, u);
  for (auto& p : s.points) {
    const Vec3 q = p;
    for (std::size_t d = 0; d < 3; ++d) p[d] = from[d] + q[0] * u[d] + q[1] * v[d] + q[2] * w[d];
  }
  return s;
}

}  // namespace finverse::cfd
