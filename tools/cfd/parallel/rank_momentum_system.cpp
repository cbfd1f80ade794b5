// The momentum systems of a whole-flow run solved over MPI ranks; see rank_momentum_system.hpp.
#include "cfd/parallel/rank_momentum_system.hpp"

#include "cfd/parallel/distributed_poisson.hpp"

namespace finverse::cfd {

void RankMomentumSystem::setup(const PoissonOperator& op, const FaceCoefficients& beta, const BoundaryConditions& bc) {
  const StretchedGrid& whole = op.grid();
  const int dim = whole.dim();
  solver_.reset();  // the old solver refers to the old grid
  grid_ = std::make_unique<DistributedGrid>(comm_, whole.nx(), whole.ny(), whole.nz(), dim,
                                            std::array<bool, 3>{false, bc.periodic(1), dim == 3 && bc.periodic(2)});
  const Block& blk = grid_->block();
  solver_ = std::make_unique<DistributedHelmholtz>(
      *grid_, whole, block_faces(beta, whole.block(blk.j0, blk.j1, blk.k0, blk.k1), blk), bc);
  b_ = grid_->make_field(1);
  x_ = grid_->make_field(1);
}

std::optional<LineRange> RankMomentumSystem::lines_read() const {
  if (!grid_) return std::nullopt;
  return grid_->block();
}

HelmholtzStats RankMomentumSystem::solve(const PoissonOperator& op, double mass, double stiffness, const Field& b,
                                         Field& x, double rtol, int max_iterations) {
  op.fill_ghosts(x);  // as the threaded solve's first product A x does
  grid_->own_part(b, b_);
  grid_->own_part(x, x_);
  const HelmholtzStats st = solver_->solve(mass, stiffness, b_, x_, rtol, max_iterations);
  grid_->allgather(x_, x);
  return st;
}

}  // namespace finverse::cfd
