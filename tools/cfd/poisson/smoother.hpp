// Multigrid smoothers for the Poisson operator A x = b (poisson_operator.hpp).
//
// Red-black Gauss-Seidel: cells coloured by parity of i+j+k; cells of one colour couple only to the
// other colour through the 5/7-point stencil, so each half sweep is an exactly parallel Jacobi-like
// update and the result does not depend on the thread count. The forward sweep does red then
// black, the backward sweep black then red, so pre- and post-smoothing are adjoint and the V-cycle
// is a symmetric preconditioner for conjugate gradients. The point update may be over-relaxed
// (x += omega (x_GS - x)); in 3-D omega = 1.2 lowers the V(2,2) factor (multigrid.hpp), and the
// symmetric forward/backward pair stays symmetric for any omega in (0, 2).
//
// Zebra line Gauss-Seidel: whole grid lines along one axis are solved at once (tridiagonal, cyclic
// for a periodic axis) with lines coloured by the parity of their two transverse indices. It
// removes the error that point smoothers leave where cells are strongly coupled along that axis,
// i.e. where the transverse spacing is large compared with the spacing along the line: stretched
// far-field cells and high-aspect-ratio cells. An "alternating" sweep runs it along every axis.
#pragma once

#include "cfd/grid/field.hpp"
#include "cfd/poisson/poisson_operator.hpp"

namespace finverse::cfd {

enum class SmootherKind { RedBlack, ZebraLines };

// One symmetric-pair half: forward = true runs colours 0,1 (and axes x,y,z), false runs 1,0 (and
// z,y,x). x's ghosts are refreshed as needed.
// omega: over-relaxation factor of the point updates (1 = Gauss-Seidel).
void red_black_sweep(const PoissonOperator& op, const Field& b, Field& x, bool forward, double omega = 1.0);
// A forward red-black sweep followed by r = b - A x, bit for bit red_black_sweep(.., true, ..) and
// op.residual, in one pass over the grid where no axis is periodic (the multigrid's last
// pre-smoothing sweep: the fine levels are bound by memory bandwidth).
void red_black_sweep_residual(const PoissonOperator& op, const Field& b, Field& x, double omega, Field& r);
void zebra_line_sweep(const PoissonOperator& op, const Field& b, Field& x, bool forward);
// One colour of a red-black sweep: the cells whose i + j + k has parity `colour`, ghosts as they
// are. Two of them with the ghosts refreshed before each are red_black_sweep bit for bit; the
// distributed sweep (cfd/parallel) refreshes them by halo exchange.
void red_black_colour(const PoissonOperator& op, const Field& b, Field& x, int colour, double omega = 1.0);

inline void smooth(SmootherKind kind, const PoissonOperator& op, const Field& b, Field& x, bool forward,
                   double omega = 1.0) {
  if (kind == SmootherKind::RedBlack) red_black_sweep(op, b, x, forward, omega);
  else zebra_line_sweep(op, b, x, forward);
}

}  // namespace finverse::cfd
