// The pressure Poisson solve over MPI ranks (tools/cfd/parallel/distributed_poisson_solver.hpp,
// distributed_components.hpp), run by run_cfd_ranks.sh on 1-4 ranks, against the serial
// PoissonSolver on the whole grid: with a Dirichlet side and an immersed body the MG-PCG
// iterates, the residual history and the solution are the serial ones bit for bit, all-Neumann
// (one singular component) too; a fluid pocket sealed inside a solid shell is
// found as its own singular component, numbered as the serial operator numbers it.
#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>

#include "cfd/parallel/distributed_poisson_solver.hpp"

using namespace finverse::cfd;

namespace {

StretchedGrid solver_grid() {
  return StretchedGrid(Axis::stretched_count(0, 1.6, 0.5, 1.1, 24, 1.2), Axis::stretched_count(-0.6, 0.6, -0.2, 0.2, 20, 1.15),
                       Axis::stretched_count(0, 0.9, 0.3, 0.6, 16, 1.15));
}

// A solid box; with `shell`, only its walls are solid and a fluid pocket is sealed inside.
bool solid_cell(int i, int j, int k, bool shell) {
  const bool box = i >= 8 && i <= 15 && j >= 6 && j <= 13 && k >= 4 && k <= 11;
  if (!shell) return box;
  const bool inner = i >= 9 && i <= 14 && j >= 7 && j <= 12 && k >= 5 && k <= 10;
  return box && !inner;
}

FaceCoefficients whole_beta(const StretchedGrid& g, int body) {
  FaceCoefficients beta(g, [](double x, double y, double z) { return 1 + 0.5 * std::sin(2 * x - y) + 0.2 * z; });
  if (body) beta.mask_cells([&](int i, int j, int k) { return solid_cell(i, j, k, body == 2); });
  return beta;
}

struct SolveRun {
  PoissonSolveStats serial, distributed;
  Field x_serial, x_gathered;
  int rank = 0;
};

SolveRun solve_both(const BoundaryConditions& bc, int body) {
  const StretchedGrid whole = solver_grid();
  const FaceCoefficients beta = whole_beta(whole, body);
  PoissonSolverOptions options;
  options.multigrid.coarsest_max_cells = 300;
  options.rtol = 1e-10;
  PoissonSolver serial;
  serial.setup(whole, beta, bc, options);
  Field b(whole, 1), x(whole, 1);
  for (int k = 0; k < whole.nz(); ++k)
    for (int j = 0; j < whole.ny(); ++j)
      for (int i = 0; i < whole.nx(); ++i) b(i, j, k) = std::sin(0.3 * i + 0.5 * j) * std::cos(0.4 * k) + 0.05 * i;
  const Field b0(b);
  SolveRun run;
  run.serial = serial.solve_system(b, x);
  run.x_serial = x;

  const auto block_beta = [&](const StretchedGrid& block_grid, const Block& blk) { return block_faces(beta, block_grid, blk); };
  DistributedPoissonSolver dist(MPI_COMM_WORLD, whole, block_beta, bc, options);
  const DistributedGrid& g = dist.grid();
  Field bl = g.make_field(1), xl = g.make_field(1);
  g.scatter(b0, bl);
  run.distributed = dist.solve_system(bl, xl);
  run.x_gathered = Field(whole.nx(), whole.ny(), whole.nz(), whole.dim(), 0);
  g.gather(xl, run.x_gathered);
  run.rank = g.rank();
  // The components, gathered, against the serial operator's.
  Field ids = g.make_field(1), ids_whole(whole.nx(), whole.ny(), whole.nz(), whole.dim(), 0);
  for (int k = 0; k < ids.nz(); ++k)
    for (int j = 0; j < ids.ny(); ++j)
      for (int i = 0; i < ids.nx(); ++i) ids(i, j, k) = dist.components().component(i, j, k);
  g.gather(ids, ids_whole);
  EXPECT_EQ(dist.components().components(), serial.op().components());
  for (int c = 0; c < std::min(dist.components().components(), serial.op().components()); ++c)
    EXPECT_EQ(dist.components().singular(c), serial.op().singular(c)) << "component " << c;
  if (run.rank == 0) {
    int wrong = 0;
    for (int k = 0; k < whole.nz(); ++k)
      for (int j = 0; j < whole.ny(); ++j)
        for (int i = 0; i < whole.nx(); ++i)
          wrong += ids_whole(i, j, k) != serial.op().component()[serial.op().cell_index(i, j, k)];
    EXPECT_EQ(wrong, 0) << "cells whose component differs from the serial operator's";
  }
  return run;
}

}  // namespace

namespace {

// Iterations, residual history and every cell of the solution equal the serial solve's.
void expect_the_serial_solve(const SolveRun& run) {
  EXPECT_TRUE(run.distributed.converged);
  EXPECT_EQ(run.distributed.iterations, run.serial.iterations);
  EXPECT_EQ(run.distributed.history, run.serial.history);
  if (run.rank != 0) return;
  int wrong = 0;
  for (int k = 0; k < run.x_serial.nz(); ++k)
    for (int j = 0; j < run.x_serial.ny(); ++j)
      for (int i = 0; i < run.x_serial.nx(); ++i) wrong += run.x_gathered(i, j, k) != run.x_serial(i, j, k);
  EXPECT_EQ(wrong, 0) << "cells whose pressure differs from the serial solve";
}

}  // namespace

TEST(DistributedPoissonSolver, PcgWithADirichletSideAndABodyIsTheSerialSolveBitForBit) {
  BoundaryConditions bc;
  bc[Side::XHi] = BcType::Dirichlet;
  expect_the_serial_solve(solve_both(bc, 1));
}

// The singular component's projections sum in the same order on ranks and in one process
// (component_sums in poisson_operator.cpp): bit for bit here too.
TEST(DistributedPoissonSolver, AllNeumannIsTheSerialSolveBitForBit) {
  expect_the_serial_solve(solve_both(BoundaryConditions{}, 0));
}

TEST(DistributedPoissonSolver, ASealedPocketIsItsOwnSingularComponent) {
  BoundaryConditions bc;
  bc[Side::XLo] = BcType::Dirichlet;
  const SolveRun run = solve_both(bc, 2);
  EXPECT_TRUE(run.distributed.converged);
}
