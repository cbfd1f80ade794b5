// The Crank-Nicolson momentum system over MPI ranks (tools/cfd/parallel/distributed_helmholtz.hpp),
// run by run_cfd_ranks.sh on 1-4 ranks: Jacobi-PCG on the ranks' blocks gives the threaded
// HelmholtzSolver's iteration count and solution bit for bit (stretched 3-D with a masked body,
// Dirichlet walls and a periodic y; 2-D).
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>

#include "cfd/parallel/distributed_helmholtz.hpp"
#include "cfd/parallel/rank_momentum_system.hpp"

#include "gathered_equal.hpp"

using namespace finverse::cfd;

namespace {

void expect_serial_helmholtz(const StretchedGrid& whole, const BoundaryConditions& bc) {
  const int dim = whole.dim();
  FaceCoefficients beta(whole, 1.0);
  beta.mask_cells([](int i, int j, int k) { return i >= 6 && i <= 10 && j >= 5 && j <= 9 && k <= 6; });
  const double dt = 2e-3, nu = 1e-2, mass = 1 / dt, stiffness = 0.5 * nu;
  HelmholtzSolver serial;
  serial.setup(whole, beta, bc);
  Field b(whole, 1), x(whole, 1);
  for (int k = 0; k < whole.nz(); ++k)
    for (int j = 0; j < whole.ny(); ++j)
      for (int i = 0; i < whole.nx(); ++i)
        b(i, j, k) = whole.volume(i, j, k) * (std::sin(0.4 * i - 0.3 * j) + 0.2 * k) / dt, x(i, j, k) = 0.1 * std::cos(0.2 * i * j);
  const Field b0(b), x0(x);
  const HelmholtzStats st = serial.solve(mass, stiffness, b, x, 1e-12, 200);

  const std::array<bool, 3> periodic{false, bc.periodic(1), dim == 3 && bc.periodic(2)};
  const DistributedGrid g(MPI_COMM_WORLD, whole.nx(), whole.ny(), whole.nz(), dim, periodic);
  const Block& blk = g.block();
  DistributedHelmholtz dist(g, whole, block_faces(beta, whole.block(blk.j0, blk.j1, blk.k0, blk.k1), blk), bc);
  Field bl = g.make_field(1), xl = g.make_field(1);
  g.scatter(b0, bl), g.scatter(x0, xl);
  const HelmholtzStats dst = dist.solve(mass, stiffness, bl, xl, 1e-12, 200);
  EXPECT_TRUE(dst.converged);
  EXPECT_EQ(dst.iterations, st.iterations);
  EXPECT_EQ(dst.relative_residual, st.relative_residual);
  expect_gathered_equal(g, xl, x, "the velocity after the solve");
}

}  // namespace

TEST(DistributedHelmholtz, JacobiPcgIsTheThreadedSolveBitForBit) {
  BoundaryConditions bc = BoundaryConditions::all(BcType::Dirichlet);
  bc[Side::YLo] = bc[Side::YHi] = BcType::Periodic;
  bc[Side::XHi] = BcType::Neumann;
  expect_serial_helmholtz(StretchedGrid(Axis::stretched_count(0, 1.5, 0.4, 1.0, 20, 1.2), Axis::uniform(-0.5, 0.5, 16),
                                        Axis::stretched_count(0, 0.8, 0.2, 0.5, 12, 1.15)),
                          bc);
}

TEST(DistributedHelmholtz, TheSameIn2D) {
  expect_serial_helmholtz(StretchedGrid(Axis::stretched_count(0, 2, 0.5, 1.2, 28, 1.15), Axis::stretched_count(-1, 1, -0.3, 0.3, 20, 1.15)),
                          BoundaryConditions::all(BcType::Dirichlet));
}

// A flow's HelmholtzSolver with the ranks' system installed (rank_momentum_system.hpp, as FlowRanks
// installs it): the solution on every rank, ghosts included, is the threaded solve's bit for bit.
TEST(DistributedHelmholtz, TheRanksSystemLeavesTheThreadedSolution) {
  const StretchedGrid whole(Axis::stretched_count(0, 1.5, 0.4, 1.0, 20, 1.2), Axis::uniform(-0.5, 0.5, 16),
                            Axis::stretched_count(0, 0.8, 0.2, 0.5, 12, 1.15));
  BoundaryConditions bc = BoundaryConditions::all(BcType::Dirichlet);
  bc[Side::ZLo] = bc[Side::ZHi] = BcType::Periodic;
  bc[Side::XHi] = BcType::Neumann;
  const FaceCoefficients beta(whole, 1.0);
  HelmholtzSolver threaded, ranks;
  threaded.setup(whole, beta, bc);
  ranks.set_system_solver(std::make_shared<RankMomentumSystem>(MPI_COMM_WORLD));
  ranks.setup(whole, beta, bc);
  Field b(whole, 1), x(whole, 1);
  for (int k = 0; k < whole.nz(); ++k)
    for (int j = 0; j < whole.ny(); ++j)
      for (int i = 0; i < whole.nx(); ++i)
        b(i, j, k) = whole.volume(i, j, k) * std::cos(0.3 * i + 0.2 * j - 0.5 * k) * 500, x(i, j, k) = 0.01 * i - 0.02 * k;
  Field xr(x);
  const HelmholtzStats st = threaded.solve(500, 0.005, b, x, 1e-10, 200);
  const HelmholtzStats sr = ranks.solve(500, 0.005, b, xr, 1e-10, 200);
  EXPECT_TRUE(sr.converged);
  EXPECT_EQ(sr.iterations, st.iterations);
  EXPECT_EQ(sr.relative_residual, st.relative_residual);
  int wrong = 0;
  for (int k = -1; k <= whole.nz(); ++k)
    for (int j = -1; j <= whole.ny(); ++j)
      for (int i = -1; i <= whole.nx(); ++i) wrong += xr(i, j, k) != x(i, j, k);
  EXPECT_EQ(wrong, 0) << "cells (ghosts included) that differ from the threaded solve";
}
