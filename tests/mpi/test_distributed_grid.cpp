// The flow grid over MPI ranks (tools/cfd/parallel/distributed_grid.hpp), run by
// run_cfd_ranks.sh on 1, 2, 3 and 4 ranks: ghost layers filled from the neighbours' interiors
// (walls left alone, periodic axes wrapped), reductions bitwise the serial ones on the whole
// grid, gather/scatter round trips, and a stencil sweep with halos that is the serial sweep bit
// for bit. Every rank makes every collective call; checks are EXPECT_ so that a failure on one
// rank cannot leave the others waiting.
#include <gtest/gtest.h>
#include <mpi.h>

#include <array>
#include <cmath>

#include "cfd/grid/field.hpp"
#include "cfd/parallel/distributed_grid.hpp"

using finverse::cfd::DistributedGrid;
using finverse::cfd::Field;

namespace {

constexpr double kWall = -12345;  // what a ghost on a domain wall holds before and after

double value(int i, int j, int k) { return std::sin(0.37 * i + 1.1) + 100.0 * j + 10000.0 * k + 0.001 * i * j; }

int wrap(int c, int n) { return (c % n + n) % n; }

// A rank's field: interior and x ghosts from `value` at global indices, other ghosts kWall.
Field local_field(const DistributedGrid& g, int ghost) {
  Field f = g.make_field(ghost);
  f.fill(kWall);
  const auto& b = g.block();
  const int gz = f.dim() == 3 ? ghost : 0;
  for (int k = -gz; k < f.nz() + gz; ++k)
    for (int j = -ghost; j < f.ny() + ghost; ++j)
      for (int i = -ghost; i < f.nx() + ghost; ++i)
        if (j >= 0 && j < f.ny() && k >= 0 && k < f.nz()) f(i, j, k) = value(i, b.j0 + j, b.k0 + k);
  return f;
}

void check_halo(int nx, int ny, int nz, int dim, int ghost, std::array<bool, 3> periodic) {
  const DistributedGrid g(MPI_COMM_WORLD, nx, ny, nz, dim, periodic);
  Field f = local_field(g, ghost);
  g.exchange(f);
  const auto& b = g.block();
  const int gz = dim == 3 ? ghost : 0;
  int wrong = 0;
  for (int k = -gz; k < f.nz() + gz; ++k)
    for (int j = -ghost; j < f.ny() + ghost; ++j)
      for (int i = -ghost; i < f.nx() + ghost; ++i) {
        int jg = b.j0 + j, kg = b.k0 + k;
        const bool y_in = (jg >= 0 && jg < ny) || periodic[1], z_in = dim == 2 || (kg >= 0 && kg < nz) || periodic[2];
        jg = wrap(jg, ny), kg = dim == 2 ? 0 : wrap(kg, nz);
        const double expect = y_in && z_in ? value(i, jg, kg) : kWall;
        if (f(i, j, k) != expect && ++wrong <= 3)
          ADD_FAILURE() << "rank " << g.rank() << " ghost " << ghost << ": (" << i << "," << j << "," << k << ") holds "
                        << f(i, j, k) << ", expected " << expect;
      }
  EXPECT_EQ(wrong, 0);
}

}  // namespace

TEST(DistributedGrid, GhostsHoldTheNeighboursInteriorWallsAreLeftAlone) {
  check_halo(7, 12, 10, 3, 1, {false, false, false});
  check_halo(7, 12, 10, 3, 2, {true, true, false});
  check_halo(7, 12, 10, 3, 2, {false, false, true});
  check_halo(9, 16, 1, 2, 2, {false, true, false});
}

TEST(DistributedGrid, ReductionsAreTheSerialOnesBitForBit) {
  const int nx = 37, ny = 14, nz = 11;
  const DistributedGrid g(MPI_COMM_WORLD, nx, ny, nz, 3, {false, false, false});
  Field a = local_field(g, 1), b = g.make_field(1);
  Field ga(nx, ny, nz, 3, 1), gb(nx, ny, nz, 3, 1);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i) ga(i, j, k) = value(i, j, k), gb(i, j, k) = std::cos(0.1 * i * j - 0.3 * k);
  g.scatter(gb, b);
  EXPECT_EQ(g.dot(a, b), finverse::cfd::dot(ga, gb));
  EXPECT_EQ(g.norm2(a), finverse::cfd::norm2(ga));
  EXPECT_EQ(g.max_abs(b), finverse::cfd::max_abs(gb));
}

TEST(DistributedGrid, GatherAndScatterRoundTrip) {
  const int nx = 5, ny = 9, nz = 8;
  const DistributedGrid g(MPI_COMM_WORLD, nx, ny, nz, 3, {false, false, false});
  const Field a = local_field(g, 1);
  Field whole(nx, ny, nz, 3, 0), back = g.make_field(2);
  g.gather(a, whole);
  if (g.rank() == 0) {
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) EXPECT_EQ(whole(i, j, k), value(i, j, k));
  }
  g.scatter(whole, back);
  for (int k = 0; k < back.nz(); ++k)
    for (int j = 0; j < back.ny(); ++j)
      for (int i = 0; i < nx; ++i) EXPECT_EQ(back(i, j, k), a(i, j, k));
}

// Weighted Jacobi on the 7-point Laplacian with zero walls and a periodic y axis: the distributed
// sweeps (halo exchange, then the same point update) equal the serial sweeps on the whole grid.
TEST(DistributedGrid, AStencilSweepWithHalosIsTheSerialSweep) {
  const int nx = 11, ny = 13, nz = 9, sweeps = 6;
  const std::array<bool, 3> periodic{false, true, false};
  const DistributedGrid g(MPI_COMM_WORLD, nx, ny, nz, 3, periodic);
  const auto rhs = [](int i, int j, int k) { return std::cos(0.5 * i) * std::sin(0.7 * j + 0.2 * k); };
  const auto sweep = [&](Field& x, Field& y, int j0, int k0) {
    for (int k = 0; k < x.nz(); ++k)
      for (int j = 0; j < x.ny(); ++j)
        for (int i = 0; i < x.nx(); ++i) {
          const double s = x(i - 1, j, k) + x(i + 1, j, k) + x(i, j - 1, k) + x(i, j + 1, k) + x(i, j, k - 1) + x(i, j, k + 1);
          y(i, j, k) = x(i, j, k) + 0.8 * ((s + rhs(i, j0 + j, k0 + k)) / 6.0 - x(i, j, k));
        }
  };
  Field whole(nx, ny, nz, 3, 1), next(nx, ny, nz, 3, 1);
  for (int n = 0; n < sweeps; ++n) {
    for (int k = 0; k < nz; ++k)
      for (int i = 0; i < nx; ++i) whole(i, -1, k) = whole(i, ny - 1, k), whole(i, ny, k) = whole(i, 0, k);
    sweep(whole, next, 0, 0);
    std::swap(whole, next);
  }
  Field x = g.make_field(1), y = g.make_field(1);
  for (int n = 0; n < sweeps; ++n) {
    g.exchange(x);
    sweep(x, y, g.block().j0, g.block().k0);
    std::swap(x, y);
  }
  Field gathered(nx, ny, nz, 3, 0);
  g.gather(x, gathered);
  if (g.rank() == 0) {
    for (int k = 0; k < nz; ++k)
      for (int j = 0; j < ny; ++j)
        for (int i = 0; i < nx; ++i) EXPECT_EQ(gathered(i, j, k), whole(i, j, k)) << i << "," << j << "," << k;
  }
}

int main(int argc, char** argv) {
  MPI_Init(&argc, &argv);
  ::testing::InitGoogleTest(&argc, argv);
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  // One rank prints the run; every rank still reports its failures.
  if (rank > 0) delete ::testing::UnitTest::GetInstance()->listeners().Release(
      ::testing::UnitTest::GetInstance()->listeners().default_result_printer());
  const int failed = RUN_ALL_TESTS();
  int any = 0;
  MPI_Allreduce(&failed, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
  MPI_Finalize();
  return any;
}
