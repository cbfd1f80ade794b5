// Loops built in shares over MPI ranks (tools/cfd/parallel/rank_share.hpp, mpi_rank_share.hpp), run
// by run_cfd_ranks.sh on 1-4 ranks: every rank ends with the whole array, item for item what one
// process computes; a failing item is the lowest failing index's message on every rank; the lines
// of a field gathered from the ranks that own them (allgather_lines); and a
// 3-D body's ghost cells (ghost_cells_3d.cpp) and surface samples (surface_traction_3d.cpp) built
// in shares are one process's, bit for bit.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "cfd/forces/surface_traction_3d.hpp"
#include "cfd/immersed/ghost_cells.hpp"
#include "cfd/immersed/surface_shapes.hpp"
#include "cfd/parallel/block_decomposition.hpp"
#include "cfd/parallel/mpi_rank_share.hpp"

using namespace finverse::cfd;

namespace {

// The share installed for one test's scope (FlowRanks installs it for a whole run).
struct ShareScope {
  ShareScope() { install_rank_share(std::make_shared<MpiRankShare>(MPI_COMM_WORLD)); }
  ~ShareScope() { install_rank_share(nullptr); }
};

struct Item {
  int index;
  double value;
};

std::vector<Item> numbered(int n) {
  std::vector<Item> v(static_cast<std::size_t>(n));
  for (int m = 0; m < n; ++m) v[static_cast<std::size_t>(m)] = {m, 0.0};
  return v;
}

int world_size() {
  int p = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &p);
  return p;
}

// Field by field (memcmp would also compare the structs' padding).
bool same(const PointStencil& a, const PointStencil& b) {
  if (a.count != b.count || a.boundary_weight != b.boundary_weight) return false;
  for (int k = 0; k < a.count; ++k)
    if (a.cell[static_cast<std::size_t>(k)] != b.cell[static_cast<std::size_t>(k)] ||
        a.weight[static_cast<std::size_t>(k)] != b.weight[static_cast<std::size_t>(k)])
      return false;
  return true;
}

bool same(const GhostCell& a, const GhostCell& b) {
  return a.i == b.i && a.j == b.j && a.k == b.k && a.boundary.point == b.boundary.point &&
         a.boundary.normal == b.boundary.normal && a.boundary.distance == b.boundary.distance && a.image == b.image &&
         a.stencil == b.stencil && a.weights == b.weights && a.stencil_all_fluid == b.stencil_all_fluid &&
         same(a.dirichlet, b.dirichlet) && same(a.neumann, b.neumann) && a.intercept == b.intercept &&
         a.normal == b.normal && a.image_point == b.image_point && a.triangle == b.triangle &&
         a.barycentric == b.barycentric && a.probe == b.probe;
}

bool same(const SurfaceSample3D& a, const SurfaceSample3D& b) {
  return a.point == b.point && a.normal == b.normal && a.barycentric == b.barycentric && a.triangle == b.triangle &&
         a.area == b.area && a.probe == b.probe && same(a.velocity1, b.velocity1) && same(a.velocity2, b.velocity2) &&
         same(a.pressure1, b.pressure1) && same(a.pressure2, b.pressure2);
}

template <class T>
int count_differing(const std::vector<T>& a, const std::vector<T>& b) {
  int n = 0;
  for (std::size_t m = 0; m < a.size(); ++m) n += !same(a[m], b[m]);
  return n;
}

StretchedGrid sphere_grid() {
  return {Axis::stretched_count(0, 1, 0.3, 0.7, 28, 1.15), Axis::stretched_count(0, 1, 0.3, 0.7, 26, 1.15),
          Axis::stretched_count(0, 1, 0.3, 0.7, 24, 1.15)};
}

}  // namespace

TEST(RankShare, EveryRankEndsWithTheWholeArray) {
  const ShareScope scope;
  // More items than ranks, not divisible; fewer items than ranks; none.
  for (int n : {37, 2, 0}) {
    std::vector<Item> items = numbered(n);
    int calls = 0;
    shared_for_each(items, [&](Item& it) {
#pragma omp atomic
      ++calls;
      it.value = std::sin(0.3 * it.index) + it.index;
    });
    EXPECT_LE(calls, n / world_size() + 1) << n << " items: this rank computed more than its share";
    for (int m = 0; m < n; ++m) {
      EXPECT_EQ(items[static_cast<std::size_t>(m)].index, m);
      EXPECT_EQ(items[static_cast<std::size_t>(m)].value, std::sin(0.3 * m) + m) << "item " << m;
    }
  }
}

// A whole-flow run's face velocities and convective term computed on each rank's own lines
// (tools/cfd/flow/rank_lines.cpp) are gathered with allgather_lines: every line from the rank that
// owns it, face rows that two blocks share from either, lines of no rank untouched.
TEST(RankShare, AllgatherLinesLeavesEveryLineItsOwnersValues) {
  const ShareScope scope;
  const RankShare& share = *rank_share();
  const int nx = 5, ny = 7, nz = 4;
  const BlockDecomposition split(nx, ny, nz, 3, share.size(), 1);
  const Block& b = split.block(share.rank());
  const auto truth = [](int i, int j, int k) { return 100.0 * k + 10.0 * j + i + 0.25; };
  // Cells of the block's lines, the rest garbage that differs by rank.
  Field f(nx, ny, nz, 3);
  f.fill(-1.0 - share.rank());
  for (int k = b.k0; k < b.k1; ++k)
    for (int j = b.j0; j < b.j1; ++j)
      for (int i = 0; i < nx; ++i) f(i, j, k) = truth(i, j, k);
  allgather_lines(share, b, nx, [&](int j, int k) { return &f(0, j, k); });
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) ASSERT_EQ(f(i, j, k), truth(i, j, k)) << i << " " << j << " " << k;
  // y faces: rows j in [j0, j1] (the upper row is the next block's lower one), ny + 1 rows in all;
  // z row 0 is nobody's and keeps its value.
  const int rows = ny + 1;
  std::vector<double> faces(static_cast<std::size_t>(nx) * rows * nz, -5.0 - share.rank());
  const auto row = [&](int j, int k) {
    return faces.data() + static_cast<std::size_t>(nx) * (j + static_cast<std::size_t>(rows) * k);
  };
  const LineRange mine{b.j0, b.j1 + 1, std::max(b.k0, 1), b.k1};
  for (int k = mine.k0; k < mine.k1; ++k)
    for (int j = mine.j0; j < mine.j1; ++j)
      for (int i = 0; i < nx; ++i) row(j, k)[i] = truth(i, j, k);
  allgather_lines(share, mine, nx, row);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < rows; ++j)
      for (int i = 0; i < nx; ++i)
        ASSERT_EQ(row(j, k)[i], k == 0 ? -5.0 - share.rank() : truth(i, j, k)) << i << " " << j << " " << k;
  EXPECT_EQ(share.max(0.5 * share.rank()), 0.5 * (share.size() - 1));
}

TEST(RankShare, AFailingItemThrowsTheLowestIndexsMessageOnEveryRank) {
  const ShareScope scope;
  std::vector<Item> items = numbered(40);
  try {
    shared_for_each(items, [](Item& it) {
      if (it.index == 33 || it.index == 35) throw std::runtime_error("item " + std::to_string(it.index) + " failed");
    });
    ADD_FAILURE() << "no rank threw";
  } catch (const std::exception& e) {
    EXPECT_EQ(std::string(e.what()), "item 33 failed");
  }
  // Without a share the same loop gives the same message.
  install_rank_share(nullptr);
  std::vector<Item> alone = numbered(40);
  EXPECT_THROW(shared_for_each(alone, [](Item& it) { if (it.index == 33) throw std::runtime_error("x"); }),
               finverse::Error);
}

TEST(RankShare, GhostCellsAndSamplesOfASphereAreOneProcesssBitForBit) {
  const StretchedGrid grid = sphere_grid();
  const SurfaceGeometry body(icosphere({0.48, 0.51, 0.5}, 0.13, 3));
  const GhostCellSet alone(grid, body);
  ASSERT_GT(alone.ghosts().size(), 100u);
  const ShareScope scope;
  const GhostCellSet shared(grid, body);
  ASSERT_EQ(shared.ghosts().size(), alone.ghosts().size());
  EXPECT_EQ(count_differing(shared.ghosts(), alone.ghosts()), 0);
  int kinds_differ = 0;
  for (int k = 0; k < grid.nz(); ++k)
    for (int j = 0; j < grid.ny(); ++j)
      for (int i = 0; i < grid.nx(); ++i) kinds_differ += shared.kind(i, j, k) != alone.kind(i, j, k);
  EXPECT_EQ(kinds_differ, 0);
  EXPECT_EQ(shared.near_wall_faces().size(), alone.near_wall_faces().size());

  // The surface's samples and their probes' stencils, clipped and not.
  for (const bool clipped : {false, true}) {
    SurfaceClip clip;
    clip.enabled = clipped;
    install_rank_share(nullptr);
    const SurfaceTraction3D one(grid, alone, body, clip);
    install_rank_share(std::make_shared<MpiRankShare>(MPI_COMM_WORLD));
    const SurfaceTraction3D many(grid, shared, body, clip);
    ASSERT_EQ(many.samples().size(), one.samples().size());
    ASSERT_GT(one.samples().size(), 1000u);
    EXPECT_EQ(count_differing(many.samples(), one.samples()), 0) << (clipped ? "clipped" : "whole");
  }
}

TEST(RankShare, ABodyAtTheDomainsEdgeFailsAlikeOnEveryRank) {
  const StretchedGrid grid = sphere_grid();
  const SurfaceGeometry body(icosphere({0.5, 0.5, 0.04}, 0.13, 2));  // through the z = 0 wall
  std::string alone;
  try {
    const GhostCellSet g(grid, body);
  } catch (const std::exception& e) {
    alone = e.what();
  }
  ASSERT_NE(alone, "") << "one process accepted a body through the wall";
  const ShareScope scope;
  std::string shared;
  try {
    const GhostCellSet g(grid, body);
  } catch (const std::exception& e) {
    shared = e.what();
  }
  EXPECT_EQ(shared, alone);
}
