// Velocity boundary conditions and their mapping onto the sub-problems; see velocity_boundary.hpp.
#include "cfd/flow/velocity_boundary.hpp"

#include <cmath>
#include <numbers>
#include <string>

#include "core/error.hpp"

namespace finverse::cfd {

namespace {
const char* side_name(int s) {
  static const char* names[] = {"x-low", "x-high", "y-low", "y-high", "z-low", "z-high"};
  return names[s];
}
}  // namespace

void FlowBoundary::validate(int dim) const {
  for (int d = 0; d < dim; ++d) {
    const bool lo = side[static_cast<std::size_t>(2 * d)].type == FlowBcType::Periodic;
    const bool hi = side[static_cast<std::size_t>(2 * d + 1)].type == FlowBcType::Periodic;
    if (lo != hi)
      throw Error(std::string("flow boundary: periodic ") + side_name(2 * d) + "/" + side_name(2 * d + 1) +
                  " sides must come in pairs");
  }
  for (int s = 0; s < 2 * dim; ++s) {
    const auto& b = side[static_cast<std::size_t>(s)];
    const int a = s / 2;
    if (b.type == FlowBcType::NoSlip && b.wall_velocity[static_cast<std::size_t>(a)] != 0)
      throw Error(std::string("flow boundary: ") + side_name(s) + " wall velocity must be tangential");
    if (b.type == FlowBcType::Inlet && b.profile == InletProfile::Function && !b.function)
      throw Error(std::string("flow boundary: ") + side_name(s) + " inlet profile function missing");
    if (b.ramp_time < 0) throw Error(std::string("flow boundary: ") + side_name(s) + " ramp time must be >= 0");
  }
}

BcType FlowBoundary::component_type(Side s, int c) const {
  const auto& b = (*this)[s];
  switch (b.type) {
    case FlowBcType::Periodic: return BcType::Periodic;
    case FlowBcType::Slip: return c == side_axis(s) ? BcType::Dirichlet : BcType::Neumann;
    case FlowBcType::ZeroGradientOutlet: return BcType::Neumann;
    // The convective outlet's boundary value is advanced explicitly and then imposed.
    default: return BcType::Dirichlet;
  }
}

BoundaryConditions FlowBoundary::pressure_conditions() const {
  BoundaryConditions bc;
  for (int s = 0; s < 6; ++s)
    bc.type[static_cast<std::size_t>(s)] =
        side[static_cast<std::size_t>(s)].type == FlowBcType::Periodic ? BcType::Periodic : BcType::Neumann;
  return bc;
}

std::array<double, 3> FlowBoundary::velocity(const StretchedGrid& g, Side s, double x, double y, double z,
                                             double t) const {
  const auto& b = (*this)[s];
  std::array<double, 3> v{0, 0, 0};
  if (b.type == FlowBcType::NoSlip) return b.wall_velocity;
  if (b.type != FlowBcType::Inlet) return v;
  if (b.profile == InletProfile::Function) {
    v = b.function(x, y, z, t);
  } else {
    const int a = side_axis(s);
    double shape = 1;
    if (b.profile == InletProfile::Parabolic) {
      const double xyz[3] = {x, y, z};
      for (int d = 0; d < g.dim(); ++d) {
        if (d == a || periodic(d)) continue;
        const double lo = g.axis(d).lo(), h = g.axis(d).length();
        const double e = xyz[d] - lo;
        shape *= 4 * e * (h - e) / (h * h);
      }
    }
    v[static_cast<std::size_t>(a)] = (side_is_high(s) ? -1.0 : 1.0) * b.speed * shape;
  }
  if (b.ramp_time > 0 && t < b.ramp_time) {
    const double r = 0.5 * (1 - std::cos(std::numbers::pi * t / b.ramp_time));
    for (auto& c : v) c *= r;
  }
  return v;
}

}  // namespace finverse::cfd
