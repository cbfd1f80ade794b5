// Cut-cell face apertures of a polygon (see cut_faces.hpp). Each grid line x = x_i (y = y_j) that
// crosses the polygon's bounding box is cut with every polygon edge under the half-open rule of
// the crossing-number test, so the sorted crossings pair up into the intervals inside the polygon;
// each face on the line then takes its overlap with those intervals.
#include "cfd/immersed/cut_faces.hpp"

#include <algorithm>
#include <limits>
#include <vector>

namespace finverse::cfd {

namespace {

// Inside intervals of the polygon on the line {x_d = c}, as coordinates along the other axis.
std::vector<double> crossings(const std::vector<std::array<double, 2>>& v, int d, double c) {
  const int t = 1 - d;
  std::vector<double> s;
  const std::size_t n = v.size();
  for (std::size_t e = 0; e < n; ++e) {
    const auto& a = v[e];
    const auto& b = v[(e + 1) % n];
    if ((a[static_cast<std::size_t>(d)] <= c) == (b[static_cast<std::size_t>(d)] <= c)) continue;
    const double f = (c - a[static_cast<std::size_t>(d)]) / (b[static_cast<std::size_t>(d)] - a[static_cast<std::size_t>(d)]);
    s.push_back(a[static_cast<std::size_t>(t)] + f * (b[static_cast<std::size_t>(t)] - a[static_cast<std::size_t>(t)]));
  }
  std::sort(s.begin(), s.end());
  return s;
}

}  // namespace

CutFaces cut_faces(const StretchedGrid& g, const Polygon& body) {
  CutFaces cf{FaceCoefficients(g, 1.0), FaceCoefficients(g, 0.0)};
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i <= g.nx(); ++i) cf.centroid(0, i, j, 0) = g.yc(j);
  for (int j = 0; j <= g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i) cf.centroid(1, i, j, 0) = g.xc(i);

  const auto& v = body.vertices();
  std::array<double, 2> lo{std::numeric_limits<double>::max(), std::numeric_limits<double>::max()};
  std::array<double, 2> hi{std::numeric_limits<double>::lowest(), std::numeric_limits<double>::lowest()};
  for (const auto& p : v)
    for (std::size_t a = 0; a < 2; ++a) {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
  for (int d = 0; d < 2; ++d) {
    const int t = 1 - d;
    const Axis& normal_axis = g.axis(d);
    const Axis& tangent_axis = g.axis(t);
    for (int f = 0; f <= normal_axis.size(); ++f) {
      const double c = normal_axis.face(f);
      if (c < lo[static_cast<std::size_t>(d)] || c > hi[static_cast<std::size_t>(d)]) continue;
      const std::vector<double> s = crossings(v, d, c);
      for (int m = 0; m < tangent_axis.size(); ++m) {
        const double a = tangent_axis.face(m), b = tangent_axis.face(m + 1);
        if (b < lo[static_cast<std::size_t>(t)] || a > hi[static_cast<std::size_t>(t)]) continue;
        // Solid length and first moment of the face from its overlap with the inside intervals.
        double len = 0, moment = 0;
        for (std::size_t q = 0; q + 1 < s.size(); q += 2) {
          const double x0 = std::max(a, s[q]), x1 = std::min(b, s[q + 1]);
          if (x1 <= x0) continue;
          len += x1 - x0;
          moment += 0.5 * (x1 * x1 - x0 * x0);
        }
        if (len <= 0) continue;
        const double w = b - a;
        double alpha = 1 - len / w;
        const int i = d == 0 ? f : m, j = d == 0 ? m : f;
        if (alpha < 1e-12) {
          cf.aperture(d, i, j, 0) = 0;
          continue;
        }
        alpha = std::min(alpha, 1.0);
        cf.aperture(d, i, j, 0) = alpha;
        cf.centroid(d, i, j, 0) = (0.5 * (b * b - a * a) - moment) / (w - len);
      }
    }
  }
  return cf;
}

CutFaces cut_faces(const StretchedGrid& g, const std::vector<SolidRegion>& regions) {
  CutFaces cf{FaceCoefficients(g, 1.0), FaceCoefficients(g, 0.0)};
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i <= g.nx(); ++i) cf.centroid(0, i, j, 0) = g.yc(j);
  for (int j = 0; j <= g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i) cf.centroid(1, i, j, 0) = g.xc(i);
  for (const SolidRegion& r : regions) {
    const CutFaces one = cut_faces(g, r.polygon);
    for (int d = 0; d < 2; ++d) {
      const std::vector<double>& a = one.aperture.values(d);
      for (std::size_t f = 0; f < a.size(); ++f) {
        const double solid = r.outside ? a[f] : 1 - a[f];
        const int nx = g.nx() + (d == 0);
        const int i = static_cast<int>(f % static_cast<std::size_t>(nx)), j = static_cast<int>(f / static_cast<std::size_t>(nx));
        double& alpha = cf.aperture(d, i, j, 0);
        alpha = alpha - solid < 1e-12 ? 0.0 : alpha - solid;
      }
    }
  }
  return cf;
}

}  // namespace finverse::cfd
