// Normal pressure gradient on a wall at rest from the wall vorticity, 3-D; see
// wall_pressure_gradient_3d.hpp.
#include "cfd/forces/wall_pressure_gradient_3d.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "cfd/immersed/vec3.hpp"
#include "core/error.hpp"

namespace finverse::cfd {

namespace {
double local_width(const StretchedGrid& g, const Vec3& x) {
  return std::max({g.axis(0).width_at(x[0]), g.axis(1).width_at(x[1]), g.axis(2).width_at(x[2])});
}
}  // namespace

WallPressureGradient3D::WallPressureGradient3D(const StretchedGrid& grid, const GhostCellSet& ghosts,
                                               const SurfaceGeometry& body) {
  if (grid.dim() != 3) throw Error("wall pressure gradient: the 3-D form needs a 3-D grid");
  // As in 2-D (wall_pressure_gradient.cpp): K points spaced D cells on each side of B along each
  // tangent, normals within ~25 degrees of B's, so a body resolved by fewer than about 14 cells per
  // radius keeps dp/dn = 0 (the sphere of sphere_re100 at D/20 and DFG 3D-1Z's cylinder at D/12).
  // Narrower windows that reached them were tried and dropped (docs/studies/wall_momentum_balance.md).
  constexpr double kSmooth = 0.906;
  constexpr int K = 3;
  constexpr double D = 2.0;
  const auto wall_point = [&](const SurfaceHit& s) {
    WallPoint p;
    p.normal = s.normal;
    p.probe = local_width(grid, s.point);
    Vec3 p1, p2;
    for (std::size_t d = 0; d < 3; ++d) {
      p1[d] = s.point[d] + p.probe * s.normal[d];
      p2[d] = s.point[d] + 2 * p.probe * s.normal[d];
    }
    p.near = ghosts.stencil(p1, s.point, s.normal, BoundaryCondition::Dirichlet);
    p.far = ghosts.stencil(p2, s.point, s.normal, BoundaryCondition::Dirichlet);
    return p;
  };
  const std::array<Vec3, 3> axes{Vec3{1, 0, 0}, Vec3{0, 1, 0}, Vec3{0, 0, 1}};
  entries_.resize(ghosts.ghosts().size());
  std::size_t at = 0;
  for (const GhostCell& g : ghosts.ghosts()) {
    Entry& e = entries_[at++];
    const Vec3& b = g.intercept;
    const Vec3& n = g.normal;
    // t1 across the axis least aligned with n, t2 = n x t1.
    std::size_t least = 0;
    for (std::size_t d = 1; d < 3; ++d)
      if (std::abs(n[d]) < std::abs(n[least])) least = d;
    const Vec3 t1 = unit(cross(n, axes[least])), t2 = cross(n, t1);
    const double h = D * local_width(grid, b);
    std::vector<WallPoint> points;
    std::vector<std::array<double, 2>> s;
    bool usable = true;
    for (int a = 0; a < 2 && usable; ++a)
      for (int k = -K; k <= K && usable; ++k) {
        if (k == 0) continue;
        const Vec3& t = a == 0 ? t1 : t2;
        const SurfaceHit q = body.closest({b[0] + k * h * t[0], b[1] + k * h * t[1], b[2] + k * h * t[2]});
        if (dot(q.normal, n) <= kSmooth) {
          usable = false;
          break;
        }
        try {
          points.push_back(wall_point(q));
        } catch (const Error&) {  // a probe outside the grid's cell centres
          usable = false;
          break;
        }
        const Vec3 r{q.point[0] - b[0], q.point[1] - b[1], q.point[2] - b[2]};
        s.push_back({dot(r, t1), dot(r, t2)});
      }
    if (!usable) continue;
    // Least squares omega ~ c + s1 a1 + s2 a2: the slopes' weights are rows 1 and 2 of
    // (X^T X)^-1 X^T, X = [1 s1 s2].
    const auto m = static_cast<Eigen::Index>(s.size());
    Eigen::MatrixXd X(m, 3);
    for (Eigen::Index r = 0; r < m; ++r) {
      X(r, 0) = 1;
      X(r, 1) = s[static_cast<std::size_t>(r)][0];
      X(r, 2) = s[static_cast<std::size_t>(r)][1];
    }
    const Eigen::Matrix3d N = X.transpose() * X;
    const Eigen::FullPivLU<Eigen::Matrix3d> lu(N);
    if (!lu.isInvertible()) continue;
    const Eigen::MatrixXd W = lu.inverse() * X.transpose();
    e.points = std::move(points);
    e.w1.resize(s.size());
    e.w2.resize(s.size());
    for (Eigen::Index r = 0; r < m; ++r) {
      e.w1[static_cast<std::size_t>(r)] = W(1, r);
      e.w2[static_cast<std::size_t>(r)] = W(2, r);
    }
    e.n = n;
    e.t1 = t1;
    e.t2 = t2;
  }
}

std::size_t WallPressureGradient3D::active() const {
  return static_cast<std::size_t>(
      std::count_if(entries_.begin(), entries_.end(), [](const Entry& e) { return !e.points.empty(); }));
}

// omega = n x du/dn with the one-sided second-order derivative of the no-slip wall.
Vec3 WallPressureGradient3D::vorticity(const WallPoint& p, const Field& u, const Field& v, const Field& w) const {
  const Field* c[3] = {&u, &v, &w};
  Vec3 dudn;
  for (std::size_t d = 0; d < 3; ++d)
    dudn[d] = (4 * p.near.apply(*c[d], 0.0) - p.far.apply(*c[d], 0.0)) / (2 * p.probe);
  return cross(p.normal, dudn);
}

std::vector<double> WallPressureGradient3D::evaluate(const Field& u, const Field& v, const Field& w, double nu) const {
  std::vector<double> g(entries_.size(), 0.0);
  const long count = static_cast<long>(entries_.size());
#pragma omp parallel for schedule(static) if (count >= 256)
  for (long q = 0; q < count; ++q) {
    const Entry& e = entries_[static_cast<std::size_t>(q)];
    if (e.points.empty()) continue;
    Vec3 a1{0, 0, 0}, a2{0, 0, 0};
    for (std::size_t k = 0; k < e.points.size(); ++k) {
      const Vec3 om = vorticity(e.points[k], u, v, w);
      for (std::size_t d = 0; d < 3; ++d) {
        a1[d] += e.w1[k] * om[d];
        a2[d] += e.w2[k] * om[d];
      }
    }
    const Vec3 c1 = cross(e.t1, a1), c2 = cross(e.t2, a2);
    g[static_cast<std::size_t>(q)] = -nu * (dot(e.n, c1) + dot(e.n, c2));
  }
  return g;
}

}  // namespace finverse::cfd
