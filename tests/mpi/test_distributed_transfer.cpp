// Multigrid transfers and coarse operators between MPI ranks' blocks
// (tools/cfd/poisson/grid_transfer.hpp setup_block, coarsening.hpp coarsen_beta), run by
// run_cfd_ranks.sh on 1-4 ranks: with the block edges on the coarse faces
// (BlockDecomposition::snapped), the block's coarse operator, the restriction of a residual and
// the prolongation of a correction, gathered, are the serial ones on the whole grid bit for bit,
// with and without immersed (inactive) cells, across walls and a periodic axis.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>

#include "cfd/parallel/distributed_grid.hpp"
#include "cfd/parallel/distributed_multigrid.hpp"
#include "cfd/parallel/distributed_poisson.hpp"
#include "cfd/poisson/coarsening.hpp"
#include "cfd/poisson/grid_transfer.hpp"

#include "gathered_equal.hpp"

using namespace finverse::cfd;

namespace {

std::vector<int> coarse_faces(const AxisCoarsening& m) { return m.first; }

void expect_serial_transfers(const StretchedGrid& whole, const BoundaryConditions& bc, bool solid) {
  const int dim = whole.dim();
  FaceCoefficients beta(whole, [](double x, double y, double z) { return 1 + 0.4 * std::sin(2 * x + y) + 0.2 * z; });
  if (solid) beta.mask_cells([](int i, int j, int k) { return i >= 5 && i <= 9 && j >= 6 && j <= 11 && k >= 2 && k <= 6; });
  PoissonOperator op;
  op.setup(whole, beta, bc);
  const Coarsening c = choose_coarsening(op, 2.0);
  ASSERT_TRUE(c[1].merges());
  const PoissonOperator coarse = coarsen_operator(op, c);
  GridTransfer t;
  t.setup(op, coarse, c);
  const StretchedGrid& cw = coarse.grid();
  Field r(whole, 1), fx(whole, 1), e(cw, 1), cb(cw, 1), rc(cw, 1), bc_field(cw, 1);
  for (int k = 0; k < whole.nz(); ++k)
    for (int j = 0; j < whole.ny(); ++j)
      for (int i = 0; i < whole.nx(); ++i) r(i, j, k) = std::sin(0.9 * i - 0.4 * j + 0.7 * k), fx(i, j, k) = 0.01 * (i + j - k);
  for (int k = 0; k < cw.nz(); ++k)
    for (int j = 0; j < cw.ny(); ++j)
      for (int i = 0; i < cw.nx(); ++i) e(i, j, k) = std::cos(0.5 * i * j + k), bc_field(i, j, k) = std::sin(i + 2.0 * j * k);
  op.zero_inactive(r);
  coarse.zero_inactive(e);
  Field r_in(r), e_in(e), fx_in(fx);
  t.restrict_residual(r, cb);
  t.prolongate_add(e, fx);
  coarse.residual(bc_field, e, rc);

  // The ranks: fine blocks on the coarse faces, the coarse blocks their parents.
  const std::array<bool, 3> periodic{false, bc.periodic(1), dim == 3 && bc.periodic(2)};
  int ranks = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  const BlockDecomposition fine_split =
      BlockDecomposition(whole.nx(), whole.ny(), whole.nz(), dim, ranks).snapped(coarse_faces(c[1]), coarse_faces(c[2]));
  const BlockDecomposition coarse_split = fine_split.coarsened(cw.nx(), c[1].parent, c[2].parent);
  const DistributedGrid gf(MPI_COMM_WORLD, fine_split, periodic), gc(MPI_COMM_WORLD, coarse_split, periodic);
  const Block &fb = gf.block(), &cbk = gc.block();
  const StretchedGrid fine_block = whole.block(fb.j0, fb.j1, fb.k0, fb.k1);
  const DistributedPoisson fine_op(gf, whole, block_faces(beta, fine_block, fb), bc);
  const Coarsening local = block_coarsening(c, fb.j0, fb.j1, fb.k0, fb.k1, dim);
  const StretchedGrid coarse_block = cw.block(cbk.j0, cbk.j1, cbk.k0, cbk.k1);
  const DistributedPoisson coarse_op(gc, cw, coarsen_beta(fine_block, fine_op.block_operator().beta(), local, coarse_block), bc);

  BlockTransferInfo info;
  info.fine_whole = &whole, info.coarse_whole = &cw, info.coarsening = &c, info.bc = &bc;
  info.fine_offset = {fb.j0, fb.k0}, info.coarse_offset = {cbk.j0, cbk.k0};
  info.exchange_fine = [&](Field& f) { gf.exchange(f); };
  info.exchange_coarse = [&](Field& f) { gc.exchange(f); };
  info.any_inactive = solid;
  GridTransfer tb;
  tb.setup_block(fine_op.block_operator(), coarse_op.block_operator(), info);

  Field rl = gf.make_field(1), fxl = gf.make_field(1), el = gc.make_field(1), cbl = gc.make_field(1), rcl = gc.make_field(1),
        bl = gc.make_field(1);
  gf.scatter(r_in, rl), gf.scatter(fx_in, fxl), gc.scatter(e_in, el), gc.scatter(bc_field, bl);
  coarse_op.residual(bl, el, rcl);
  expect_gathered_equal(gc, rcl, rc, "coarse operator's residual");
  gf.exchange(rl);
  tb.restrict_residual(rl, cbl);
  expect_gathered_equal(gc, cbl, cb, "restriction");
  // A correction whose ghosts were never exchanged: prolongate_add exchanges them itself.
  Field fresh = gc.make_field(1);
  gc.scatter(e_in, fresh);
  tb.prolongate_add(fresh, fxl);
  expect_gathered_equal(gf, fxl, fx, "prolongation");
}

StretchedGrid stretched3() {
  return StretchedGrid(Axis::stretched_count(0, 1.5, 0.5, 1.0, 16, 1.2), Axis::stretched_count(-0.6, 0.6, -0.2, 0.2, 20, 1.15),
                       Axis::stretched_count(0, 0.8, 0.2, 0.5, 12, 1.15));
}

}  // namespace

TEST(DistributedTransfer, RestrictionProlongationAndCoarseOperatorAreTheSerialOnes) {
  BoundaryConditions bc;
  bc[Side::XLo] = BcType::Dirichlet;
  expect_serial_transfers(stretched3(), bc, false);
}

TEST(DistributedTransfer, TheSameAroundInactiveCells) {
  BoundaryConditions bc;
  bc[Side::XHi] = BcType::Dirichlet;
  bc[Side::ZLo] = BcType::Dirichlet;
  expect_serial_transfers(stretched3(), bc, true);
}

TEST(DistributedTransfer, TheSameAcrossAPeriodicY) {
  BoundaryConditions bc;
  bc[Side::XLo] = BcType::Dirichlet;
  bc[Side::YLo] = bc[Side::YHi] = BcType::Periodic;
  expect_serial_transfers(StretchedGrid(Axis::stretched_count(0, 1.5, 0.5, 1.0, 16, 1.2), Axis::uniform(-0.6, 0.6, 20),
                                        Axis::stretched_count(0, 0.8, 0.2, 0.5, 12, 1.15)),
                          bc, true);
}

TEST(DistributedTransfer, TheSameIn2D) {
  BoundaryConditions bc;
  bc[Side::XLo] = bc[Side::YHi] = BcType::Dirichlet;
  expect_serial_transfers(StretchedGrid(Axis::stretched_count(0, 2, 0.5, 1.2, 24, 1.15), Axis::stretched_count(-1, 1, -0.3, 0.3, 20, 1.15)),
                          bc, true);
}
