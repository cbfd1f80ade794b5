// A deforming 2-D polygon body with per-vertex kinematics; see deforming_polygon.hpp.
#include "cfd/immersed/deforming_polygon.hpp"

#include <algorithm>
#include <cmath>

#include "core/error.hpp"

namespace finverse::cfd {

namespace {
// The polygon of the positions, checked first so that the error says what was wrong.
Polygon checked_polygon(const PolygonState& s, const std::string& what, std::size_t expected) {
  const std::size_t n = s.position.size();
  if (n < 3) throw Error(what + ": a deforming polygon needs at least 3 vertices, got " + std::to_string(n));
  if (expected > 0 && n != expected)
    throw Error(what + ": the body has " + std::to_string(expected) + " vertices, the state " + std::to_string(n));
  if ((!s.velocity.empty() && s.velocity.size() != n) || (!s.acceleration.empty() && s.acceleration.size() != n))
    throw Error(what + ": velocity/acceleration need one entry per vertex (or none)");
  for (const auto* q : {&s.position, &s.velocity, &s.acceleration})
    for (std::size_t k = 0; k < q->size(); ++k)
      if (!std::isfinite((*q)[k][0]) || !std::isfinite((*q)[k][1]))
        throw Error(what + ": vertex " + std::to_string(k) + " has a non-finite " +
                    (q == &s.position ? "position" : q == &s.velocity ? "velocity" : "acceleration"));
  if (!(std::abs(polygon_signed_area(s.position)) > 0)) throw Error(what + ": the polygon has zero area");
  return Polygon(s.position);
}
}  // namespace

PolygonState rigid_polygon_state(const MovingBody& body, const RigidState& s) {
  PolygonState o;
  o.position = body.placed(s).vertices();  // a rotation keeps the reference's (stored) order
  for (const auto& p : o.position) {
    o.velocity.push_back(body.velocity(s, p[0], p[1]));
    o.acceleration.push_back(body.acceleration(s, p[0], p[1]));
  }
  return o;
}

DeformingPolygon::DeformingPolygon(const PolygonState& s, const std::string& what, std::size_t expected)
    : state_(s), polygon_(checked_polygon(s, what, expected)) {
  signed_area_ = polygon_signed_area(s.position);
  reversed_ = signed_area_ < 0;
  const std::size_t n = s.position.size();
  const auto stored = [&](const std::vector<std::array<double, 2>>& q) {
    std::vector<std::array<double, 2>> o(n, {0.0, 0.0});
    if (q.empty()) return o;
    for (std::size_t k = 0; k < n; ++k) o[k] = reversed_ ? q[n - 1 - k] : q[k];
    return o;
  };
  vel_ = stored(s.velocity);
  acc_ = stored(s.acceleration);
}

std::array<double, 2> DeformingPolygon::along(const std::vector<std::array<double, 2>>& q, int e, double t) const {
  const std::size_t n = q.size();
  const auto& a = q[static_cast<std::size_t>(e)];
  const auto& b = q[(static_cast<std::size_t>(e) + 1) % n];
  return {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])};
}

std::pair<int, double> DeformingPolygon::caller_edge(int e, double t) const {
  if (!reversed_) return {e, t};
  // Stored vertex m is the caller's n - 1 - m, so stored edge m (m -> m + 1) runs backwards along
  // the caller's edge n - 2 - m (mod n).
  const int n = static_cast<int>(vel_.size());
  return {((n - 2 - e) % n + n) % n, 1 - t};
}

std::vector<DeformingPolygon::CellFlux> DeformingPolygon::wall_flux(const StretchedGrid& grid, double& net) const {
  const auto& v = polygon_.vertices();
  const std::size_t n = v.size();
  std::vector<CellFlux> out;
  net = 0;
  // The cell (lo, hi] holding coordinate x along axis d (clamped to the grid).
  const auto cell_of = [&](int d, double x) {
    const auto& f = grid.axis(d).faces();
    const auto it = std::lower_bound(f.begin(), f.end(), x);
    const int c = static_cast<int>(it - f.begin()) - 1;
    return std::clamp(c, 0, grid.axis(d).size() - 1);
  };
  std::vector<double> ts;
  for (std::size_t e = 0; e < n; ++e) {
    const auto& a = v[e];
    const auto& b = v[(e + 1) % n];
    const double ex = b[0] - a[0], ey = b[1] - a[1];
    ts.assign({0.0, 1.0});
    for (int d = 0; d < 2; ++d) {
      const auto D = static_cast<std::size_t>(d);
      const double lo = std::min(a[D], b[D]), hi = std::max(a[D], b[D]);
      if (!(hi > lo)) continue;  // along a grid line's direction: no crossing
      const auto& f = grid.axis(d).faces();
      for (auto it = std::upper_bound(f.begin(), f.end(), lo); it != f.end() && *it < hi; ++it)
        ts.push_back((*it - a[D]) / (b[D] - a[D]));
    }
    std::sort(ts.begin(), ts.end());
    const auto& va = vel_[e];
    const auto& vb = vel_[(e + 1) % n];
    const double len = std::hypot(ex, ey);
    for (std::size_t q = 0; q + 1 < ts.size(); ++q) {
      const double t0 = ts[q], t1 = ts[q + 1];
      if (!(t1 > t0)) continue;
      const double tm = 0.5 * (t0 + t1);
      // u_B linear along the edge: its mean over [t0, t1] is its value at the midpoint.
      const double ux = va[0] + tm * (vb[0] - va[0]), uy = va[1] + tm * (vb[1] - va[1]);
      CellFlux c;
      c.cell = {cell_of(0, a[0] + tm * ex), cell_of(1, a[1] + tm * ey), 0};
      c.flux = (t1 - t0) * (ux * ey - uy * ex);  // n dl = (ey, -ex) dt, outward (counter-clockwise)
      c.length = (t1 - t0) * len;
      net += c.flux;
      out.push_back(c);
    }
  }
  return out;
}

}  // namespace finverse::cfd
