// Boundary values of the new time level t^{n+1}: Dirichlet velocities of walls and inlets (with
// their time ramps), the convective outlet advanced explicitly,
//     u_b^{n+1} = u_b^n - dt U_c (u_b^n - u_P^n) / (h_P / 2),   U_c = mean outflow speed,
// or with local_convection U_c = max(u_n, 0) on each face (Orlanski's local advection speed,
// frozen where the flow comes back in; dt U_c / (h / 2) = 2 CFL <= 1 at the solver's CFL 0.5),
// and the boundary face-normal velocities that enter continuity, with the outlet fluxes shifted
// uniformly so that the net flux through the boundary is zero: the pressure-correction Poisson
// problem with Neumann conditions is then compatible and the faces become exactly solenoidal.
// Only the faces of fluid cells count: where a body crosses a side (the wall of a pipe whose fluid
// is inside), the faces of its cells carry no flux.
#include <algorithm>
#include <cmath>
#include <string>

#include "cfd/flow/flow_solver.hpp"
#include "core/error.hpp"

namespace finverse::cfd {

namespace {
bool is_outlet(FlowBcType t) { return t == FlowBcType::ConvectiveOutlet || t == FlowBcType::ZeroGradientOutlet; }

// fn(i, j, k, m): cell (i,j,k) next to side s and m its face's number on the side.
template <class Fn>
void for_side(const StretchedGrid& g, Side s, Fn fn) {
  const int d = side_axis(s);
  const int at = side_is_high(s) ? g.n(d) - 1 : 0;
  std::size_t m = 0;
  if (d == 0) {
    for (int k = 0; k < g.nz(); ++k)
      for (int j = 0; j < g.ny(); ++j) fn(at, j, k, m++);
  } else if (d == 1) {
    for (int k = 0; k < g.nz(); ++k)
      for (int i = 0; i < g.nx(); ++i) fn(i, at, k, m++);
  } else {
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) fn(i, j, at, m++);
  }
}
}  // namespace

void FlowSolver::set_boundary_values(double t, double dt, bool initial) {
  const int D = dim();
  for (int s = 0; s < 2 * D; ++s) {
    const Side side = static_cast<Side>(s);
    const FlowSideBc& b = bnd_[side];
    const int a = side_axis(side);
    if (b.type == FlowBcType::Periodic) continue;
    const double wall = side_is_high(side) ? grid_.axis(a).hi() : grid_.axis(a).lo();
    // Mean outflow speed through the side at t^n (from the face velocities, which carry the flux).
    double uc = 0;
    if (b.type == FlowBcType::ConvectiveOutlet && !initial) {
      double q = 0, area = 0;
      const double sign = side_is_high(side) ? 1.0 : -1.0;
      for_side(grid_, side, [&](int i, int j, int k, std::size_t) {
        if (!fluid(i, j, k)) return;
        int f[3] = {i, j, k};
        if (side_is_high(side)) ++f[a];
        const double A = face_area(a, i, j, k);
        q += sign * U_(a, f[0], f[1], f[2]) * A;
        area += A;
      });
      uc = std::max(0.0, q / area);
    }
    for (int c = 0; c < D; ++c) {
      auto& v = bv_new_[static_cast<std::size_t>(c)][side];
      if (bnd_.component_type(side, c) == BcType::Neumann) {
        v.clear();
        continue;
      }
      v.assign(side_faces(grid_, side), 0.0);
      const Field& uc_field = u_[static_cast<std::size_t>(c)];
      const auto& old = bv_[static_cast<std::size_t>(c)][side];
      for_side(grid_, side, [&](int i, int j, int k, std::size_t m) {
        if (b.type == FlowBcType::ConvectiveOutlet) {
          const double up = uc_field(i, j, k);
          if (initial || old.size() != v.size()) {
            v[m] = up;
          } else {
            const double half = 0.5 * grid_.axis(a).width(a == 0 ? i : a == 1 ? j : k);
            double speed = uc;
            if (b.local_convection) {
              int f[3] = {i, j, k};
              if (side_is_high(side)) ++f[a];
              speed = std::max(0.0, (side_is_high(side) ? 1.0 : -1.0) * U_(a, f[0], f[1], f[2]));
            }
            v[m] = old[m] - dt * speed * (old[m] - up) / half;
          }
        } else {
          double x[3] = {grid_.xc(i), grid_.yc(j), grid_.zc(k)};
          x[a] = wall;
          v[m] = bnd_.velocity(grid_, side, x[0], x[1], x[2], t)[static_cast<std::size_t>(c)];
        }
      });
    }
  }

  // Boundary face-normal velocities and the global mass balance.
  double net = 0, outlet_area = 0, scale = 0;
  for (int s = 0; s < 2 * D; ++s) {
    const Side side = static_cast<Side>(s);
    const FlowSideBc& b = bnd_[side];
    if (b.type == FlowBcType::Periodic) continue;
    const int a = side_axis(side);
    const double sign = side_is_high(side) ? 1.0 : -1.0;
    auto& vn = bv_new_[static_cast<std::size_t>(a)][side];
    for_side(grid_, side, [&](int i, int j, int k, std::size_t m) {
      int f[3] = {i, j, k};
      if (side_is_high(side)) ++f[a];
      if (!fluid(i, j, k)) {  // a body crossing the side (a pipe's wall): no flux into solid cells
        Ustar_(a, f[0], f[1], f[2]) = 0;
        if (!vn.empty()) vn[m] = 0;
        return;
      }
      const double un = vn.empty() ? u_[static_cast<std::size_t>(a)](i, j, k) : vn[m];
      Ustar_(a, f[0], f[1], f[2]) = un;
      const double A = face_area(a, i, j, k);
      net += sign * un * A;
      scale += std::abs(un) * A;
      if (is_outlet(b.type)) outlet_area += A;
    });
  }
  if (outlet_area > 0) {
    const double shift = -net / outlet_area;  // added to the outward normal velocity
    for (int s = 0; s < 2 * D; ++s) {
      const Side side = static_cast<Side>(s);
      if (!is_outlet(bnd_[side].type)) continue;
      const int a = side_axis(side);
      const double sign = side_is_high(side) ? 1.0 : -1.0;
      auto& vn = bv_new_[static_cast<std::size_t>(a)][side];
      for_side(grid_, side, [&](int i, int j, int k, std::size_t m) {
        if (!fluid(i, j, k)) return;
        int f[3] = {i, j, k};
        if (side_is_high(side)) ++f[a];
        Ustar_(a, f[0], f[1], f[2]) += sign * shift;
        if (!vn.empty()) vn[m] += sign * shift;
      });
    }
  } else if (std::abs(net) > 1e-12 * std::max(scale, 1e-300) && std::abs(net) > 1e-14) {
    throw Error("flow boundary: net boundary inflow " + std::to_string(-net) +
                " m^3/s (per unit depth in 2-D) into a domain without an outlet");
  }
}

}  // namespace finverse::cfd
