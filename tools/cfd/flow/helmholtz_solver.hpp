// Implicit (Crank-Nicolson) diffusion solve of one velocity component:
//
//     (V/dt + nu/2 A) u* = b,     A = -(integrated Laplacian), the finite-volume operator of
//                                 poisson_operator.hpp with the component's own boundary types,
//
// solved by conjugate gradients preconditioned with the diagonal (Jacobi-PCG).
//
// Why not multigrid or ADI: the V/dt term makes the system diagonally dominant (condition number
// about 1 + 8 nu dt / h^2 in 2-D), so Jacobi-PCG needs O(sqrt(nu dt / h^2)) iterations, few at the
// time steps explicit convection allows; unlike ADI it adds no factorisation error, and it works
// unchanged on periodic, stretched and masked grids with deterministic reductions. Iteration
// counts measured: docs/studies/momentum_solver.md.
#pragma once

#include "cfd/poisson/poisson_boundary.hpp"
#include "cfd/poisson/face_coefficients.hpp"
#include "cfd/grid/field.hpp"
#include "cfd/poisson/poisson_operator.hpp"

namespace finverse::cfd {

struct HelmholtzStats {
  int iterations = 0;
  double relative_residual = 0;
  bool converged = false;
};

// Work vectors of helmholtz_pcg.hpp: residual, preconditioned residual, direction, A d.
struct HelmholtzWork {
  Field r, z, d, q;
};

class HelmholtzSolver {
 public:
  void setup(const StretchedGrid& grid, const FaceCoefficients& beta, const BoundaryConditions& bc);

  const PoissonOperator& op() const { return op_; }

  // Solves (mass V + stiffness A) x = b to ||r|| <= rtol ||b||; x holds the initial guess.
  HelmholtzStats solve(double mass, double stiffness, const Field& b, Field& x, double rtol, int max_iterations);

  // out = (mass V + stiffness A) x; fills x's ghosts.
  void apply(double mass, double stiffness, Field& x, Field& out) const;

 private:
  PoissonOperator op_;
  HelmholtzWork work_;
};

}  // namespace finverse::cfd
