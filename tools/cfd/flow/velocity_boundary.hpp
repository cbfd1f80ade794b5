// Velocity boundary conditions of the Navier-Stokes solver on the six sides of the box, and what
// they imply for each discrete sub-problem of the fractional step:
//   - the momentum (Helmholtz) problem of each velocity component: Dirichlet or Neumann per side;
//   - the pressure-correction Poisson problem: homogeneous Neumann on every non-periodic side,
//     because the boundary face fluxes are prescribed (Zang, Street & Koseff 1994), so the
//     correction must not change them;
//   - the boundary face-normal velocities that enter continuity.
//
// Kinds: periodic (in pairs); no-slip wall (optionally moving tangentially); slip wall (zero normal
// velocity, zero tangential stress); velocity inlet (uniform or parabolic profile along the
// non-periodic transverse axes, or any function, optionally ramped in time by (1 - cos(pi t/T))/2
// for t < T as in Turek & Hron 2006); outlet, zero-gradient or convective
// du/dt + U_c du/dn = 0 (Orlanski-type with the mean outflow speed U_c), whose net flux is corrected
// every step so that the discrete domain conserves mass exactly.
#pragma once

#include <array>
#include <functional>

#include "cfd/poisson/poisson_boundary.hpp"
#include "cfd/grid/stretched_grid.hpp"

namespace finverse::cfd {

enum class FlowBcType { Periodic, NoSlip, Slip, Inlet, ConvectiveOutlet, ZeroGradientOutlet };
enum class InletProfile { Uniform, Parabolic, Function };

using VelocityFunction = std::function<std::array<double, 3>(double x, double y, double z, double t)>;

struct FlowSideBc {
  FlowBcType type = FlowBcType::NoSlip;
  // NoSlip: the wall's velocity (its normal component must be zero: the box does not move).
  std::array<double, 3> wall_velocity{0, 0, 0};
  // Inlet: profile shape; speed = the uniform speed, or the centreline (maximum) speed of the
  // parabola, directed into the domain along the side's normal.
  InletProfile profile = InletProfile::Uniform;
  double speed = 1.0;
  double ramp_time = 0.0;     // > 0: (1 - cos(pi t / ramp_time)) / 2 for t < ramp_time
  VelocityFunction function;  // InletProfile::Function (also used for moving walls in tests)
  // ConvectiveOutlet: advect with each face's own outflow speed max(u_n, 0) instead of the side's
  // mean. Jets that reach the outlet (a pipe junction's) at many times the mean speed would
  // otherwise meet a nearly frozen boundary value and reflect (boundary_update.cpp).
  bool local_convection = false;
};

struct FlowBoundary {
  std::array<FlowSideBc, 6> side;

  FlowSideBc& operator[](Side s) { return side[static_cast<std::size_t>(s)]; }
  const FlowSideBc& operator[](Side s) const { return side[static_cast<std::size_t>(s)]; }

  static FlowBoundary all_periodic() {
    FlowBoundary b;
    for (auto& s : b.side) s.type = FlowBcType::Periodic;
    return b;
  }
  bool periodic(int axis) const { return side[static_cast<std::size_t>(2 * axis)].type == FlowBcType::Periodic; }
  // Throws finverse::Error unless periodic sides pair up and the sides fit the grid's dimension.
  void validate(int dim) const;

  // Condition type of velocity component c on side s for the implicit momentum problem.
  BcType component_type(Side s, int c) const;
  // Pressure (and pressure-correction) conditions: periodic or homogeneous Neumann.
  BoundaryConditions pressure_conditions() const;

  // Velocity on the face (x, y, z) of side s at time t for the Dirichlet kinds (wall, slip normal
  // component, inlet). Outlets are handled by the solver (they carry state).
  std::array<double, 3> velocity(const StretchedGrid& grid, Side s, double x, double y, double z, double t) const;
};

}  // namespace finverse::cfd
