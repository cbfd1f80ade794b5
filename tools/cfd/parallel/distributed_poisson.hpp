// The pressure Poisson operator and its red-black smoother over MPI ranks (issue 48;
// docs/studies/flow_mpi.md). Each rank holds its block's PoissonOperator (setup_block: the whole
// grid's coefficients bit for bit); apply and residual exchange the halo and run the serial
// stencil, and a sweep exchanges before each colour, colours by the parity of the global
// i + j + k. Results are the serial ones bit for bit on any rank count. The components and
// null-space projections live in distributed_components.hpp and distributed_poisson_solver.hpp.
#pragma once

#include "cfd/grid/field.hpp"
#include "cfd/grid/stretched_grid.hpp"
#include "cfd/parallel/distributed_grid.hpp"
#include "cfd/poisson/face_coefficients.hpp"
#include "cfd/poisson/poisson_boundary.hpp"
#include "cfd/poisson/poisson_operator.hpp"

namespace finverse::cfd {

// A whole grid's face coefficients cut to one rank's block (its grid: whole.block(...)): for a
// caller that has the whole beta, as tests and benchmarks do; a flow solver computes each block's
// own.
FaceCoefficients block_faces(const FaceCoefficients& whole, const StretchedGrid& block_grid, const Block& block);

class DistributedPoisson {
 public:
  // Collective. `whole`: the whole grid (its axes only are used); `beta`: this rank's block faces
  // (block_faces() below gives the layout); `bc`: the whole domain's conditions, periodic axes as
  // in `grid`'s exchange. A periodic axis's last face takes face 0's beta from its owner.
  DistributedPoisson(const DistributedGrid& grid, const StretchedGrid& whole, FaceCoefficients beta,
                     const BoundaryConditions& bc);

  const DistributedGrid& grid() const { return grid_; }
  const PoissonOperator& block_operator() const { return op_; }
  // The whole domain's conditions (block_operator().bc() has the block's own sides Neumann).
  const BoundaryConditions& bc_whole() const { return bc_; }
  const StretchedGrid& block_grid() const { return op_.grid(); }

  // Collective; out = A p, r = b - A x on the block (the ghosts of p, x refreshed first).
  void apply(Field& p, Field& out) const;
  void residual(const Field& b, Field& x, Field& r) const;
  // Collective; red_black_sweep (smoother.hpp) on the whole grid, this rank's part.
  void red_black_sweep(const Field& b, Field& x, bool forward, double omega = 1.0) const;
  // Collective; a forward sweep and then r = b - A x (red_black_sweep_residual's bits).
  void red_black_sweep_residual(const Field& b, Field& x, double omega, Field& r) const;

 private:
  void refresh(Field& x) const;

  const DistributedGrid& grid_;
  BoundaryConditions bc_;
  PoissonOperator op_;
  int parity_ = 0;  // (j0 + k0) mod 2: local colour = global colour xor parity
  // One rank and no periodic y or z: the exchange does nothing, and the serial smoother's fused
  // passes (the same bits, one pass over memory per sweep) serve.
  bool alone_ = false;
};

}  // namespace finverse::cfd
