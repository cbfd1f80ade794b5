// Velocity gradient, vorticity and lambda_2 (cfd/vortex_identification.hpp): exact for quadratic
// fields on a stretched grid, the textbook signs of lambda_2 (rotation < 0, strain > 0), solid
// cells kept out of the fluid values, eigenvalues against Eigen's symmetric solver.
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <cmath>
#include <random>

#include "cfd/flow/vortex_identification.hpp"

using namespace finverse::cfd;

namespace {

StretchedGrid stretched_vortex_grid() {
  return StretchedGrid(Axis::stretched(0, 2, 0.8, 1.2, 0.1, 1.2), Axis::stretched(0, 1, 0.4, 0.6, 0.08, 1.15),
                       Axis::stretched(-1, 1, -0.2, 0.2, 0.1, 1.25));
}

template <class F>
Field sample(const StretchedGrid& g, F f) {
  Field out(g);
  for (int k = 0; k < g.nz(); ++k)
    for (int j = 0; j < g.ny(); ++j)
      for (int i = 0; i < g.nx(); ++i) out(i, j, k) = f(g.xc(i), g.yc(j), g.zc(k));
  return out;
}

}  // namespace

TEST(VortexIdentification, GradientOfAQuadraticFieldIsExactOnAStretchedGrid) {
  const StretchedGrid g = stretched_vortex_grid();
  ASSERT_GT(g.axis(0).max_stretch_ratio(), 1.1);
  const Field u = sample(g, [](double x, double y, double z) { return 0.5 * x * x - 2 * x * y + 3 * z * z + y; });
  const Field v = sample(g, [](double x, double y, double z) { return x * z - y * y; });
  const Field w = sample(g, [](double x, double, double z) { return 4 * x - z; });
  double worst = 0;
  for (int k = 1; k < g.nz() - 1; ++k)
    for (int j = 1; j < g.ny() - 1; ++j)
      for (int i = 1; i < g.nx() - 1; ++i) {
        const double x = g.xc(i), y = g.yc(j), z = g.zc(k);
        const VelocityGradient gr = velocity_gradient(g, {&u, &v, &w}, i, j, k, {});
        const double exact[3][3] = {{x - 2 * y, -2 * x + 1, 6 * z}, {z, -2 * y, x}, {4, 0, -1}};
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b) worst = std::max(worst, std::abs(gr[a][b] - exact[a][b]));
      }
  EXPECT_LT(worst, 1e-11);
}

TEST(VortexIdentification, RotationIsAVortexAndStrainIsNot) {
  const StretchedGrid g = stretched_vortex_grid();
  const double omega = 1.7, a = 0.9;
  // Solid-body rotation about z: vorticity (0, 0, 2 Omega); S = 0, W^2 has eigenvalues
  // -Omega^2, -Omega^2, 0, so lambda_2 = -Omega^2.
  const Field ur = sample(g, [&](double, double y, double) { return -omega * y; });
  const Field vr = sample(g, [&](double x, double, double) { return omega * x; });
  const VortexFields rot = vortex_fields(g, {&ur, &vr, nullptr}, {});
  // Plane strain: W = 0, S^2 = diag(a^2, a^2, 0), lambda_2 = a^2 > 0.
  const Field us = sample(g, [&](double x, double, double) { return a * x; });
  const Field vs = sample(g, [&](double, double y, double) { return -a * y; });
  const VortexFields str = vortex_fields(g, {&us, &vs, nullptr}, {});
  for (std::size_t m = 0; m < g.cells(); ++m) {
    ASSERT_NEAR(rot.vorticity[3 * m + 2], 2 * omega, 1e-12);
    ASSERT_NEAR(rot.vorticity[3 * m], 0, 1e-12);
    ASSERT_NEAR(rot.lambda2[m], -omega * omega, 1e-11);
    ASSERT_NEAR(str.vorticity[3 * m + 2], 0, 1e-12);
    ASSERT_NEAR(str.lambda2[m], a * a, 1e-11);
  }
}

TEST(VortexIdentification, SolidCellsDoNotLeakIntoTheFluid) {
  // A linear field with garbage in a solid block: every fluid cell still sees the exact gradient
  // (one-sided next to the solid) and the solid cells report zero.
  const StretchedGrid g(Axis::stretched(0, 1, 0.3, 0.7, 0.05, 1.2), Axis::uniform(0, 1, 16));
  const auto solid = [&](int i, int j, int) { return i >= 6 && i < 10 && j >= 5 && j < 9; };
  Field u = sample(g, [](double x, double y, double) { return 2 * x + 3 * y; });
  Field v = sample(g, [](double x, double, double) { return -x; });
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i)
      if (solid(i, j, 0)) u(i, j, 0) = v(i, j, 0) = 1e30;
  const VortexFields f = vortex_fields(g, {&u, &v, nullptr}, [&](int i, int j, int k) { return !solid(i, j, k); });
  for (int j = 0; j < g.ny(); ++j)
    for (int i = 0; i < g.nx(); ++i) {
      const std::size_t m = static_cast<std::size_t>(i + g.nx() * j);
      if (solid(i, j, 0)) {
        EXPECT_EQ(f.vorticity[3 * m + 2], 0.0);
        EXPECT_EQ(f.lambda2[m], 0.0);
      } else {
        ASSERT_NEAR(f.vorticity[3 * m + 2], -1.0 - 3.0, 1e-10) << i << " " << j;
      }
    }
}

TEST(VortexIdentification, Lambda2IsTheMiddleEigenvalueOfS2PlusW2) {
  std::mt19937 rng(7);
  std::normal_distribution<double> n01;
  for (int trial = 0; trial < 200; ++trial) {
    VelocityGradient g;
    Eigen::Matrix3d G;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) G(a, b) = g[a][b] = n01(rng) * (trial % 3 == 0 ? 1e-3 : 1.0);
    if (trial % 7 == 0) {  // repeated eigenvalues: a pure rotation about a coordinate axis
      G.setZero();
      g = {};
      G(0, 1) = g[0][1] = -1.5;
      G(1, 0) = g[1][0] = 1.5;
    }
    const Eigen::Matrix3d S = 0.5 * (G + G.transpose()), W = 0.5 * (G - G.transpose());
    const Eigen::Matrix3d M = S * S + W * W;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> es(M);
    const double expected = es.eigenvalues()(1);  // ascending
    EXPECT_NEAR(lambda2(g), expected, 1e-10 * (1 + M.norm())) << "trial " << trial;
  }
}
