// The Crank-Nicolson momentum systems over MPI ranks (issue 48, deliverable 2; flow_mpi.md):
// HelmholtzSolver's Jacobi-PCG (helmholtz_pcg.hpp) with the operator on the rank's block
// (DistributedPoisson) and DistributedGrid's reductions. The iterates and the solution are the
// threaded solver's bit for bit, for any rank count.
#pragma once

#include "cfd/flow/helmholtz_solver.hpp"
#include "cfd/parallel/distributed_poisson.hpp"

namespace finverse::cfd {

class DistributedHelmholtz {
 public:
  // Collective. beta on the rank's block faces (block_faces), bc the component's whole-domain types.
  DistributedHelmholtz(const DistributedGrid& grid, const StretchedGrid& whole, FaceCoefficients beta,
                       const BoundaryConditions& bc);

  // Collective: (mass V + stiffness A) x = b to ||r|| <= rtol ||b|| (HelmholtzSolver::solve).
  HelmholtzStats solve(double mass, double stiffness, const Field& b, Field& x, double rtol, int max_iterations);
  // Collective: out = (mass V + stiffness A) x; refreshes x's ghosts.
  void apply(double mass, double stiffness, Field& x, Field& out) const;
  const DistributedPoisson& op() const { return op_; }

 private:
  const DistributedGrid& grid_;
  DistributedPoisson op_;
  HelmholtzWork work_;
};

}  // namespace finverse::cfd
