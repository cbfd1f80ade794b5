// Prescribed rigid motion of an immersed 2-D body (issue 4, moving sharp-interface boundaries;
// Mittal et al. 2008, J. Comput. Phys. 227:4825, section 2.4): a translation d(t) of a reference
// point (the pivot) and a rotation theta(t) about it. A body point x_ref of the reference
// configuration (t where d = 0, theta = 0) sits at
//     x(t) = c(t) + R(theta) (x_ref - pivot),     c(t) = pivot + d(t),
// and the rigid-body velocity and acceleration fields are
//     u_B(x) = U + Omega x r,    a_B(x) = A + dOmega/dt x r - Omega^2 r,     r = x - c(t),
// which give the no-slip datum of a ghost cell at its boundary intercept, and the pressure's
// Neumann datum dp/dn = -a_B . n (kinematic pressure; the normal momentum balance at a no-slip
// wall, neglecting the viscous term nu n . lap u, which is O(nu) and small at moderate Re).
#pragma once

#include <array>
#include <cmath>
#include <functional>
#include <vector>

#include "cfd/immersed/immersed_polygon.hpp"

namespace finverse::cfd {

struct RigidState {
  std::array<double, 2> displacement{}, velocity{}, acceleration{};  // of the pivot
  double angle = 0, angular_velocity = 0, angular_acceleration = 0;  // counter-clockwise [rad]
};

using RigidMotion = std::function<RigidState(double t)>;

struct MovingBody {
  Polygon reference;
  std::array<double, 2> pivot{};
  RigidMotion motion;

  std::array<double, 2> centre(const RigidState& s) const {
    return {pivot[0] + s.displacement[0], pivot[1] + s.displacement[1]};
  }
  Polygon placed(const RigidState& s) const {
    const double c = std::cos(s.angle), sn = std::sin(s.angle);
    const auto o = centre(s);
    std::vector<std::array<double, 2>> v;
    v.reserve(reference.vertices().size());
    for (const auto& p : reference.vertices()) {
      const double rx = p[0] - pivot[0], ry = p[1] - pivot[1];
      v.push_back({o[0] + c * rx - sn * ry, o[1] + sn * rx + c * ry});
    }
    return Polygon(std::move(v));
  }
  std::array<double, 2> velocity(const RigidState& s, double x, double y) const {
    const auto o = centre(s);
    return {s.velocity[0] - s.angular_velocity * (y - o[1]), s.velocity[1] + s.angular_velocity * (x - o[0])};
  }
  std::array<double, 2> acceleration(const RigidState& s, double x, double y) const {
    const auto o = centre(s);
    const double rx = x - o[0], ry = y - o[1], w2 = s.angular_velocity * s.angular_velocity;
    return {s.acceleration[0] - s.angular_acceleration * ry - w2 * rx,
            s.acceleration[1] + s.angular_acceleration * rx - w2 * ry};
  }
};

}  // namespace finverse::cfd
