// Derived fields for viewing the wake: the velocity gradient at cell centres, the vorticity
// omega = curl u, and the lambda_2 vortex criterion of Jeong & Hussain (1995, J. Fluid Mech. 285):
// lambda_2 is the middle eigenvalue of S^2 + W^2 (S, W the symmetric and antisymmetric parts of
// grad u); a vortex core is a connected region with lambda_2 < 0.
//
// Derivatives are the three-point formula for unequal spacing on the stretched grid (second order
// at every centre, also where the cell width changes), one-sided (first order) where a neighbour
// lies outside the domain or in a solid (non-fluid) cell, so nothing inside an immersed body
// leaks into the fluid values. Solid cells themselves get zero.
#pragma once

#include <array>
#include <functional>
#include <vector>

#include "cfd/grid/field.hpp"
#include "cfd/grid/stretched_grid.hpp"

namespace finverse::cfd {

// grad u at a cell centre: g[a][b] = d u_a / d x_b.
using VelocityGradient = std::array<std::array<double, 3>, 3>;

// fluid(i, j, k): whether the cell holds flow (empty function: every cell).
using FluidMask = std::function<bool(int, int, int)>;

VelocityGradient velocity_gradient(const StretchedGrid& grid, const std::array<const Field*, 3>& u, int i, int j,
                                   int k, const FluidMask& fluid);

// The middle eigenvalue of S^2 + W^2 for the gradient g.
double lambda2(const VelocityGradient& g);

// Per cell (x fastest, as FlowSolver::cell_output): vorticity [3 * cells] and lambda_2 [cells].
// u[2] may be null in 2-D.
struct VortexFields {
  std::vector<double> vorticity, lambda2;
};
VortexFields vortex_fields(const StretchedGrid& grid, const std::array<const Field*, 3>& u, const FluidMask& fluid);

}  // namespace finverse::cfd
