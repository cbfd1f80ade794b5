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
#include <utility>
#include <vector>

#include "cfd/poisson/coarsening.hpp"
#include "cfd/grid/field.hpp"
#include "cfd/poisson/poisson_operator.hpp"

namespace finverse::cfd {

class GridTransfer {
 public:
  // `coarsening` maps the fine cells onto the coarse ones (coarsening.hpp).
  void setup(const PoissonOperator& fine, const PoissonOperator& coarse, const Coarsening& coarsening);

  // coarse_b = R fine_r.
  void restrict_residual(const Field& fine_r, Field& coarse_b) const;
  // fine_x += P coarse_e. Fills coarse_e's ghosts (periodic wrap; zero elsewhere).
  void prolongate_add(Field& coarse_e, Field& fine_x) const;

 private:
  struct Entry {
    int c = 0;       // coarse index along the axis, -1 or n for the ghost (wrap or wall value 0)
    double w = 0.0;  // 1-D weight
  };
  const PoissonOperator* coarse_ = nullptr;
  const PoissonOperator* fine_ = nullptr;
  std::array<std::vector<std::array<Entry, 2>>, 3> prol_;  // per axis, per fine index
  // R = P^T per axis in compressed rows: coarse index C gathers fine indices ridx_[q] with weights
  // rw_[q], q in [rptr_[C], rptr_[C+1]). Applied axis by axis (x, then y, then z), so only the x
  // pass gathers and the others are contiguous row updates.
  std::array<std::vector<int>, 3> rptr_, ridx_;
  std::array<std::vector<double>, 3> rw_;
  std::vector<double> scale_;  // per fine cell renormalisation; empty when every cell is active
  // Scratch of restrict_residual (after the x and after the y pass): one restriction at a time per
  // transfer, which is how the multigrid cycle uses it.
  mutable std::vector<double> tx_, txy_;
};

}  // namespace finverse::cfd
