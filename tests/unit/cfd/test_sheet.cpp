// Tests of the zero-thickness immersed surface (delta_kernel.hpp, sheet_markers.hpp,
// sheet_forcing.hpp, sheet_step.cpp): the kernels' moment conditions and smoothness, the markers'
// sampling and force return, the adjointness of interpolation and spreading, and, in the flow, a
// plate towed through still fluid against the same plate fixed in a stream (Galilean invariance,
// no force impulse as the towed plate's markers cross grid lines).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <vector>

#include "cfd/flow/flow_solver.hpp"
#include "cfd/immersed/delta_kernel.hpp"
#include "cfd/immersed/sheet_forcing.hpp"
#include "cfd/immersed/sheet_markers.hpp"
#include "cfd/validation/spanwise_plate_2d3d.hpp"
#include "cfd/validation/towed_plate.hpp"
#include "core/error.hpp"

namespace finverse::cfd {
namespace {

const DeltaKernel kAll[] = {DeltaKernel::Roma3, DeltaKernel::Peskin4, DeltaKernel::Smooth3, DeltaKernel::Smooth4};

TEST(DeltaKernel, PartitionOfUnityAndZeroFirstMoment) {
  for (DeltaKernel k : kAll)
    for (int s = 0; s <= 20; ++s) {
      const double r = s / 20.0;
      double sum = 0, first = 0;
      for (int i = -4; i <= 4; ++i) {
        sum += delta_kernel(k, r - i);
        first += (r - i) * delta_kernel(k, r - i);
      }
      EXPECT_NEAR(sum, 1.0, 1e-12) << delta_kernel_name(k) << " r " << r;
      EXPECT_NEAR(first, 0.0, 1e-12) << delta_kernel_name(k) << " r " << r;
    }
}

TEST(DeltaKernel, SmoothedKernelsHaveAContinuousCurvature) {
  // Largest jump of the one-sided second derivatives over r in [-3, 3]: the unsmoothed kernels
  // are C1 with jumps in curvature (Roma's about 12, Peskin's about 2), the box-smoothed ones C2.
  const auto worst_jump = [](DeltaKernel k) {
    const double e = 1e-4;
    double w = 0;
    for (int s = -300; s <= 300; ++s) {
      const double r = s / 100.0 + 1e-9;
      const double left = (delta_kernel(k, r) - 2 * delta_kernel(k, r - e) + delta_kernel(k, r - 2 * e)) / (e * e);
      const double right = (delta_kernel(k, r + 2 * e) - 2 * delta_kernel(k, r + e) + delta_kernel(k, r)) / (e * e);
      w = std::max(w, std::abs(right - left));
    }
    return w;
  };
  EXPECT_GT(worst_jump(DeltaKernel::Roma3), 5.0);
  EXPECT_GT(worst_jump(DeltaKernel::Peskin4), 1.0);
  EXPECT_LT(worst_jump(DeltaKernel::Smooth3), 0.05);
  EXPECT_LT(worst_jump(DeltaKernel::Smooth4), 0.05);
  EXPECT_THROW(delta_kernel_from_name("gauss"), Error);
}

TEST(SheetMarkers, SamplesEveryElementAndConservesTheForce) {
  // Two triangles of a unit square, markers at most 0.1 apart.
  SheetTopology t{3, 4, {{0, 1, 2}, {0, 2, 3}}};
  const std::vector<Vec3> x = {{0, 0, 0}, {1, 0, 0}, {1, 0, 1}, {0, 0, 1}};
  const SheetMarkers m(t, x, 0.1, "square");
  // Markers (their patches' centroids) no closer than half the spacing, and every point of the
  // square within 1.2 spacings of one.
  const std::vector<Vec3> X = m.at_markers(x);
  for (std::size_t a = 0; a < X.size(); ++a)
    for (std::size_t b = a + 1; b < X.size(); ++b) ASSERT_GE(norm(sub(X[a], X[b])), 0.05);
  for (int i = 0; i <= 50; ++i)
    for (int k = 0; k <= 50; ++k) {
      double best = 1e9;
      for (const Vec3& y : X) best = std::min(best, norm(sub(Vec3{i / 50.0, 0, k / 50.0}, y)));
      ASSERT_LE(best, 0.12);
    }
  EXPECT_GT(m.size(), 80u);
  EXPECT_LT(m.size(), 160u);
  const std::vector<double> a = m.node_measure(x);
  EXPECT_NEAR(a[0] + a[1] + a[2] + a[3], 1.0, 1e-12);
  // A uniform load per marker returns to the nodes with the same total and moment.
  std::vector<Vec3> f(m.size(), Vec3{0, 2.0, 0});
  const std::vector<Vec3> nodal = m.to_nodes(f);
  double fy = 0, mx = 0, mx_markers = 0;
  for (std::size_t i = 0; i < nodal.size(); ++i) fy += nodal[i][1], mx += nodal[i][1] * x[i][0];
  for (std::size_t k = 0; k < X.size(); ++k) mx_markers += f[k][1] * X[k][0];
  EXPECT_NEAR(fy, 2.0 * m.size(), 1e-9);
  EXPECT_NEAR(mx, mx_markers, 1e-9);
  // A degenerate triangle and a node out of range are refused.
  EXPECT_THROW(SheetMarkers(SheetTopology{3, 3, {{0, 1, 2}}}, {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}}, 0.1, "line"), Error);
  EXPECT_THROW(SheetMarkers(SheetTopology{3, 3, {{0, 1, 7}}}, {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}, 0.1, "bad"), Error);
}

TEST(SheetMarkers, APeriodicSeamHoldsOneRowOfMarkers) {
  // A 1 x 0.5 rectangle in the x-z plane, nodes every 0.1 on both seams of a z-period of 0.5.
  const int nx = 10, nz = 5;
  SheetTopology t{3, static_cast<std::size_t>((nx + 1) * (nz + 1)), {}};
  std::vector<Vec3> x;
  const auto id = [&](int i, int k) { return k * (nx + 1) + i; };
  for (int k = 0; k <= nz; ++k)
    for (int i = 0; i <= nx; ++i) x.push_back({0.1 * i, 0, 0.1 * k});
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < nx; ++i) {
      t.elements.push_back({id(i, k), id(i + 1, k), id(i + 1, k + 1)});
      t.elements.push_back({id(i, k), id(i + 1, k + 1), id(i, k + 1)});
    }
  const SheetMarkers open(t, x, 0.1, "open");
  const SheetMarkers seam(t, x, 0.1, "seam", {0, 0, 0.5});
  EXPECT_EQ(open.size(), 66u);  // every node
  ASSERT_EQ(seam.size(), 55u);  // the seam's second row is the first one's image
  // Every marker sits near a row k 0.1 (mod 0.5; within h/27 as the diagonal split's pieces fall
  // unevenly between patches), across the seam too: the patches that straddle it are shifted by
  // the period, not averaged across the domain (which would put them near z = 0.25).
  const std::vector<Vec3> X = seam.positions_at_markers(x);
  for (const Vec3& p : X) {
    const double row = std::fmod(p[2] + 10 * 0.5, 0.5) / 0.1;
    EXPECT_NEAR(row, std::round(row), 0.05) << p[2];
    EXPECT_NEAR(p[1], 0, 1e-12);
  }
  for (std::size_t a = 0; a < X.size(); ++a)
    for (std::size_t b = a + 1; b < X.size(); ++b) {
      Vec3 d = sub(X[a], X[b]);
      d[2] -= 0.5 * std::round(d[2] / 0.5);
      ASSERT_GE(norm(d), 0.05);  // the edges' markers sit a quarter spacing inward
    }
  // Velocities carry no offset; the force returns whole.
  const std::vector<Vec3> v = seam.at_markers(std::vector<Vec3>(x.size(), Vec3{0, 1, 0}));
  for (const Vec3& p : v) EXPECT_NEAR(p[1], 1, 1e-12);
  double fy = 0;
  for (const Vec3& f : seam.to_nodes(std::vector<Vec3>(seam.size(), Vec3{0, 1, 0}))) fy += f[1];
  EXPECT_NEAR(fy, 55.0, 1e-9);
  // A period shorter than four spacings is refused.
  EXPECT_THROW(SheetMarkers(t, x, 0.1, "short", {0, 0, 0.3}), Error);
}

TEST(SheetFlow, APeriodicSlabSheetCarriesTheForceOfItsSection) {
  // The spanwise plate (issue 44, goal 5) at c/10 on a 4-cell periodic slab, sheets only: the 3-D
  // sheet's force per span is the 2-D section's. Measured: mean C_T 1.7 % apart, C_L amplitude
  // 0.4 % with the band correction (at c/20: 0.18 % and 0.1 %; docs/studies/thin_surface.md); the
  // closed body's 3-D path 2.4 % and 6.3 % on the same grid.
  SpanwisePlateSetup s;
  s.cells_per_chord = 10;
  s.span_cells = 4;
  s.closed = false;
  const SpanwisePlateResult r = run_spanwise_plate(s);
  ASSERT_FALSE(r.slab_sheet.failed) << r.slab_sheet.error;
  ASSERT_FALSE(r.flat_sheet.failed) << r.flat_sheet.error;
  EXPECT_FALSE(r.flat.ran);
  EXPECT_NEAR(r.slab_sheet.mean_ct, r.flat_sheet.mean_ct, 0.025 * std::abs(r.flat_sheet.mean_ct));
  EXPECT_NEAR(r.slab_sheet.cl_amplitude, r.flat_sheet.cl_amplitude, 0.01 * r.flat_sheet.cl_amplitude);
  EXPECT_NEAR(r.slab_sheet.mean_cl, r.flat_sheet.mean_cl, 0.01 * r.flat_sheet.cl_amplitude);
}

TEST(RegularizedStencils, InterpolationIsExactForLinearFieldsAndAdjointToSpreading) {
  const StretchedGrid g(Axis::uniform(0, 1, 32), Axis::uniform(0, 1, 32), Axis::uniform(0, 1, 16));
  const std::vector<Vec3> X = {{0.413, 0.52, 0.5}, {0.47, 0.561, 0.43}, {0.52, 0.6, 0.57}};
  for (DeltaKernel k : kAll) {
    const RegularizedStencils s(g, {false, false, false}, X, k, "test");
    Field q(g);
    for (int kk = 0; kk < g.nz(); ++kk)
      for (int j = 0; j < g.ny(); ++j)
        for (int i = 0; i < g.nx(); ++i) q(i, j, kk) = 1 + 2 * g.xc(i) - 3 * g.yc(j) + 0.5 * g.zc(kk);
    std::vector<double> v;
    s.interpolate(q, v);
    for (std::size_t m = 0; m < X.size(); ++m)
      EXPECT_NEAR(v[m], 1 + 2 * X[m][0] - 3 * X[m][1] + 0.5 * X[m][2], 1e-12) << delta_kernel_name(k);
    // <q, S g>_V = <I q, g>.
    Field sg(g);
    sg.fill(0.0);
    const std::vector<double> gm = {0.3, -1.2, 0.7};
    s.spread(gm, 1.0, sg);
    double lhs = 0, rhs = 0;
    for (int kk = 0; kk < g.nz(); ++kk)
      for (int j = 0; j < g.ny(); ++j)
        for (int i = 0; i < g.nx(); ++i) lhs += g.volume(i, j, kk) * q(i, j, kk) * sg(i, j, kk);
    for (std::size_t m = 0; m < X.size(); ++m) rhs += v[m] * gm[m];
    EXPECT_NEAR(lhs, rhs, 1e-12 * std::abs(rhs));
  }
  // A marker whose kernel reaches past a wall is refused, naming the boundary.
  EXPECT_THROW(RegularizedStencils(g, {false, false, false}, {{0.02, 0.5, 0.5}}, DeltaKernel::Roma3, "test"), Error);
  EXPECT_NO_THROW(RegularizedStencils(g, {true, false, false}, {{0.02, 0.5, 0.5}}, DeltaKernel::Roma3, "test"));
}

TEST(SheetFlow, TowedPlateFeelsTheForceOfTheFixedPlateWithoutImpulses) {
  // 2-D plate at 10 degrees, Re 100, c/32, 120 steps (towed_plate.hpp): the towed plate crosses
  // 38 cells. Galilean invariance of the continuous problem in a periodic box: the same force
  // history. The forcing is continuous in the markers' positions, so no step of the towed plate's
  // force departs from its neighbours by more than a small bound (a cell changing kind gives a
  // one-step impulse of 10-100 %).
  validation::TowedPlateSetup s;
  s.closed = false;
  const validation::TowedPlateResult r = validation::run_towed_plate(s);
  std::printf("towed vs fixed: max difference %.4f; largest one-step departure fixed %.4f towed %.4f\n",
              r.sheet.max_difference, r.sheet.max_departure_fixed, r.sheet.max_departure_towed);
  // Measured (docs/studies/thin_surface.md): difference 3.2 %, departures 0.02 % (fixed) and 4.5 %
  // (towed: its force oscillates by about 3 % as the markers cross the cells, one cell every 3.1
  // steps, near the sampling's Nyquist rate; the oscillation falls with h, 9 % at c/16).
  EXPECT_LT(r.sheet.max_difference, 0.04);
  EXPECT_LT(r.sheet.max_departure_towed, 0.055);
  EXPECT_GT(r.sheet.cd_fixed_end, 0.3);  // a plate at incidence: drag and lift
  EXPECT_GT(r.sheet.cl_fixed_end, 0.3);
}

}  // namespace
}  // namespace finverse::cfd
