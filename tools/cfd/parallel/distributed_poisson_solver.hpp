// The pressure Poisson solve over MPI ranks: MG-PCG or multigrid cycles (poisson_solver.hpp) on
// the ranks' blocks (issue 48, deliverable 2; docs/studies/flow_mpi.md).
//
// Every step is the serial solver's on the block: the operator and smoother
// (distributed_poisson.hpp), the multigrid with its coarse levels gathered onto rank 0
// (distributed_multigrid.hpp), inner products and norms bitwise the serial ones
// (distributed_grid.hpp), the components (distributed_components.hpp). Where every component of
// the problem touches a Dirichlet face (the flow's usual case: an outflow at fixed pressure) the
// iterates, the iteration count and the solution are the serial solver's bit for bit, for any
// rank count. On singular components (all-Neumann) the compatibility and mean projections sum
// each grid line and then the lines in order (the serial code sums cell after cell), so the
// solution agrees with the serial one to rounding (about 1e-14 relative), not bit for bit; one
// singular component only (several: refused, one line).
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
  // Sum over the singular component's cells of w x and of w, line by line in the global order.
  std::pair<double, double> singular_sums(const Field& x, bool volume_weight) const;

  PoissonSolverOptions options_;
  StretchedGrid whole_;
  WholeHierarchy hierarchy_;
  std::unique_ptr<DistributedGrid> grid_;
  std::unique_ptr<DistributedPoisson> op_;
  std::unique_ptr<DistributedMultigrid> mg_;
  std::unique_ptr<DistributedComponents> components_;
  long long active_cells_ = 0, cells_ = 0;  // the whole grid's
  SolveWork work_;
};

}  // namespace finverse::cfd
