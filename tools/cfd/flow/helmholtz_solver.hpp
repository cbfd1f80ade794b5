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

#include <functional>
#include <memory>
#include <optional>
#include <utility>

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

// A solver of the momentum system that takes the Jacobi-PCG's place: the MPI ranks' one
// (cfd/parallel/rank_momentum_system.hpp). It sees every operator HelmholtzSolver builds and leaves
// x as helmholtz_pcg does, ghosts included (filled from the initial guess).
class HelmholtzSystemSolver {
 public:
  virtual ~HelmholtzSystemSolver() = default;
  virtual void setup(const PoissonOperator& op, const FaceCoefficients& beta, const BoundaryConditions& bc) = 0;
  virtual HelmholtzStats solve(const PoissonOperator& op, double mass, double stiffness, const Field& b, Field& x,
                               double rtol, int max_iterations) = 0;
  // The lines of b that solve reads once set up (an MPI rank's block); empty: all of them.
  virtual std::optional<LineRange> lines_read() const { return std::nullopt; }
};

// The process's flow solvers take their momentum system solver from this factory once one is
// installed (FlowRanks under an MPI launcher); empty, the default: the threaded Jacobi-PCG.
using HelmholtzSystemFactory = std::function<std::shared_ptr<HelmholtzSystemSolver>()>;
void install_flow_momentum_system(HelmholtzSystemFactory factory);
std::shared_ptr<HelmholtzSystemSolver> make_flow_momentum_system();

class HelmholtzSolver {
 public:
  // Solve with `system` instead of the threaded Jacobi-PCG (null: that); takes effect at the next setup().
  void set_system_solver(std::shared_ptr<HelmholtzSystemSolver> system) { system_ = std::move(system); }
  void setup(const StretchedGrid& grid, const FaceCoefficients& beta, const BoundaryConditions& bc);

  const PoissonOperator& op() const { return op_; }

  // Solves (mass V + stiffness A) x = b to ||r|| <= rtol ||b||; x holds the initial guess.
  HelmholtzStats solve(double mass, double stiffness, const Field& b, Field& x, double rtol, int max_iterations);

  // The lines of b that solve() reads: all of them, or an MPI rank's block when the ranks solve
  // the system (its caller may leave the rest of b unset).
  LineRange rhs_lines() const;

  // out = (mass V + stiffness A) x; fills x's ghosts.
  void apply(double mass, double stiffness, Field& x, Field& out) const;

 private:
  PoissonOperator op_;
  HelmholtzWork work_;
  std::shared_ptr<HelmholtzSystemSolver> system_;
};

}  // namespace finverse::cfd
