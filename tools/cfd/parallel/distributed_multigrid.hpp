// The pressure multigrid over MPI ranks (issue 48; docs/studies/flow_mpi.md). The serial
// hierarchy (multigrid.hpp), chosen from the whole grid's axes: levels 0 .. D-1 are smoothed,
// restricted and prolongated on the ranks' blocks; level D (the deepest on which every rank keeps
// two lines per cut direction) is gathered onto rank 0, which runs the serial cycle below it, or,
// when large, handed to half the ranks as a multigrid of their own (agglomeration, as AMReX's MLMG
// does). Finer splits refine level D's edges, so every block is whole coarse cells. A cycle is the
// serial cycle bit for bit on any rank count. Red-black smoothing only: the zebra lines along y
// and z would need distributed tridiagonal solves.
#pragma once

#include <memory>
#include <vector>

#include "cfd/grid/stretched_grid.hpp"
#include "cfd/parallel/block_decomposition.hpp"
#include "cfd/parallel/distributed_grid.hpp"
#include "cfd/parallel/distributed_poisson.hpp"
#include "cfd/poisson/coarsening.hpp"
#include "cfd/poisson/grid_transfer.hpp"
#include "cfd/poisson/multigrid.hpp"

namespace finverse::cfd {

// The serial hierarchy's grids and coarsenings (grids[l + 1] = coarsen_grid(grids[l], c[l])).
struct WholeHierarchy {
  std::vector<StretchedGrid> grids;
  std::vector<Coarsening> coarsenings;
};
WholeHierarchy whole_hierarchy(const StretchedGrid& whole, const BoundaryConditions& bc, const MultigridOptions& options);

// The fine level's split for `ranks` ranks (its edges on level D's faces) and D. Throws (one line,
// naming the largest rank count that works) when not even the fine level can be split.
struct MultigridSplit {
  BlockDecomposition fine;
  int gathered_level = 0;  // D
};
MultigridSplit plan_multigrid_split(const WholeHierarchy& h, int ranks, int min_lines = 2);

// The whole coarsening restricted to a block's lines [j0, j1) x [k0, k1) (whole coarse cells).
Coarsening block_coarsening(const Coarsening& whole, int j0, int j1, int k0, int k1, int dim);

class DistributedMultigrid {
 public:
  // Collective. `fine`: the fine level's operator on the split plan_multigrid_split gave (its
  // DistributedGrid's decomposition must be MultigridSplit::fine); `hierarchy` from
  // whole_hierarchy with the same options. Both must outlive this object.
  // Level D larger than serial_below_cells cells goes to half the ranks (agglomeration) rather
  // than to rank 0 alone, recursively.
  DistributedMultigrid(const DistributedPoisson& fine, const WholeHierarchy& hierarchy, int gathered_level,
                       const MultigridOptions& options, long serial_below_cells = 1L << 15);
  ~DistributedMultigrid();

  // Collective: one cycle for A x = b on the fine level (x the initial guess), the serial cycle.
  void cycle(const Field& b, Field& x);
  void cycle(const Field& b, Field& x, CycleType type);
  int levels() const { return static_cast<int>(hierarchy_.grids.size()); }
  int gathered_level() const { return gathered_; }
  // Whether levels D and below run agglomerated on half the ranks (else on rank 0).
  bool agglomerated() const { return sub_hierarchy_ != nullptr; }

 private:
  struct Level;
  void cycle_level(int l, const Field& b, Field& x, CycleType type);
  void gathered_cycle(const Field& b, Field& x, CycleType type);
  bool agglomerate(const FaceCoefficients& beta, const BoundaryConditions& bc, long serial_below_cells);

  const WholeHierarchy& hierarchy_;
  MultigridOptions options_;
  double omega_ = 1;
  int gathered_ = 0;
  std::vector<std::unique_ptr<Level>> levels_;  // 0 .. D (level D: grid and block operator only)
  // Rank 0: level D's whole operator and the serial cycle of levels D and below.
  std::unique_ptr<PoissonOperator> whole_gathered_;
  std::unique_ptr<Multigrid> coarse_mg_;
  std::unique_ptr<Field> gb_, gx_;
  // Agglomerated: the half's hierarchy (levels D and below), communicator, grid, operator and
  // multigrid (the last four on the half's ranks only).
  std::unique_ptr<WholeHierarchy> sub_hierarchy_;
  MPI_Comm sub_comm_ = MPI_COMM_NULL;
  std::unique_ptr<DistributedGrid> sub_grid_;
  std::unique_ptr<DistributedPoisson> sub_op_;
  std::unique_ptr<DistributedMultigrid> sub_mg_;
  std::unique_ptr<Field> sub_b_, sub_x_;
};

}  // namespace finverse::cfd
