// The pressure multigrid over MPI ranks (tools/cfd/parallel/distributed_multigrid.hpp), run by
// run_cfd_ranks.sh on 1-4 ranks: cycles on the ranks' blocks with the coarse levels gathered onto
// rank 0 are the serial Multigrid's cycles on the whole grid bit for bit (V and W cycles, a
// stretched 3-D grid with inactive cells, a periodic axis, 2-D).
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <string>

#include "cfd/parallel/distributed_multigrid.hpp"

#include "gathered_equal.hpp"

using namespace finverse::cfd;

namespace {

void expect_serial_cycles(const StretchedGrid& whole, const BoundaryConditions& bc, bool solid, CycleType type,
                          long serial_below_cells = 1L << 15) {
  const int dim = whole.dim();
  FaceCoefficients beta(whole, [](double x, double y, double z) { return 1 + 0.5 * std::sin(2 * x - y) + 0.2 * z; });
  if (solid)
    beta.mask_cells([](int i, int j, int k) { return i >= 8 && i <= 13 && j >= 7 && j <= 12 && k >= 3 && k <= 8; });
  MultigridOptions options;
  options.cycle = type;
  options.coarsest_max_cells = serial_below_cells == 0 ? 8 : 200;  // agglomeration: a deep hierarchy
  PoissonOperator op;
  op.setup(whole, beta, bc);
  Multigrid mg;
  mg.setup(op, options);
  Field b(whole, 1), x(whole, 1);
  for (int k = 0; k < whole.nz(); ++k)
    for (int j = 0; j < whole.ny(); ++j)
      for (int i = 0; i < whole.nx(); ++i) b(i, j, k) = std::sin(0.3 * i + 0.5 * j) * std::cos(0.4 * k) + 0.1;
  op.zero_inactive(b);
  const Field b0(b);

  const WholeHierarchy h = whole_hierarchy(whole, bc, options);
  ASSERT_EQ(static_cast<int>(h.grids.size()), mg.levels());
  int ranks = 0;
  MPI_Comm_size(MPI_COMM_WORLD, &ranks);
  const MultigridSplit split = plan_multigrid_split(h, ranks);
  const std::array<bool, 3> periodic{false, bc.periodic(1), dim == 3 && bc.periodic(2)};
  const DistributedGrid g(MPI_COMM_WORLD, split.fine, periodic);
  const Block& blk = g.block();
  const DistributedPoisson dp(g, whole, block_faces(beta, whole.block(blk.j0, blk.j1, blk.k0, blk.k1), blk), bc);
  DistributedMultigrid dmg(dp, h, split.gathered_level, options, serial_below_cells);
  if (ranks > 1) {
    EXPECT_GT(dmg.gathered_level(), 0) << "every level gathered: nothing distributed";
  }
  if (ranks >= 4 && serial_below_cells == 0) {
    EXPECT_TRUE(dmg.agglomerated()) << "levels below the gathered one not agglomerated on " << ranks << " ranks";
  }
  Field bl = g.make_field(1), xl = g.make_field(1);
  g.scatter(b0, bl);
  for (int c = 0; c < 3; ++c) {
    mg.cycle(b, x);
    dmg.cycle(bl, xl);
  }
  expect_gathered_equal(g, xl, x, "after 3 cycles (gathered level " + std::to_string(split.gathered_level) + " of " +
                                        std::to_string(mg.levels()) + ")");
}

StretchedGrid multigrid_grid3() {
  return StretchedGrid(Axis::stretched_count(0, 1.6, 0.5, 1.1, 24, 1.2), Axis::stretched_count(-0.6, 0.6, -0.2, 0.2, 20, 1.15),
                       Axis::stretched_count(0, 0.9, 0.3, 0.6, 12, 1.15));
}

}  // namespace

TEST(DistributedMultigrid, VCyclesAreTheSerialOnes) {
  BoundaryConditions bc;
  bc[Side::XHi] = BcType::Dirichlet;
  expect_serial_cycles(multigrid_grid3(), bc, false, CycleType::V);
}

TEST(DistributedMultigrid, WCyclesAroundInactiveCellsAreTheSerialOnes) {
  BoundaryConditions bc;
  bc[Side::XHi] = BcType::Dirichlet;
  expect_serial_cycles(multigrid_grid3(), bc, true, CycleType::W);
}

TEST(DistributedMultigrid, VCyclesWithAPeriodicYAreTheSerialOnes) {
  BoundaryConditions bc;
  bc[Side::XLo] = BcType::Dirichlet;
  bc[Side::YLo] = bc[Side::YHi] = BcType::Periodic;
  expect_serial_cycles(StretchedGrid(Axis::stretched_count(0, 1.6, 0.5, 1.1, 24, 1.2), Axis::uniform(-0.6, 0.6, 24),
                                     Axis::stretched_count(0, 0.9, 0.3, 0.6, 12, 1.15)),
                       bc, true, CycleType::V);
}

TEST(DistributedMultigrid, FCyclesIn2DAreTheSerialOnes) {
  BoundaryConditions bc;
  bc[Side::XLo] = bc[Side::YHi] = BcType::Dirichlet;
  expect_serial_cycles(StretchedGrid(Axis::stretched_count(0, 2, 0.5, 1.2, 48, 1.15), Axis::stretched_count(-1, 1, -0.3, 0.3, 40, 1.15)),
                       bc, true, CycleType::F);
}

// The levels below the gathered one on half the ranks (agglomeration), forced by a zero threshold:
// on 4 ranks levels D and below run on 2 of them; the cycles are still the serial ones.
TEST(DistributedMultigrid, AgglomeratedCoarseLevelsGiveTheSerialCycles) {
  BoundaryConditions bc;
  bc[Side::XHi] = BcType::Dirichlet;
  expect_serial_cycles(StretchedGrid(Axis::stretched_count(0, 1.6, 0.5, 1.1, 32, 1.2), Axis::uniform(-0.6, 0.6, 64),
                                     Axis::uniform(0, 0.9, 8)),
                       bc, true, CycleType::W, 0);
}
