// The pressure Poisson operator and its red-black smoother over MPI ranks
// (tools/cfd/parallel/distributed_poisson.hpp), run by run_cfd_ranks.sh on 1-4 ranks: on a
// stretched grid with a variable coefficient, an immersed block of solid cells, Dirichlet,
// Neumann and periodic sides, the residual and three sweeps (forward, backward, over-relaxed)
// gathered from the ranks are the serial operator's on the whole grid bit for bit.
#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>

#include "cfd/grid/field.hpp"
#include "cfd/parallel/distributed_grid.hpp"
#include "cfd/parallel/distributed_poisson.hpp"
#include "cfd/poisson/smoother.hpp"

#include "gathered_equal.hpp"

using namespace finverse::cfd;

namespace {

struct Case {
  StretchedGrid grid;
  BoundaryConditions bc;
  bool solid_block;
};

void expect_serial_bits(const Case& c) {
  const StretchedGrid& whole = c.grid;
  const int nx = whole.nx(), ny = whole.ny(), nz = whole.nz(), dim = whole.dim();
  FaceCoefficients beta(whole, [](double x, double y, double z) { return 1 + 0.5 * std::sin(3 * x) * std::cos(2 * y) + 0.3 * z; });
  if (c.solid_block) beta.mask_cells([](int i, int j, int k) { return i >= 4 && i <= 6 && j >= 5 && j <= 8 && k >= 3 && k <= 5; });
  PoissonOperator op;
  op.setup(whole, beta, c.bc);
  Field x(whole, 1), b(whole, 1), r(whole, 1);
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        x(i, j, k) = std::sin(0.7 * i + 0.3 * j - 0.2 * k), b(i, j, k) = std::cos(0.4 * i * j + k);
  op.zero_inactive(x);

  const std::array<bool, 3> periodic{false, c.bc.periodic(1), dim == 3 && c.bc.periodic(2)};
  const DistributedGrid g(MPI_COMM_WORLD, nx, ny, nz, dim, periodic);
  const Block& blk = g.block();
  const DistributedPoisson dp(g, whole, block_faces(beta, whole.block(blk.j0, blk.j1, blk.k0, blk.k1), blk), c.bc);
  Field xl = g.make_field(1), bl = g.make_field(1), rl = g.make_field(1);
  g.scatter(x, xl);
  g.scatter(b, bl);

  const auto compare = [&](const Field& local, const Field& serial, const char* what) {
    expect_gathered_equal(g, local, serial, what);
  };
  op.residual(b, x, r);
  dp.residual(bl, xl, rl);
  compare(rl, r, "residual");
  const struct {
    bool forward;
    double omega;
  } sweeps[] = {{true, 1.0}, {false, 1.0}, {true, 1.2}};
  for (const auto& s : sweeps) {
    red_black_sweep(op, b, x, s.forward, s.omega);
    dp.red_black_sweep(bl, xl, s.forward, s.omega);
  }
  compare(xl, x, "three red-black sweeps");
}

StretchedGrid grid3() {
  return StretchedGrid(Axis::stretched_count(0, 1.3, 0.4, 0.8, 12, 1.15), Axis::stretched_count(-0.5, 0.6, -0.2, 0.2, 14, 1.1),
                       Axis::stretched_count(0, 0.7, 0.2, 0.5, 10, 1.12));
}

}  // namespace

TEST(DistributedPoisson, ResidualAndSweepsAreTheSerialOnesWithADirichletSideAPeriodicYAndASolidBlock) {
  BoundaryConditions bc;
  bc[Side::XLo] = BcType::Dirichlet;
  bc[Side::YLo] = bc[Side::YHi] = BcType::Periodic;
  expect_serial_bits({grid3(), bc, true});
}

TEST(DistributedPoisson, ResidualAndSweepsAreTheSerialOnesWithPeriodicXAndZ) {
  BoundaryConditions bc;
  bc[Side::XLo] = bc[Side::XHi] = BcType::Periodic;
  bc[Side::ZLo] = bc[Side::ZHi] = BcType::Periodic;
  bc[Side::YLo] = BcType::Dirichlet;
  expect_serial_bits({grid3(), bc, false});
}

TEST(DistributedPoisson, ResidualAndSweepsAreTheSerialOnesIn2D) {
  BoundaryConditions bc;
  bc[Side::XLo] = bc[Side::XHi] = BcType::Dirichlet;
  bc[Side::YLo] = bc[Side::YHi] = BcType::Periodic;
  expect_serial_bits({StretchedGrid(Axis::stretched_count(0, 2, 0.5, 1.2, 20, 1.1), Axis::stretched_count(-1, 1, -0.3, 0.3, 16, 1.1)),
                      bc, true});
}
