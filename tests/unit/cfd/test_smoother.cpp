// Tests of the red-black smoother (smoother.cpp): the one-pass sweep of a grid without periodic
// axes (both colours plane by plane) must be the textbook two-colour Gauss-Seidel sweep, forward
// and backward, on one and on two threads; the sweep with the residual fused into it must give the
// bits of the sweep followed by the operator's residual.
#include <gtest/gtest.h>

#include <omp.h>

#include <cmath>

#include "cfd/poisson/poisson_operator.hpp"
#include "cfd/poisson/smoother.hpp"
#include "support.hpp"

namespace finverse::cfd {
namespace {

// The reference: every cell of colour c (parity of i + j + k), then every cell of the other
// colour, in plain loop order, read straight from the operator's coefficients.
void reference_sweep(const PoissonOperator& op, const Field& b, Field& x, bool forward, double omega) {
  const StretchedGrid& g = op.grid();
  const FaceCoefficients& f = op.beta();
  const auto t = [&](int d, int i, int j, int k) { return op.transmissibility(d)[f.index(d, i, j, k)]; };
  for (int c : {forward ? 0 : 1, forward ? 1 : 0})
    for (int k = 0; k < g.nz(); ++k)
      for (int j = 0; j < g.ny(); ++j)
        for (int i = 0; i < g.nx(); ++i) {
          if (((i + j + k) & 1) != c) continue;
          const double inv = op.inverse_diagonal()[op.cell_index(i, j, k)];
          double s = b(i, j, k) + t(0, i, j, k) * x(i - 1, j, k) + t(0, i + 1, j, k) * x(i + 1, j, k) +
                     t(1, i, j, k) * x(i, j - 1, k) + t(1, i, j + 1, k) * x(i, j + 1, k);
          if (g.dim() == 3) s += t(2, i, j, k) * x(i, j, k - 1) + t(2, i, j, k + 1) * x(i, j, k + 1);
          x(i, j, k) = inv > 0 ? x(i, j, k) + omega * (s * inv - x(i, j, k)) : 0.0;
        }
}

// A grid big enough for the parallel path, a sphere (circle) of masked cells and a Dirichlet side;
// with `periodic`, the last axis periodic.
PoissonOperator masked_operator(int dim, bool periodic) {
  const int n = dim == 3 ? 28 : 160;
  const StretchedGrid g = dim == 3 ? StretchedGrid(test::stretched_axis(1), test::stretched_axis(1).refined(),
                                                   Axis::uniform(-1, 2, n))
                                   : StretchedGrid(test::stretched_axis(3), Axis::uniform(-1, 2, n));
  FaceCoefficients beta(g, 1.0);
  beta.mask_cells([&](int i, int j, int k) {
    const double x = g.xc(i) - 0.3, y = g.yc(j) - 0.2, z = dim == 3 ? g.zc(k) - 0.5 : 0.0;
    return x * x + y * y + z * z < 0.3 * 0.3;
  });
  BoundaryConditions bc = BoundaryConditions::all(BcType::Neumann);
  bc[Side::XHi] = BcType::Dirichlet;
  if (periodic) bc[dim == 3 ? Side::ZLo : Side::YLo] = bc[dim == 3 ? Side::ZHi : Side::YHi] = BcType::Periodic;
  PoissonOperator op;
  op.setup(g, beta, bc);
  return op;
}

double max_difference(const StretchedGrid& g, const Field& a, const Field& b) {
  double d = 0;
  for (int k = 0; k < g.nz(); ++k)
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) d = std::max(d, std::abs(a(i, j, k) - b(i, j, k)));
  return d;
}

TEST(RedBlackSmoother, OnePassSweepIsTheTwoColourGaussSeidel) {
  const int saved = omp_get_max_threads();
  for (int dim : {2, 3}) {
    const PoissonOperator op = masked_operator(dim, false);
    const StretchedGrid& g = op.grid();
    ASSERT_GE(static_cast<long>(g.cells()), parallel_min_cells);
    const Field b = test::random_field(g, 11);
    for (bool forward : {true, false})
      for (int threads : {1, 2}) {
        omp_set_num_threads(threads);
        Field x = test::random_field(g, 5), y = x;
        for (int s = 0; s < 3; ++s) {
          red_black_sweep(op, b, x, forward, 1.2);
          reference_sweep(op, b, y, forward, 1.2);
        }
        // Scale: the first sweep moves x by O(1); a wrong ordering moves it by as much.
        EXPECT_LT(max_difference(g, x, y), 1e-12)
            << dim << "-D, " << (forward ? "forward" : "backward") << ", " << threads << " threads";
      }
  }
  omp_set_num_threads(saved);
}

// The fused sweep + residual against the two separate passes, bit for bit, in 2-D and 3-D, on one
// and two threads, with a masked body and a Dirichlet side; and with a periodic axis (its fallback).
TEST(RedBlackSmoother, FusedResidualIsTheSweepThenTheResidual) {
  const int saved = omp_get_max_threads();
  for (int dim : {2, 3})
    for (bool periodic : {false, true}) {
      const PoissonOperator op = masked_operator(dim, periodic);
      const StretchedGrid& g = op.grid();
      ASSERT_GE(static_cast<long>(g.cells()), parallel_min_cells);
      const Field b = test::random_field(g, 11);
      for (int threads : {1, 2}) {
        omp_set_num_threads(threads);
        Field x = test::random_field(g, 5), y = x, r = op.make_field(), s = op.make_field();
        for (int sweep = 0; sweep < 2; ++sweep) {
          red_black_sweep_residual(op, b, x, 1.2, r);
          red_black_sweep(op, b, y, true, 1.2);
          op.residual(b, y, s);
        }
        EXPECT_EQ(max_difference(g, x, y), 0.0) << dim << "-D, periodic " << periodic << ", " << threads << " threads";
        EXPECT_EQ(max_difference(g, r, s), 0.0) << dim << "-D, periodic " << periodic << ", " << threads << " threads";
        // Not trivially zero: a residual that was never written would fail here.
        EXPECT_GT(max_difference(g, r, op.make_field()), 1e-3);
      }
    }
  omp_set_num_threads(saved);
}

}  // namespace
}  // namespace finverse::cfd
