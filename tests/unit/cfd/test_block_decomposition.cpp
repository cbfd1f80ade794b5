// The flow grid's pencil decomposition over ranks (tools/cfd/parallel/block_decomposition.hpp):
// every line owned once, balanced blocks, consistent neighbours, the halo's size, and a rank
// count the grid cannot take refused with the largest one that works.
#include <gtest/gtest.h>

#include <set>
#include <string>

#include "cfd/parallel/block_decomposition.hpp"
#include "core/error.hpp"

using finverse::cfd::BlockDecomposition;

namespace {

void expect_partition(const BlockDecomposition& d, int balance = 1) {
  std::vector<int> owned(static_cast<std::size_t>(d.ny() * d.nz()), -1);
  int ymin = 1 << 30, ymax = 0, zmin = 1 << 30, zmax = 0;
  for (int r = 0; r < d.ranks(); ++r) {
    const auto& b = d.block(r);
    ymin = std::min(ymin, b.ny()), ymax = std::max(ymax, b.ny()), zmin = std::min(zmin, b.nz()), zmax = std::max(zmax, b.nz());
    for (int k = b.k0; k < b.k1; ++k)
      for (int j = b.j0; j < b.j1; ++j) {
        auto& o = owned[static_cast<std::size_t>(j + d.ny() * k)];
        EXPECT_EQ(o, -1) << "line " << j << "," << k << " owned twice";
        o = r;
        EXPECT_EQ(d.owner(j, k), r);
      }
  }
  for (int o : owned) EXPECT_GE(o, 0);
  EXPECT_LE(ymax - ymin, balance);
  EXPECT_LE(zmax - zmin, balance);
}

}  // namespace

TEST(BlockDecomposition, EveryLineOnceBalancedWithinOneLine) {
  for (int ranks : {1, 2, 3, 4, 6, 8, 12}) {
    const BlockDecomposition d(40, 37, 23, 3, ranks);
    EXPECT_EQ(d.ranks(), ranks);
    expect_partition(d);
  }
  const BlockDecomposition flat(64, 50, 1, 2, 5);
  EXPECT_EQ(flat.pz(), 1);
  EXPECT_EQ(flat.py(), 5);
  expect_partition(flat);
}

TEST(BlockDecomposition, TheSquarestSplitHasTheSmallestHalo) {
  // 9 ranks on 60 x 60 lines: 3 x 3 blocks of 20 x 20 (a middle block's halo 2 x 20 + 2 x 20
  // lines), not 9 slabs (2 x 60).
  const BlockDecomposition d(10, 60, 60, 3, 9);
  EXPECT_EQ(d.py(), 3);
  EXPECT_EQ(d.pz(), 3);
  // One ghost layer, no periodic axis: the middle block receives two y faces (20 lines each) and
  // two z faces widened by its two y ghosts (22 lines each), each nx + 2 cells long.
  EXPECT_EQ(d.max_halo_cells(1, {false, false, false}), std::size_t((2 * 20 + 2 * 22) * 12));
  // 4 ranks on 40 x 40: slabs and 2 x 2 cut as many lines (80); the tie goes to slabs (fewer
  // messages).
  EXPECT_EQ(BlockDecomposition(10, 40, 40, 3, 4).py(), 4);
  // Slabs where z is short.
  EXPECT_EQ(BlockDecomposition(10, 64, 4, 3, 4).pz(), 1);
}

TEST(BlockDecomposition, NeighboursAreMutualAndWrapOnPeriodicAxes) {
  const BlockDecomposition d(8, 30, 20, 3, 6);
  const std::array<bool, 3> walls{false, false, false}, periodic_y{false, true, false};
  for (int r = 0; r < d.ranks(); ++r)
    for (int axis : {1, 2})
      for (int side : {-1, 1}) {
        const int n = d.neighbour(r, axis, side, periodic_y);
        if (n >= 0) {
          EXPECT_EQ(d.neighbour(n, axis, -side, periodic_y), r);
        }
        if (axis == 1) {
          EXPECT_GE(n, 0);  // periodic: always someone
        }
      }
  // The first block has a wall below in y, the wrap's last block with periodic y.
  EXPECT_EQ(d.neighbour(0, 1, -1, walls), -1);
  EXPECT_EQ(d.neighbour(0, 1, -1, periodic_y), d.py() - 1);
  // One block along a periodic axis is its own neighbour.
  const BlockDecomposition one(8, 30, 20, 3, 1);
  EXPECT_EQ(one.neighbour(0, 1, 1, periodic_y), 0);
  EXPECT_EQ(one.neighbour(0, 2, 1, periodic_y), -1);
}

TEST(BlockDecomposition, ARankCountTheGridCannotTakeIsRefusedWithTheLargestThatWorks) {
  // 2-D, 9 lines, at least 2 per rank: at most 4 ranks; 7 (prime, > 4) is refused.
  try {
    BlockDecomposition(16, 9, 1, 2, 7);
    FAIL() << "7 ranks on 9 lines were accepted";
  } catch (const finverse::Error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("cannot be split into 7 ranks"), std::string::npos) << what;
    EXPECT_NE(what.find("use at most 4 ranks"), std::string::npos) << what;
  }
  EXPECT_EQ(BlockDecomposition::largest_feasible(9, 1, 2, 7), 4);
  EXPECT_THROW(BlockDecomposition(16, 9, 1, 2, 0), finverse::Error);
  EXPECT_THROW(BlockDecomposition(16, 9, 3, 2, 1), finverse::Error);  // 2-D with nz > 1
}

TEST(BlockDecomposition, EdgesSnapToCoarseFacesAndCarryDownTheLevels) {
  // 30 lines whose coarse level merges pairs: the allowed edges are the even faces.
  std::vector<int> even, parent;
  for (int f = 0; f <= 30; f += 2) even.push_back(f);
  for (int i = 0; i < 30; ++i) parent.push_back(i / 2);
  const BlockDecomposition even_split = BlockDecomposition(8, 30, 1, 2, 4).snapped(even, {0, 1});
  for (int e : even_split.y_edges()) EXPECT_EQ(e % 2, 0) << e;
  expect_partition(even_split, 2);  // within one coarse cell
  const BlockDecomposition coarse = even_split.coarsened(4, parent, {0});
  EXPECT_EQ(coarse.ny(), 15);
  for (int r = 0; r < 4; ++r) {
    EXPECT_EQ(coarse.block(r).j0 * 2, even_split.block(r).j0);
    EXPECT_EQ(coarse.block(r).j1 * 2, even_split.block(r).j1);
  }
  // The unsnapped split of 30 into 4 (8, 8, 7, 7) cuts at 15, inside a coarse cell: refused.
  EXPECT_THROW(BlockDecomposition(8, 30, 1, 2, 4).coarsened(4, parent, {0}), finverse::Error);
  // Too few coarse faces for the blocks: refused with the advice.
  EXPECT_THROW(BlockDecomposition(8, 30, 1, 2, 4).snapped({0, 30}, {0, 1}), finverse::Error);
}
