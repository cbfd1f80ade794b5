// Tests of the finite-volume Poisson operator: symmetry, null space, exactness for linear
// solutions on stretched grids, and second-order convergence against manufactured solutions
// (uniform and stretched grids, 2-D and 3-D, Dirichlet, Neumann and periodic, variable beta).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numbers>
#include <random>
#include <stdexcept>
#include <utility>
#include <vector>

#include "cfd/poisson/poisson_operator.hpp"
#include "cfd/poisson/poisson_solver.hpp"
#include "support.hpp"

namespace finverse::cfd {
namespace {

using test::Errors;
using test::Manufactured;

StretchedGrid stretched_3d(int n) {
  return StretchedGrid(Axis::stretched_count(-2, 3, -0.5, 1, n, 1.1), Axis::stretched_count(-2, 2, -0.5, 0.5, n, 1.1),
                       Axis::stretched_count(-1, 2, -0.25, 0.75, n / 2, 1.1));
}

TEST(PoissonOperator, SymmetricWithMaskStretchingAndMixedBoundaries) {
  const StretchedGrid g = stretched_3d(16);
  FaceCoefficients beta(g, [](double x, double y, double z) { return 1 + 0.1 * x * x + 0.05 * y * z; });
  beta.mask_cells([&](int i, int j, int k) {
    const double x = g.xc(i), y = g.yc(j), z = g.zc(k);
    return x * x + y * y + (z - 0.25) * (z - 0.25) < 0.3;
  });
  BoundaryConditions bc;
  bc[Side::XLo] = BcType::Dirichlet;
  bc[Side::YLo] = bc[Side::YHi] = BcType::Periodic;
  PoissonOperator op;
  op.setup(g, beta, bc);
  Field x = test::random_field(g, 1), y = test::random_field(g, 2), ax(g), ay(g);
  op.zero_inactive(x);
  op.zero_inactive(y);
  op.apply(x, ax);
  op.apply(y, ay);
  const double a = dot(ax, y), b = dot(x, ay);
  EXPECT_NEAR(a, b, 1e-12 * norm2(ax) * norm2(y));
  EXPECT_GT(dot(ax, x), 0);  // positive definite: a Dirichlet side pins the constant
  EXPECT_LT(op.active_cells(), g.cells());
  EXPECT_FALSE(op.any_singular());
}

TEST(PoissonOperator, ConstantsSpanTheNullSpaceOfAllNeumannProblems) {
  const StretchedGrid g = stretched_3d(32);
  FaceCoefficients beta(g, 1.0);
  // A hollow shell of solid cells separates an inner fluid pocket from the outer fluid: two
  // singular components.
  beta.mask_cells([&](int i, int j, int k) {
    const double r = std::sqrt(g.xc(i) * g.xc(i) + g.yc(j) * g.yc(j) + (g.zc(k) - 0.25) * (g.zc(k) - 0.25));
    return r > 0.25 && r < 0.6;
  });
  PoissonOperator op;
  op.setup(g, beta, BoundaryConditions::all(BcType::Neumann));
  EXPECT_EQ(op.components(), 2);
  EXPECT_TRUE(op.singular(0));
  EXPECT_TRUE(op.singular(1));
  Field one(g), out(g);
  one.fill(1.0);
  op.zero_inactive(one);
  op.apply(one, out);
  EXPECT_LT(max_abs(out), 1e-13);
}

// Set up without its connectivity (a system solver's operator, an MPI block), the operator applies
// and assembles as with it, and its null-space projections refuse rather than use stale components.
TEST(PoissonOperator, WithoutConnectivityAppliesTheSameAndRefusesTheProjections) {
  const StretchedGrid g = stretched_3d(16);
  FaceCoefficients beta(g, 1.0);
  beta.mask_cells([&](int i, int j, int k) { return g.xc(i) * g.xc(i) + g.yc(j) * g.yc(j) + g.zc(k) * g.zc(k) < 0.3; });
  const BoundaryConditions bc = BoundaryConditions::all(BcType::Neumann);
  PoissonOperator with, without;
  with.setup(g, beta, bc);
  without.setup(g, beta, bc);  // connectivity built once, then the same operator set up again without it
  without.setup(g, beta, bc, PoissonOperator::Connectivity::Skip);
  EXPECT_TRUE(with.has_connectivity());
  EXPECT_FALSE(without.has_connectivity());
  Field x = test::random_field(g, 3), a(g), b(g);
  with.apply(x, a);
  without.apply(x, b);
  axpy(-1.0, a, b);
  EXPECT_EQ(max_abs(b), 0.0);
  EXPECT_EQ(with.active_cells(), without.active_cells());
  EXPECT_THROW((void)without.any_singular(), std::logic_error);
  EXPECT_THROW((void)without.components(), std::logic_error);
  EXPECT_THROW(without.remove_mean(b), std::logic_error);
  EXPECT_TRUE(with.any_singular());
}

// The components of the union-find labelling against a plain flood fill written here: the same id
// for every cell (ids in scan order of each component's first active cell) and the same singular
// flags, on masks of scattered solid cells (many small pockets, pockets touching a Dirichlet side,
// components joined only through a periodic side), for each combination of side conditions.
// On MPI ranks that hold the whole flow, a rank computes the momentum and pressure right-hand
// sides on its own lines only (momentum_predictor.cpp): apply and assemble_rhs on a LineRange must
// give the whole call's bits there and leave every other cell alone.
TEST(PoissonOperator, ApplyAndRightHandSideOnLinesAreTheWholeCallsThere) {
  const StretchedGrid g = stretched_3d(16);
  FaceCoefficients beta(g, [](double x, double y, double z) { return 1 + 0.1 * x * x + 0.05 * y * z; });
  BoundaryConditions bc;
  bc[Side::XLo] = bc[Side::YHi] = bc[Side::ZLo] = BcType::Dirichlet;
  PoissonOperator op;
  op.setup(g, beta, bc);
  const LineRange lines{3, g.ny(), 2, 5};  // touches the Dirichlet side YHi, not ZLo
  Field x = test::random_field(g, 3), f = test::random_field(g, 4);
  BoundaryValues bv;
  for (Side s : {Side::XLo, Side::YHi, Side::ZLo})
    bv.sample(g, s, [](double x, double y, double z) { return x - 2 * y + z * z; });
  Field whole(g), part(g), rhs_whole(g), rhs_part(g);
  part.fill(7.0);
  rhs_part.fill(7.0);
  op.apply(x, whole);
  op.apply(x, part, lines);
  op.assemble_rhs(f, bv, rhs_whole);
  op.assemble_rhs(f, bv, rhs_part, lines);
  long inside = 0, outside = 0;
  for (int k = 0; k < g.nz(); ++k)
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) {
        if (lines.contains(j, k)) {
          ++inside;
          ASSERT_EQ(part(i, j, k), whole(i, j, k)) << i << " " << j << " " << k;
          ASSERT_EQ(rhs_part(i, j, k), rhs_whole(i, j, k)) << i << " " << j << " " << k;
        } else {
          ++outside;
          ASSERT_EQ(part(i, j, k), 7.0);
          ASSERT_EQ(rhs_part(i, j, k), 7.0);
        }
      }
  EXPECT_EQ(inside, static_cast<long>(g.nx()) * lines.ny() * lines.nz());
  EXPECT_GT(outside, 0);
}

TEST(PoissonOperator, ComponentsMatchAFloodFill) {
  const StretchedGrid g = stretched_3d(16);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0, 1);
  std::vector<char> solid(g.cells());
  for (auto& c : solid) c = u(rng) < 0.55 ? 1 : 0;  // near the site-percolation threshold: many pockets
  const auto at = [&](int i, int j, int k) {
    return static_cast<std::size_t>(i) + static_cast<std::size_t>(g.nx()) * (j + static_cast<std::size_t>(g.ny()) * k);
  };
  int checked = 0;
  for (int variant = 0; variant < 4; ++variant) {
    FaceCoefficients beta(g, 1.0);
    beta.mask_cells([&](int i, int j, int k) { return solid[at(i, j, k)] != 0; });
    BoundaryConditions bc;
    if (variant & 1) bc[Side::XLo] = BcType::Dirichlet;
    if (variant & 2) bc[Side::YLo] = bc[Side::YHi] = BcType::Periodic;
    PoissonOperator op;
    op.setup(g, beta, bc);
    // Reference: depth-first flood fill over faces with nonzero transmissibility.
    const int n[3] = {g.nx(), g.ny(), g.nz()};
    std::vector<int> comp(g.cells(), -1);
    std::vector<char> singular;
    for (int k0 = 0; k0 < n[2]; ++k0)
      for (int j0 = 0; j0 < n[1]; ++j0)
        for (int i0 = 0; i0 < n[0]; ++i0) {
          if (!op.active(i0, j0, k0) || comp[at(i0, j0, k0)] >= 0) continue;
          const int id = static_cast<int>(singular.size());
          bool pinned = false;
          std::vector<std::array<int, 3>> stack{{i0, j0, k0}};
          comp[at(i0, j0, k0)] = id;
          while (!stack.empty()) {
            const auto c = stack.back();
            stack.pop_back();
            for (int d = 0; d < 3; ++d)
              for (int side = 0; side < 2; ++side) {
                std::array<int, 3> f = c, nb = c;
                f[static_cast<std::size_t>(d)] += side;
                const auto& t = op.transmissibility(d);
                const auto [fx, fy] = std::pair<std::size_t, std::size_t>(n[0] + (d == 0), n[1] + (d == 1));
                if (!(t[static_cast<std::size_t>(f[0]) + fx * (f[1] + fy * static_cast<std::size_t>(f[2]))] > 0)) continue;
                int& m = nb[static_cast<std::size_t>(d)];
                m += side ? 1 : -1;
                if (m < 0 || m >= n[d]) {
                  if (!bc.periodic(d)) {
                    pinned = true;
                    continue;
                  }
                  m = (m + n[d]) % n[d];
                }
                if (comp[at(nb[0], nb[1], nb[2])] < 0) {
                  comp[at(nb[0], nb[1], nb[2])] = id;
                  stack.push_back(nb);
                }
              }
          }
          singular.push_back(pinned ? 0 : 1);
        }
    ASSERT_EQ(op.components(), static_cast<int>(singular.size())) << "variant " << variant;
    EXPECT_GT(op.components(), 8) << "variant " << variant;  // the mask really makes many pockets
    for (std::size_t c = 0; c < comp.size(); ++c) ASSERT_EQ(op.component()[c], comp[c]) << "variant " << variant << ", cell " << c;
    int pinned = 0;
    for (int c = 0; c < op.components(); ++c) {
      ASSERT_EQ(op.singular(c), singular[static_cast<std::size_t>(c)] != 0) << "variant " << variant << ", component " << c;
      pinned += !op.singular(c);
    }
    if (variant & 1) {
      EXPECT_GT(pinned, 0);
    }
    ++checked;
  }
  EXPECT_EQ(checked, 4);
}

// For a linear p the face difference quotients and the half-cell Dirichlet quotient are exact on
// any grid, so the discrete solution must equal p to solver tolerance, stretching or not.
TEST(PoissonOperator, ExactForLinearSolutionsOnStretchedGrids) {
  const StretchedGrid g = stretched_3d(32);
  const auto exact = [](double x, double y, double z) { return 2 * x - 3 * y + 0.5 * z + 1; };
  const double grad[3] = {2, -3, 0.5};
  for (BcType type : {BcType::Dirichlet, BcType::Neumann}) {
    PoissonSolver solver;
    PoissonSolverOptions opt;
    opt.rtol = 1e-13;
    solver.setup(g, FaceCoefficients(g, 1.0), BoundaryConditions::all(type), opt);
    BoundaryValues bv;
    for (int s = 0; s < 6; ++s) {
      const Side side = static_cast<Side>(s);
      const double sign = side_is_high(side) ? 1 : -1;
      if (type == BcType::Dirichlet) bv.sample(g, side, exact);
      else bv.sample(g, side, [&](double, double, double) { return sign * grad[side_axis(side)]; });
    }
    Field f(g), p(g);
    const auto st = solver.solve(f, bv, p);
    ASSERT_TRUE(st.converged);
    const Errors e = test::error(g, p, exact, type == BcType::Neumann);
    EXPECT_LT(e.linf, 1e-9) << (type == BcType::Dirichlet ? "Dirichlet" : "Neumann");
  }
}

struct OrderCase {
  const char* name;
  int dim;
  BoundaryConditions bc;
  bool stretched;
  double s;  // beta = 1 + s x y
  std::vector<int> n;
  double ratio = 1.2;  // stretch ratio of the coarsest grid of a stretched family
};

// Solves the manufactured problem on each grid of the sequence and returns observed orders
// (L2, Linf) between the last two grids, with h taken as (cells)^(-1/dim).
std::pair<double, double> observed_order(const OrderCase& c) {
  Manufactured m;
  m.dim = c.dim;
  m.s = c.s;
  std::vector<Errors> errs;
  std::vector<double> h;
  bool neumann_only = true;
  for (int s = 0; s < 2 * c.dim; ++s)
    if (c.bc.type[static_cast<std::size_t>(s)] == BcType::Dirichlet) neumann_only = false;
  for (std::size_t l = 0; l < c.n.size(); ++l) {
    const int n = c.n[l];
    // Stretched: one smooth mapping sampled ever finer (the coarsest grid refined l times).
    auto axis = [&](double lo, double hi, double ulo, double uhi, int cells) {
      if (!c.stretched) return Axis::uniform(lo, hi, cells);
      Axis a = Axis::stretched_count(lo, hi, ulo, uhi, c.n[0], c.ratio);
      for (std::size_t r = 0; r < l; ++r) a = a.refined();
      EXPECT_EQ(a.size(), cells);
      return a;
    };
    const StretchedGrid g = c.dim == 2 ? StretchedGrid(axis(-2, 3, -0.5, 1, n), axis(-2, 2.5, -0.5, 0.5, n))
                                       : StretchedGrid(axis(-2, 3, -0.5, 1, n), axis(-2, 2.5, -0.5, 0.5, n),
                                                       axis(-1.5, 2, -0.5, 0.5, n));
    PoissonSolver solver;
    PoissonSolverOptions opt;
    opt.rtol = 1e-12;
    solver.setup(g, FaceCoefficients(g, [&](double x, double y, double z) { return m.beta(x, y, z); }), c.bc, opt);
    Field p(g);
    const auto st = solver.solve(test::source(g, [&](double x, double y, double z) { return m.f(x, y, z); }),
                                 test::boundary_values(g, c.bc, m), p);
    EXPECT_TRUE(st.converged) << c.name << " n=" << n;
    errs.push_back(test::error(g, p, [&](double x, double y, double z) { return m.p(x, y, z); }, neumann_only));
    h.push_back(std::pow(static_cast<double>(g.cells()), -1.0 / c.dim));
    std::printf("  %-28s n=%4d  L2=%.3e  Linf=%.3e  (%d MG-PCG iterations, levels %s)\n", c.name, n, errs.back().l2,
                errs.back().linf, st.iterations, solver.multigrid().describe().c_str());
  }
  const std::size_t a = errs.size() - 2, b = errs.size() - 1;
  const double lh = std::log(h[a] / h[b]);
  return {std::log(errs[a].l2 / errs[b].l2) / lh, std::log(errs[a].linf / errs[b].linf) / lh};
}

void expect_second_order(const OrderCase& c) {
  const auto [o2, oinf] = observed_order(c);
  std::printf("  %-28s observed order L2 %.3f, Linf %.3f\n", c.name, o2, oinf);
  EXPECT_GE(o2, 1.9) << c.name;
  EXPECT_GE(oinf, 1.9) << c.name;
}

BoundaryConditions mixed() {
  BoundaryConditions bc = BoundaryConditions::all(BcType::Neumann);
  bc[Side::XHi] = BcType::Dirichlet;
  bc[Side::YLo] = BcType::Dirichlet;
  return bc;
}

TEST(PoissonOrder, Uniform2D) {
  expect_second_order({"2-D uniform Dirichlet", 2, BoundaryConditions::all(BcType::Dirichlet), false, 0, {32, 64, 128, 256}});
  expect_second_order({"2-D uniform Neumann", 2, BoundaryConditions::all(BcType::Neumann), false, 0, {32, 64, 128, 256}});
}

TEST(PoissonOrder, Stretched2D) {
  expect_second_order({"2-D stretched Dirichlet", 2, BoundaryConditions::all(BcType::Dirichlet), true, 0, {32, 64, 128, 256}});
  expect_second_order({"2-D stretched Neumann", 2, BoundaryConditions::all(BcType::Neumann), true, 0, {32, 64, 128, 256}});
  expect_second_order({"2-D stretched mixed, var. beta", 2, mixed(), true, 0.05, {32, 64, 128, 256}});
}

// The Dirichlet max-norm error is still pre-asymptotic at 64^3 (order 1.90 from 32^3, 1.95 from
// 64^3 to 128^3: the one-sided half-cell wall gradient is first order, its effect on the solution
// second order), hence the extra level.
TEST(PoissonOrder, Uniform3D) {
  expect_second_order({"3-D uniform Dirichlet", 3, BoundaryConditions::all(BcType::Dirichlet), false, 0, {16, 32, 64, 128}});
  expect_second_order({"3-D uniform Neumann", 3, BoundaryConditions::all(BcType::Neumann), false, 0, {16, 32, 64}});
}

TEST(PoissonOrder, Stretched3D) {
  expect_second_order({"3-D stretched Dirichlet", 3, BoundaryConditions::all(BcType::Dirichlet), true, 0, {16, 32, 64}, 1.1});
  expect_second_order({"3-D stretched Neumann", 3, BoundaryConditions::all(BcType::Neumann), true, 0, {16, 32, 64}});
}

// Periodic in x (solution with the domain period), Dirichlet in y.
TEST(PoissonOrder, Periodic2D) {
  const double L = 4.0, k = 2 * std::numbers::pi / L;
  const auto exact = [&](double x, double y, double) { return std::sin(k * x + 0.3) * std::cos(1.2 * y); };
  const auto f = [&](double x, double y, double z) { return -(k * k + 1.44) * exact(x, y, z); };
  BoundaryConditions bc = BoundaryConditions::all(BcType::Dirichlet);
  bc[Side::XLo] = bc[Side::XHi] = BcType::Periodic;
  std::vector<Errors> e;
  std::vector<double> h;
  for (int n : {32, 64, 128, 256}) {
    Axis y = Axis::stretched_count(-2, 2, -0.5, 0.5, 32, 1.2);
    for (int m = 32; m < n; m *= 2) y = y.refined();
    const StretchedGrid g(Axis::uniform(-1, 3, n), y);
    PoissonSolver solver;
    PoissonSolverOptions opt;
    opt.rtol = 1e-12;
    solver.setup(g, FaceCoefficients(g, 1.0), bc, opt);
    BoundaryValues bv;
    bv.sample(g, Side::YLo, exact);
    bv.sample(g, Side::YHi, exact);
    Field p(g);
    ASSERT_TRUE(solver.solve(test::source(g, f), bv, p).converged);
    e.push_back(test::error(g, p, exact, false));
    h.push_back(std::pow(static_cast<double>(g.cells()), -0.5));
  }
  const double lh = std::log(h[2] / h[3]);
  std::printf("  2-D periodic x: order L2 %.3f Linf %.3f\n", std::log(e[2].l2 / e[3].l2) / lh,
              std::log(e[2].linf / e[3].linf) / lh);
  EXPECT_GE(std::log(e[2].l2 / e[3].l2) / lh, 1.9);
  EXPECT_GE(std::log(e[2].linf / e[3].linf) / lh, 1.9);
}

}  // namespace
}  // namespace finverse::cfd
