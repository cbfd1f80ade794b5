// Structured truth surface of the fin between its rays (seed paper section 4.1).
#include "vision/fin_surface.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace finverse::vision {

FinSurface make_fin_surface(const mesh::FinTemplate& t, int subdivisions) {
  mesh::validate(t);
  if (subdivisions < 2 || subdivisions % 2) throw Error("fin surface: subdivisions must be even and >= 2");
  const std::size_t nr = t.rays.size();
  std::size_t m = 0;
  bool same = true;
  for (const auto& r : t.rays) {
    same = same && (m == 0 || r.points.size() == m);
    m = std::max(m, r.points.size());
  }
  // rows[r][k]: point of ray r on row k, with its arc-length fraction.
  std::vector<std::vector<mesh::Point2>> rows(nr);
  std::vector<std::vector<double>> srow(nr);
  for (std::size_t r = 0; r < nr; ++r) {
    if (same) {
      rows[r] = t.rays[r].points;
      srow[r] = t.arc_fractions(r);
    } else {
      for (std::size_t k = 0; k < m; ++k) {
        const double s = static_cast<double>(k) / (m - 1);
        rows[r].push_back(t.point_at(r, s));
        srow[r].push_back(s);
      }
    }
  }
  FinSurface f;
  f.chord = t.chord;
  f.rays = nr;
  const std::size_t ncol = (nr - 1) * subdivisions + 1;
  f.rest = NdArray<double>({ncol * m, 3});
  auto id = [&](std::size_t col, std::size_t k) { return static_cast<std::int32_t>(col * m + k); };
  f.eta.resize(ncol * m);
  f.s.resize(ncol * m);
  f.root.resize(ncol * m);
  f.ray_distance.resize(ncol * m);
  f.ray_half_width.resize(ncol * m);
  for (std::size_t col = 0; col < ncol; ++col) {
    const std::size_t r = std::min(col / subdivisions, nr - 2);
    const double a = static_cast<double>(col - r * subdivisions) / subdivisions;  // 0 at ray r, 1 at ray r+1
    const std::size_t nearest = a <= 0.5 ? r : r + 1;
    for (std::size_t k = 0; k < m; ++k) {
      const auto& p = rows[r][k];
      const auto& q = rows[r + 1][k];
      const std::size_t i = id(col, k);
      f.rest(i, 0) = (1 - a) * p[0] + a * q[0];
      f.rest(i, 1) = 0.0;
      f.rest(i, 2) = (1 - a) * p[1] + a * q[1];
      f.eta[i] = 1.0 - 2.0 * (r + a) / (nr - 1);
      f.s[i] = (1 - a) * srow[r][k] + a * srow[r + 1][k];
      f.root[i] = {(1 - a) * rows[r][0][0] + a * rows[r + 1][0][0], (1 - a) * rows[r][0][1] + a * rows[r + 1][0][1]};
      f.ray_distance[i] = std::min(a, 1 - a) * std::hypot(q[0] - p[0], q[1] - p[1]);
      f.ray_half_width[i] = 0.5 * t.section(nearest, f.s[i]).width;
    }
  }
  // Two triangles per cell, counter-clockwise in (x, z) like the structural mesh: columns run
  // dorsal to ventral (-z), rows root to tip (+x).
  f.triangles = NdArray<std::int32_t>({(ncol - 1) * (m - 1) * 2, 3});
  std::size_t n = 0;
  for (std::size_t col = 0; col + 1 < ncol; ++col)
    for (std::size_t k = 0; k + 1 < m; ++k) {
      const std::int32_t a = id(col, k), b = id(col + 1, k), c = id(col + 1, k + 1), d = id(col, k + 1);
      const std::int32_t tri[2][3] = {{a, b, c}, {a, c, d}};
      for (const auto& t3 : tri) {
        const double ux = f.rest(t3[1], 0) - f.rest(t3[0], 0), uz = f.rest(t3[1], 2) - f.rest(t3[0], 2);
        const double vx = f.rest(t3[2], 0) - f.rest(t3[0], 0), vz = f.rest(t3[2], 2) - f.rest(t3[0], 2);
        const bool ccw = ux * vz - uz * vx > 0;
        f.triangles(n, 0) = t3[0];
        f.triangles(n, 1) = ccw ? t3[1] : t3[2];
        f.triangles(n, 2) = ccw ? t3[2] : t3[1];
        ++n;
      }
    }
  return f;
}

}  // namespace finverse::vision
