// The pressure Poisson solve over MPI ranks (issue 48; docs/studies/flow_mpi.md): PoissonSolver's
// MG-PCG or cycles (mg_pcg.hpp) with the block operator, the distributed multigrid, the bitwise
// reductions and the components across ranks. Where every component touches a Dirichlet face
// (the flow's usual case) iterates and solution are the serial ones bit for bit; on one singular
// component too, whose projections both sum each x line and then the lines in the global order.
// Several singular components are refused.
#pragma once

#include <functional>
#include <memory>

#include "cfd/parallel/distributed_components.hpp"
#include "cfd/parallel/distributed_grid.hpp"
#include "cfd/parallel/distributed_multigrid.hpp"
#include "cfd/parallel/distributed_poisson.hpp"
#include "cfd/poisson/poisson_solver.hpp"

namespace finverse::cfd {

class DistributedPoissonSolver {
 public:
  // beta on a rank's block faces (the block's grid and lines given); each rank computes its own.
  using BlockBeta = std::function<FaceCoefficients(const StretchedGrid& block_grid, const Block& block)>;

  // Collective. Splits `whole` over comm's ranks (the multigrid's split) and builds every level.
  DistributedPoissonSolver(MPI_Comm comm, const StretchedGrid& whole, const BlockBeta& beta, const BoundaryConditions& bc,
                           const PoissonSolverOptions& options = {});
  ~DistributedPoissonSolver();

  const DistributedGrid& grid() const { return *grid_; }
  const DistributedPoisson& op() const { return *op_; }
  const DistributedMultigrid& multigrid() const { return *mg_; }
  const DistributedComponents& components() const { return *components_; }

  // Collective: A x = b on the blocks (b made compatible in place), as PoissonSolver::solve_system.
  PoissonSolveStats solve_system(Field& b, Field& x);

  // The null-space projections (PoissonOperator's, over the ranks' blocks).
  void remove_mean(Field& r) const;
  void make_compatible(Field& b) const;
  void remove_volume_mean(Field& p) const;

 private:
  // Sum over the singular component's cells of w x (x null: of w), w the volume or 1, line by
  // line in the global order.
  double singular_sum(const Field* x, bool volume_weight) const;
  void shift_singular(Field& f, double shift, bool volume_weight) const;

  PoissonSolverOptions options_;
  StretchedGrid whole_;
  WholeHierarchy hierarchy_;
  std::unique_ptr<DistributedGrid> grid_;
  std::unique_ptr<DistributedPoisson> op_;
  std::unique_ptr<DistributedMultigrid> mg_;
  std::unique_ptr<DistributedComponents> components_;
  long long active_cells_ = 0, cells_ = 0;  // the whole grid's
  double singular_volume_ = 0;              // the singular component's volume, the whole grid's
  SolveWork work_;
};

}  // namespace finverse::cfd
