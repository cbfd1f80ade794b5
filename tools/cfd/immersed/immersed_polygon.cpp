// Polygon geometry for the 2-D ghost-cell immersed boundary; see immersed_polygon.hpp.
#include "cfd/immersed/immersed_polygon.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "core/error.hpp"

namespace finverse::cfd {

double polygon_signed_area(const std::vector<std::array<double, 2>>& v) {
  double a = 0;
  for (std::size_t k = 0; k < v.size(); ++k) {
    const auto& p = v[k];
    const auto& q = v[(k + 1) % v.size()];
    a += p[0] * q[1] - q[0] * p[1];
  }
  return 0.5 * a;
}

Polygon::Polygon(std::vector<std::array<double, 2>> vertices) : v_(std::move(vertices)) {
  if (v_.size() < 3) throw Error("immersed body: a polygon needs at least 3 vertices");
  const double a = polygon_signed_area(v_);
  if (!(std::abs(a) > 0)) throw Error("immersed body: polygon has zero area");
  if (a < 0) std::reverse(v_.begin(), v_.end());
}

Polygon Polygon::circle(double cx, double cy, double r, int n) {
  if (n < 3 || !(r > 0)) throw Error("immersed body: circle needs r > 0 and n >= 3 segments");
  std::vector<std::array<double, 2>> v(static_cast<std::size_t>(n));
  for (int k = 0; k < n; ++k) {
    const double t = 2 * std::numbers::pi * k / n;
    v[static_cast<std::size_t>(k)] = {cx + r * std::cos(t), cy + r * std::sin(t)};
  }
  return Polygon(std::move(v));
}

double Polygon::area() const { return polygon_signed_area(v_); }

std::array<double, 4> Polygon::bounds() const {
  std::array<double, 4> b{v_[0][0], v_[0][1], v_[0][0], v_[0][1]};
  for (const auto& p : v_) {
    b[0] = std::min(b[0], p[0]);
    b[1] = std::min(b[1], p[1]);
    b[2] = std::max(b[2], p[0]);
    b[3] = std::max(b[3], p[1]);
  }
  return b;
}

bool Polygon::contains(double x, double y) const {
  bool in = false;
  for (std::size_t k = 0, l = v_.size() - 1; k < v_.size(); l = k++) {
    const auto& a = v_[k];
    const auto& b = v_[l];
    if ((a[1] > y) != (b[1] > y) && x < (b[0] - a[0]) * (y - a[1]) / (b[1] - a[1]) + a[0]) in = !in;
  }
  return in;
}

SurfacePoint Polygon::closest(double x, double y) const {
  SurfacePoint best;
  double best_d2 = std::numeric_limits<double>::infinity();
  // contains() is O(n): evaluated once, when first needed (a point deep inside the body improves
  // on vertex-closest candidates many times).
  int inside = -1;
  const auto in = [&] {
    if (inside < 0) inside = contains(x, y) ? 1 : 0;
    return inside == 1;
  };
  for (std::size_t k = 0; k < v_.size(); ++k) {
    const auto& a = v_[k];
    const auto& b = v_[(k + 1) % v_.size()];
    const double ex = b[0] - a[0], ey = b[1] - a[1];
    const double len2 = ex * ex + ey * ey;
    double t = ((x - a[0]) * ex + (y - a[1]) * ey) / len2;
    t = std::clamp(t, 0.0, 1.0);
    const double px = a[0] + t * ex, py = a[1] + t * ey;
    const double d2 = (x - px) * (x - px) + (y - py) * (y - py);
    if (d2 < best_d2) {
      best_d2 = d2;
      best.point = {px, py};
      best.edge = static_cast<int>(k);
      best.edge_t = t;
      const double len = std::sqrt(len2);
      best.normal = {ey / len, -ex / len};  // outward for a counter-clockwise polygon
      if (t == 0.0 || t == 1.0) {
        // Closest to a vertex: the probe direction is along (x - p), not the edge normal.
        const double d = std::sqrt(d2);
        if (d > 0) {
          const double s = in() ? -1.0 : 1.0;
          best.normal = {s * (x - px) / d, s * (y - py) / d};
        }
      }
    }
  }
  best.distance = (in() ? -1.0 : 1.0) * std::sqrt(best_d2);
  return best;
}

}  // namespace finverse::cfd
