// Inter-grid transfers of the cell-centred multigrid: prolongation P (coarse correction to fine
// grid) and restriction R = P^T (fine residual to coarse right-hand side).
//
// P is the tensor product of 1-D linear interpolations between cell centres at their true
// (stretched) positions: a fine cell takes its parent and the coarse neighbour on its side; along
// an axis where the cell was not merged (semi-coarsening, coarsening.hpp) it takes its parent only. At a
// Dirichlet wall the neighbour is the wall itself with correction 0, at a Neumann wall the
// correction is extended constantly (zero gradient), across a periodic boundary the neighbour
// wraps. Coarse cells that are inactive (inside an immersed body) are dropped and the remaining
// weights renormalised, so no correction is interpolated from inside the solid; inactive fine
// cells get none.
//
// Linear P (order 2) with R = P^T (order 2) satisfies m_P + m_R > 2 for the second-order operator,
// which V-cycles need for h-independent convergence on cell-centred grids, and R = P^T makes the
// V-cycle symmetric, as conjugate gradients requires. Equations are volume-integrated on every
// level, and each fine residual is distributed with weights summing to one, so no rescaling is
// needed between levels.
#pragma once

#include <array>
#include <functional>
#include <utility>
#include <vector>

#include "cfd/poisson/coarsening.hpp"
#include "cfd/grid/field.hpp"
#include "cfd/poisson/poisson_operator.hpp"

namespace finverse::cfd {

// What a transfer between two MPI ranks' blocks needs beyond the blocks' operators
// (cfd/parallel): the whole grids and their coarsening (1-D, every rank has them), the whole
// domain's conditions, the blocks' offsets (j0, k0) on the fine and coarse level, and the halo
// exchanges of a fine and a coarse field (collective).
struct BlockTransferInfo {
  const StretchedGrid* fine_whole = nullptr;
  const StretchedGrid* coarse_whole = nullptr;
  const Coarsening* coarsening = nullptr;
  const BoundaryConditions* bc = nullptr;
  std::array<int, 2> fine_offset{0, 0}, coarse_offset{0, 0};
  std::function<void(Field&)> exchange_fine, exchange_coarse;
  bool any_inactive = false;  // some rank's block has inactive cells (the same on every rank)
};

class GridTransfer {
 public:
  struct Entry {
    int c = 0;       // coarse index along the axis, -1 or n for the ghost (wrap or wall value 0)
    double w = 0.0;  // 1-D weight
  };

  // `coarsening` maps the fine cells onto the coarse ones (coarsening.hpp).
  void setup(const PoissonOperator& fine, const PoissonOperator& coarse, const Coarsening& coarsening);
  // Between one rank's blocks (PoissonOperator::setup_block) of two levels whose block edges are
  // coarse faces: the whole grid's transfers restricted to the block, bit for bit. Collective.
  // restrict_residual then needs the fine residual's ghosts exchanged; prolongate_add exchanges
  // the coarse correction itself.
  void setup_block(const PoissonOperator& fine, const PoissonOperator& coarse, const BlockTransferInfo& info);

  // coarse_b = R fine_r.
  void restrict_residual(const Field& fine_r, Field& coarse_b) const;
  // fine_x += P coarse_e. Fills coarse_e's ghosts (periodic wrap; zero elsewhere).
  void prolongate_add(Field& coarse_e, Field& fine_x) const;

 private:
  void set_rows(int d, const std::vector<std::vector<std::pair<int, double>>>& rows);
  void block_scale(const BlockTransferInfo& info);
  static constexpr int kWall = -1 << 30;  // a coarse index that stands for a wall's ghost
  template <class CoarseCell, class Inactive>
  double renormalisation(int i, int j, int k, CoarseCell coarse_cell, Inactive inactive) const;

  const PoissonOperator* coarse_ = nullptr;
  const PoissonOperator* fine_ = nullptr;
  std::array<std::vector<std::array<Entry, 2>>, 3> prol_;  // per axis, per fine index
  // R = P^T per axis in compressed rows: coarse index C gathers fine indices ridx_[q] with weights
  // rw_[q], q in [rptr_[C], rptr_[C+1]). Applied axis by axis (x, then y, then z), so only the x
  // pass gathers and the others are contiguous row updates.
  std::array<std::vector<int>, 3> rptr_, ridx_;
  std::array<std::vector<double>, 3> rw_;
  std::vector<double> scale_;  // per fine cell renormalisation (with the pad rows); empty when every cell is active
  int pad_y_ = 0, pad_z_ = 0;  // a block: the fine rows and planes beyond it that the restriction reads
  std::function<void(Field&)> exchange_coarse_;
  // Scratch of restrict_residual (after the x and after the y pass): one restriction at a time per
  // transfer, which is how the multigrid cycle uses it.
  mutable std::vector<double> tx_, txy_;
};

}  // namespace finverse::cfd
