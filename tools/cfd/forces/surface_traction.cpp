// Surface traction and force on an immersed body at rest; see surface_traction.hpp.
#include "cfd/forces/surface_traction.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include "core/error.hpp"

namespace finverse::cfd {

SurfaceTraction::SurfaceTraction(const StretchedGrid& grid, const GhostCellSet& ghosts, const Polygon& body,
                                 WallExtrapolation extrapolation)
    : grid_(grid), ghosts_(&ghosts), body_(body), extrapolation_(extrapolation) {
  const auto& v = body_.vertices();
  for (std::size_t e = 0; e < v.size(); ++e) {
    const auto& a = v[e];
    const auto& b = v[(e + 1) % v.size()];
    const double ex = b[0] - a[0], ey = b[1] - a[1], len = std::hypot(ex, ey);
    const double mx = 0.5 * (a[0] + b[0]), my = 0.5 * (a[1] + b[1]);
    const double h = std::min(grid.axis(0).width_at(mx), grid.axis(1).width_at(my));
    const int m = std::max(1, static_cast<int>(std::ceil(len / (0.5 * h))));
    SurfacePoint s;
    s.normal = {ey / len, -ex / len};  // outward (counter-clockwise polygon)
    for (int q = 0; q < m; ++q) {
      const double t = (q + 0.5) / m;
      s.point = {a[0] + t * ex, a[1] + t * ey};
      samples_.push_back(sample(s.point[0], s.point[1], s, len / m));
      samples_.back().edge = static_cast<int>(e);
      samples_.back().edge_t = t;
    }
  }
}

SurfaceSample SurfaceTraction::sample(double x, double y, const SurfacePoint& s, double ds) const {
  SurfaceSample o;
  o.point = {x, y};
  o.normal = s.normal;
  o.ds = ds;
  o.probe = std::max(grid_.axis(0).width_at(x), grid_.axis(1).width_at(y));
  const std::array<double, 2> p1{x + o.probe * s.normal[0], y + o.probe * s.normal[1]};
  const std::array<double, 2> p2{x + 2 * o.probe * s.normal[0], y + 2 * o.probe * s.normal[1]};
  o.velocity1 = ghosts_->stencil(p1, s, BoundaryCondition::Dirichlet);
  o.velocity2 = ghosts_->stencil(p2, s, BoundaryCondition::Dirichlet);
  o.pressure1 = ghosts_->stencil(p1, s, BoundaryCondition::None);
  o.pressure2 = ghosts_->stencil(p2, s, BoundaryCondition::None);
  if (extrapolation_ == WallExtrapolation::Quadratic) {
    const std::array<double, 2> p3{x + 3 * o.probe * s.normal[0], y + 3 * o.probe * s.normal[1]};
    o.velocity3 = ghosts_->stencil(p3, s, BoundaryCondition::Dirichlet);
    o.pressure3 = ghosts_->stencil(p3, s, BoundaryCondition::None);
  }
  return o;
}

// The polynomial through the wall and the probes, evaluated (differentiated) at the wall.
double SurfaceTraction::wall_value(double q1, double q2, double q3) const {
  if (extrapolation_ == WallExtrapolation::Linear) return 2 * q1 - q2;
  return 3 * q1 - 3 * q2 + q3;
}

double SurfaceTraction::wall_derivative(double w1, double w2, double w3, double d) const {
  if (extrapolation_ == WallExtrapolation::Linear) return (4 * w1 - w2) / (2 * d);
  return (18 * w1 - 9 * w2 + 2 * w3) / (6 * d);
}

SurfaceLoads SurfaceTraction::evaluate(const Field& u, const Field& v, const Field& p, double nu, double rho) const {
  return evaluate(u, v, p, nu, rho, {});
}

SurfaceLoads SurfaceTraction::evaluate(const Field& u, const Field& v, const Field& p, double nu, double rho,
                                       const std::function<std::array<double, 2>(double, double)>& wall_velocity) const {
  const auto body = [&](double x, double y) {
    return wall_velocity ? wall_velocity(x, y) : std::array<double, 2>{0.0, 0.0};
  };
  SurfaceLoads L;
  L.pressure.resize(samples_.size());
  L.traction.resize(samples_.size());
  const bool third = extrapolation_ == WallExtrapolation::Quadratic;
  // Serial and in sample order: the sums are bitwise reproducible.
  for (std::size_t n = 0; n < samples_.size(); ++n) {
    const SurfaceSample& s = samples_[n];
    const double pw =
        rho * wall_value(s.pressure1.apply(p, 0.0), s.pressure2.apply(p, 0.0), third ? s.pressure3.apply(p, 0.0) : 0.0);
    const double mu = rho * nu;
    const auto uw = body(s.point[0], s.point[1]);
    const auto b1 = body(s.point[0] + s.probe * s.normal[0], s.point[1] + s.probe * s.normal[1]);
    const auto b2 = body(s.point[0] + 2 * s.probe * s.normal[0], s.point[1] + 2 * s.probe * s.normal[1]);
    const auto b3 = third ? body(s.point[0] + 3 * s.probe * s.normal[0], s.point[1] + 3 * s.probe * s.normal[1])
                          : std::array<double, 2>{0.0, 0.0};
    // Velocity relative to the body's rigid field at each probe: zero on the wall.
    const auto relative = [&](const Field& q, int c) {
      const auto C = static_cast<std::size_t>(c);
      return std::array<double, 3>{s.velocity1.apply(q, uw[C]) - b1[C], s.velocity2.apply(q, uw[C]) - b2[C],
                                   third ? s.velocity3.apply(q, uw[C]) - b3[C] : 0.0};
    };
    const auto wu = relative(u, 0), wv = relative(v, 1);
    const double dudn = wall_derivative(wu[0], wu[1], wu[2], s.probe);
    const double dvdn = wall_derivative(wv[0], wv[1], wv[2], s.probe);
    const std::array<double, 2> tp{-pw * s.normal[0], -pw * s.normal[1]}, tv{mu * dudn, mu * dvdn};
    L.pressure[n] = pw;
    L.traction[n] = {tp[0] + tv[0], tp[1] + tv[1]};
    for (int c = 0; c < 2; ++c) {
      const auto C = static_cast<std::size_t>(c);
      L.pressure_force[C] += tp[C] * s.ds;
      L.viscous_force[C] += tv[C] * s.ds;
    }
  }
  for (int c = 0; c < 2; ++c)
    L.force[static_cast<std::size_t>(c)] = L.pressure_force[static_cast<std::size_t>(c)] + L.viscous_force[static_cast<std::size_t>(c)];
  return L;
}

SurfaceLoads SurfaceTraction::evaluate_deforming(const Field& u, const Field& v, const Field& p, double nu, double rho,
                                                 const std::vector<std::array<double, 2>>& vertex_velocity) const {
  const auto& vs = body_.vertices();
  if (vertex_velocity.size() != vs.size())
    throw Error("surface traction: need one wall velocity per polygon vertex (" + std::to_string(vs.size()) + "), got " +
                std::to_string(vertex_velocity.size()));
  SurfaceLoads L;
  L.pressure.resize(samples_.size());
  L.traction.resize(samples_.size());
  const bool third = extrapolation_ == WallExtrapolation::Quadratic;
  const double mu = rho * nu;
  for (std::size_t n = 0; n < samples_.size(); ++n) {
    const SurfaceSample& s = samples_[n];
    const auto e = static_cast<std::size_t>(s.edge);
    const auto& va = vertex_velocity[e];
    const auto& vb = vertex_velocity[(e + 1) % vs.size()];
    const auto& a = vs[e];
    const auto& b = vs[(e + 1) % vs.size()];
    const double len = std::hypot(b[0] - a[0], b[1] - a[1]);
    const std::array<double, 2> uw{va[0] + s.edge_t * (vb[0] - va[0]), va[1] + s.edge_t * (vb[1] - va[1])};
    const std::array<double, 2> g{(vb[0] - va[0]) / len, (vb[1] - va[1]) / len};  // du_w/ds
    const std::array<double, 2> t{-s.normal[1], s.normal[0]};
    const double pw =
        rho * wall_value(s.pressure1.apply(p, 0.0), s.pressure2.apply(p, 0.0), third ? s.pressure3.apply(p, 0.0) : 0.0);
    const auto dn = [&](const Field& q, int c) {
      const auto C = static_cast<std::size_t>(c);
      return wall_derivative(s.velocity1.apply(q, uw[C]) - uw[C], s.velocity2.apply(q, uw[C]) - uw[C],
                             third ? s.velocity3.apply(q, uw[C]) - uw[C] : 0.0, s.probe);
    };
    const double gn = g[0] * s.normal[0] + g[1] * s.normal[1], gt = g[0] * t[0] + g[1] * t[1];
    const std::array<double, 2> tp{-pw * s.normal[0], -pw * s.normal[1]};
    const std::array<double, 2> tv{mu * (dn(u, 0) + gn * t[0] - gt * s.normal[0]),
                                   mu * (dn(v, 1) + gn * t[1] - gt * s.normal[1])};
    L.pressure[n] = pw;
    L.traction[n] = {tp[0] + tv[0], tp[1] + tv[1]};
    for (std::size_t c = 0; c < 2; ++c) {
      L.pressure_force[c] += tp[c] * s.ds;
      L.viscous_force[c] += tv[c] * s.ds;
    }
  }
  for (std::size_t c = 0; c < 2; ++c) L.force[c] = L.pressure_force[c] + L.viscous_force[c];
  return L;
}

double SurfaceTraction::wall_pressure(const Field& p, double x, double y) const {
  const SurfacePoint s = body_.closest(x, y);
  const SurfaceSample o = sample(s.point[0], s.point[1], s, 0.0);
  return wall_value(o.pressure1.apply(p, 0.0), o.pressure2.apply(p, 0.0),
                    extrapolation_ == WallExtrapolation::Quadratic ? o.pressure3.apply(p, 0.0) : 0.0);
}

}  // namespace finverse::cfd
