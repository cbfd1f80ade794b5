// Surface traction and per-triangle forces on an immersed triangulated body; see
// surface_traction_3d.hpp.
#include "cfd/surface_traction_3d.hpp"

#include <algorithm>
#include <cmath>

namespace finverse::cfd {

namespace {
// Width of the cell containing coordinate x along axis a (clamped to the axis).
double width_at(const Axis& a, double x) {
  const auto& f = a.faces();
  const auto it = std::upper_bound(f.begin(), f.end(), x);
  const int c = std::clamp(static_cast<int>(it - f.begin()) - 1, 0, a.size() - 1);
  return a.width(c);
}
}  // namespace

SurfaceTraction3D::SurfaceTraction3D(const StretchedGrid& grid, const GhostCellSet& ghosts, const SurfaceGeometry& body)
    : triangles_(body.triangles()), tri_(body.surface().triangles) {
  const auto& P = body.surface().points;
  for (int t = 0; t < triangles_; ++t) {
    const auto& tri = tri_[static_cast<std::size_t>(t)];
    const Vec3& a = P[static_cast<std::size_t>(tri[0])];
    const Vec3& b = P[static_cast<std::size_t>(tri[1])];
    const Vec3& c = P[static_cast<std::size_t>(tri[2])];
    Vec3 centroid{};
    double longest = 0;
    for (std::size_t d = 0; d < 3; ++d) centroid[d] = (a[d] + b[d] + c[d]) / 3;
    for (const auto& [p, q] : {std::pair{&a, &b}, std::pair{&b, &c}, std::pair{&c, &a}})
      longest = std::max(longest, std::hypot((*q)[0] - (*p)[0], (*q)[1] - (*p)[1], (*q)[2] - (*p)[2]));
    double hmin = 1e300;
    for (int d = 0; d < 3; ++d) hmin = std::min(hmin, width_at(grid.axis(d), centroid[static_cast<std::size_t>(d)]));
    const int m = std::clamp(static_cast<int>(std::ceil(longest / (0.5 * hmin))), 1, 64);
    const Vec3& n = body.triangle_normal(t);
    const double area = body.triangle_area(t) / (m * m);
    const auto add = [&](double s, double r) {  // barycentric (1 - s - r, s, r)
      SurfaceSample3D o;
      o.triangle = t;
      o.normal = n;
      o.area = area;
      o.barycentric = {1 - s - r, s, r};
      for (std::size_t d = 0; d < 3; ++d) o.point[d] = (1 - s - r) * a[d] + s * b[d] + r * c[d];
      o.probe = 0;
      for (int d = 0; d < 3; ++d) o.probe = std::max(o.probe, width_at(grid.axis(d), o.point[static_cast<std::size_t>(d)]));
      Vec3 p1, p2;
      for (std::size_t d = 0; d < 3; ++d) {
        p1[d] = o.point[d] + o.probe * n[d];
        p2[d] = o.point[d] + 2 * o.probe * n[d];
      }
      o.velocity1 = ghosts.stencil(p1, o.point, n, BoundaryCondition::Dirichlet);
      o.velocity2 = ghosts.stencil(p2, o.point, n, BoundaryCondition::Dirichlet);
      o.pressure1 = ghosts.stencil(p1, o.point, n, BoundaryCondition::None);
      o.pressure2 = ghosts.stencil(p2, o.point, n, BoundaryCondition::None);
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
