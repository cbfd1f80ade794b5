// Surface traction and per-triangle forces on an immersed triangulated body; see
// surface_traction_3d.hpp.
#include "cfd/forces/surface_traction_3d.hpp"
#include "cfd/parallel/rank_share.hpp"

#include <algorithm>
#include <cmath>

namespace finverse::cfd {

std::vector<Vec3> clip_triangle_to_box(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& lo, const Vec3& hi) {
  std::vector<Vec3> poly{a, b, c}, next;
  for (std::size_t d = 0; d < 3; ++d)
    for (int high = 0; high < 2; ++high) {
      const double bound = high ? hi[d] : lo[d];
      const auto outside = [&](const Vec3& x) { return high ? x[d] - bound : bound - x[d]; };  // > 0: outside
      next.clear();
      for (std::size_t i = 0; i < poly.size(); ++i) {
        const Vec3& P = poly[i];
        const Vec3& Q = poly[(i + 1) % poly.size()];
        const double dp = outside(P), dq = outside(Q);
        if (dp <= 0) next.push_back(P);
        if ((dp < 0 && dq > 0) || (dp > 0 && dq < 0)) {
          const double s = dp / (dp - dq);
          Vec3 X;
          for (std::size_t k = 0; k < 3; ++k) X[k] = P[k] + s * (Q[k] - P[k]);
          X[d] = bound;  // exactly on the plane, whatever the rounding of s
          next.push_back(X);
        }
      }
      poly.swap(next);
      if (poly.size() < 3) return {};
    }
  return poly;
}

SurfaceTraction3D::SurfaceTraction3D(const StretchedGrid& grid, const GhostCellSet& ghosts, const SurfaceGeometry& body,
                                     const SurfaceClip& clip)
    : triangles_(body.triangles()), tri_(body.surface().triangles) {
  const auto& P = body.surface().points;
  Vec3 lo, hi;
  for (int d = 0; d < 3; ++d) {
    lo[static_cast<std::size_t>(d)] = grid.axis(d).lo();
    hi[static_cast<std::size_t>(d)] = grid.axis(d).hi();
  }
  // A clipped body's probe x (and its boundary point b, shifted alike so that the stencil's
  // geometry is unchanged) moved onto the outermost centre plane; the factor that carries the
  // velocity to zero on a no-slip wall (header comment).
  const auto place = [&](Vec3& x, Vec3& b) {
    double factor = 1;
    if (!clip.enabled) return factor;
    for (int d = 0; d < 3; ++d) {
      const auto k = static_cast<std::size_t>(d);
      const Axis& A = grid.axis(d);
      const double c_lo = A.centre(0), c_hi = A.centre(A.size() - 1);
      double target = x[k], wall = 0;
      bool no_slip = false;
      if (x[k] < c_lo) {
        target = c_lo;
        wall = A.lo();
        no_slip = clip.no_slip[2 * k];
      } else if (x[k] > c_hi) {
        target = c_hi;
        wall = A.hi();
        no_slip = clip.no_slip[2 * k + 1];
      } else {
        continue;
      }
      if (no_slip) factor *= std::clamp((x[k] - wall) / (target - wall), 0.0, 1.0);
      b[k] += target - x[k];
      x[k] = target;
    }
    return factor;
  };
  const auto scaled = [](PointStencil st, double f) {
    for (int k = 0; k < st.count; ++k) st.weight[static_cast<std::size_t>(k)] *= f;
    st.boundary_weight *= f;
    return st;
  };
  for (int t = 0; t < triangles_; ++t) {
    const auto& tri = tri_[static_cast<std::size_t>(t)];
    const Vec3& a = P[static_cast<std::size_t>(tri[0])];
    const Vec3& b = P[static_cast<std::size_t>(tri[1])];
    const Vec3& c = P[static_cast<std::size_t>(tri[2])];
    const Vec3& n = body.triangle_normal(t);
    // The pieces to sample: the triangle itself, or the fan of its clipped polygon (with the
    // barycentric coordinates of a point in the original triangle for the vertex data).
    std::vector<std::array<Vec3, 3>> pieces;
    bool whole = true;
    if (clip.enabled) {
      const std::vector<Vec3> poly = clip_triangle_to_box(a, b, c, lo, hi);
      whole = poly.size() == 3 && poly[0] == a && poly[1] == b && poly[2] == c;
      if (!whole)
        for (std::size_t i = 1; i + 1 < poly.size(); ++i) pieces.push_back({poly[0], poly[i], poly[i + 1]});
    }
    if (whole) pieces.push_back({a, b, c});
    Vec3 e1, e2;
    for (std::size_t d = 0; d < 3; ++d) {
      e1[d] = b[d] - a[d];
      e2[d] = c[d] - a[d];
    }
    const auto dot = [](const Vec3& x, const Vec3& y) { return x[0] * y[0] + x[1] * y[1] + x[2] * y[2]; };
    const double d11 = dot(e1, e1), d12 = dot(e1, e2), d22 = dot(e2, e2), det = d11 * d22 - d12 * d12;
    for (const auto& piece : pieces) {
      const Vec3 &q0 = piece[0], &q1 = piece[1], &q2 = piece[2];
      Vec3 centroid{};
      double longest = 0;
      for (std::size_t d = 0; d < 3; ++d) centroid[d] = (q0[d] + q1[d] + q2[d]) / 3;
      for (const auto& [p, q] : {std::pair{&q0, &q1}, std::pair{&q1, &q2}, std::pair{&q2, &q0}})
        longest = std::max(longest, std::hypot((*q)[0] - (*p)[0], (*q)[1] - (*p)[1], (*q)[2] - (*p)[2]));
      double hmin = 1e300;
      for (int d = 0; d < 3; ++d) hmin = std::min(hmin, grid.axis(d).width_at(centroid[static_cast<std::size_t>(d)]));
      const int m = std::clamp(static_cast<int>(std::ceil(longest / (0.5 * hmin))), 1, 64);
      double piece_area = body.triangle_area(t);
      if (!whole) {
        const Vec3 u{q1[0] - q0[0], q1[1] - q0[1], q1[2] - q0[2]}, v{q2[0] - q0[0], q2[1] - q0[1], q2[2] - q0[2]};
        piece_area = 0.5 * std::hypot(u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]);
      }
      const double area = piece_area / (m * m);
      const auto add = [&](double s, double r) {  // barycentric (1 - s - r, s, r) in the piece
        SurfaceSample3D o;
        o.triangle = t;
        o.normal = n;
        o.area = area;
        for (std::size_t d = 0; d < 3; ++d) o.point[d] = (1 - s - r) * q0[d] + s * q1[d] + r * q2[d];
        if (whole) {
          o.barycentric = {1 - s - r, s, r};
        } else {
          const Vec3 x{o.point[0] - a[0], o.point[1] - a[1], o.point[2] - a[2]};
          const double x1 = dot(x, e1), x2 = dot(x, e2);
          const double bs = (d22 * x1 - d12 * x2) / det, br = (d11 * x2 - d12 * x1) / det;
          o.barycentric = {1 - bs - br, bs, br};
        }
        o.probe = 0;
        for (int d = 0; d < 3; ++d) o.probe = std::max(o.probe, grid.axis(d).width_at(o.point[static_cast<std::size_t>(d)]));
        samples_.push_back(o);
      };
      // Centroids of the m^2 sub-triangles: m(m+1)/2 upright, m(m-1)/2 inverted.
      for (int i = 0; i < m; ++i)
        for (int j = 0; i + j < m; ++j) {
          add((i + 1.0 / 3) / m, (j + 1.0 / 3) / m);
          if (i + j < m - 1) add((i + 2.0 / 3) / m, (j + 2.0 / 3) / m);
        }
    }
  }
  // The probes' stencils, the costly part (a least-squares fit each), one sample per item; over the
  // ranks of a whole-flow run each rank computes its share (rank_share.hpp).
  shared_for_each(samples_, [&](SurfaceSample3D& o) {
    const Vec3& n = o.normal;
    Vec3 p1, p2, b1 = o.point, b2 = o.point;
    for (std::size_t d = 0; d < 3; ++d) {
      p1[d] = o.point[d] + o.probe * n[d];
      p2[d] = o.point[d] + 2 * o.probe * n[d];
    }
    const double f1 = place(p1, b1), f2 = place(p2, b2);
    o.velocity1 = ghosts.stencil(p1, b1, n, BoundaryCondition::Dirichlet);
    o.velocity2 = ghosts.stencil(p2, b2, n, BoundaryCondition::Dirichlet);
    if (f1 != 1) o.velocity1 = scaled(o.velocity1, f1);
    if (f2 != 1) o.velocity2 = scaled(o.velocity2, f2);
    o.pressure1 = ghosts.stencil(p1, b1, n, BoundaryCondition::None);
    o.pressure2 = ghosts.stencil(p2, b2, n, BoundaryCondition::None);
  });
}

SurfaceForces SurfaceTraction3D::evaluate(const Field& u, const Field& v, const Field& w, const Field& p, double nu,
                                          double rho, const std::vector<Vec3>& vertex_velocity) const {
  SurfaceForces F;
  F.pressure.assign(static_cast<std::size_t>(triangles_), {0, 0, 0});
  F.viscous.assign(static_cast<std::size_t>(triangles_), {0, 0, 0});
  const double mu = rho * nu;
  const std::array<const Field*, 3> vel{&u, &v, &w};
  // Serial and in sample order (grouped by triangle): the sums are bitwise reproducible.
  for (const SurfaceSample3D& s : samples_) {
    Vec3 uw{};
    if (!vertex_velocity.empty()) {
      const auto& tri = tri_[static_cast<std::size_t>(s.triangle)];
      for (std::size_t k = 0; k < 3; ++k)
        for (std::size_t d = 0; d < 3; ++d) uw[d] += s.barycentric[k] * vertex_velocity[static_cast<std::size_t>(tri[k])][d];
    }
    const double pw = rho * (2 * s.pressure1.apply(p, 0.0) - s.pressure2.apply(p, 0.0));
    auto& fp = F.pressure[static_cast<std::size_t>(s.triangle)];
    auto& fv = F.viscous[static_cast<std::size_t>(s.triangle)];
    for (std::size_t c = 0; c < 3; ++c) {
      const double w1 = s.velocity1.apply(*vel[c], uw[c]) - uw[c], w2 = s.velocity2.apply(*vel[c], uw[c]) - uw[c];
      fp[c] += -pw * s.normal[c] * s.area;
      fv[c] += mu * (4 * w1 - w2) / (2 * s.probe) * s.area;
    }
  }
  for (int t = 0; t < triangles_; ++t)
    for (std::size_t c = 0; c < 3; ++c) {
      F.pressure_total[c] += F.pressure[static_cast<std::size_t>(t)][c];
      F.viscous_total[c] += F.viscous[static_cast<std::size_t>(t)][c];
    }
  for (std::size_t c = 0; c < 3; ++c) F.total[c] = F.pressure_total[c] + F.viscous_total[c];
  return F;
}

}  // namespace finverse::cfd
