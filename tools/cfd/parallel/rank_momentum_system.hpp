// The Crank-Nicolson momentum systems of a whole-flow run solved over MPI ranks (issue 48;
// docs/studies/flow_mpi.md, "The momentum solves on ranks"), as RankPressureSystem does for the
// pressure: every rank holds the whole velocity, takes its block of b and x, DistributedHelmholtz
// runs the threaded Jacobi-PCG's iterations bit for bit, and the solution is gathered onto every
// rank. x's ghosts are filled from the initial guess first, where the threaded solve's first
// product fills them. A flow with a closed body solves its momentum with the ghost cells' rows
// (immersed_momentum_solver.hpp) and does not come here.
#pragma once

#include <mpi.h>

#include <memory>
#include <optional>

#include "cfd/flow/helmholtz_solver.hpp"
#include "cfd/parallel/distributed_helmholtz.hpp"

namespace finverse::cfd {

class RankMomentumSystem : public HelmholtzSystemSolver {
 public:
  explicit RankMomentumSystem(MPI_Comm comm) : comm_(comm) {}

  // Collective: the ranks' solver for the whole operator `op` (each rank's block of beta).
  void setup(const PoissonOperator& op, const FaceCoefficients& beta, const BoundaryConditions& bc) override;
  // Collective: b and x whole on every rank, x the solution on every rank on return.
  HelmholtzStats solve(const PoissonOperator& op, double mass, double stiffness, const Field& b, Field& x, double rtol,
                       int max_iterations) override;

  // This rank's block: the lines of b that solve reads.
  std::optional<LineRange> lines_read() const override;

 private:
  MPI_Comm comm_;
  std::unique_ptr<DistributedGrid> grid_;
  std::unique_ptr<DistributedHelmholtz> solver_;
  Field b_, x_;  // this rank's block
};

}  // namespace finverse::cfd
