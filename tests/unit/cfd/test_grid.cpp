// Tests of the stretched Cartesian grid (axis construction, coarsening), the Field layout and the
// immersed-boundary face mask.
#include <gtest/gtest.h>

#include <cmath>

#include "cfd/grid/stretched_axis.hpp"
#include "cfd/poisson/face_coefficients.hpp"
#include "cfd/grid/field.hpp"
#include "cfd/grid/stretched_grid.hpp"

namespace finverse::cfd {
namespace {

TEST(Axis, UniformGeometry) {
  const Axis a = Axis::uniform(-1.0, 3.0, 8);
  ASSERT_EQ(a.size(), 8);
  EXPECT_DOUBLE_EQ(a.face(0), -1.0);
  EXPECT_DOUBLE_EQ(a.face(8), 3.0);
  for (int i = 0; i < 8; ++i) {
    EXPECT_NEAR(a.width(i), 0.5, 1e-15);
    EXPECT_NEAR(a.centre(i), -0.75 + 0.5 * i, 1e-15);
  }
  EXPECT_NEAR(a.max_stretch_ratio(), 1.0, 1e-12);
}

TEST(Axis, WidthAtIsTheContainingCellsWidthClampedToTheAxis) {
  const Axis a({0.0, 1.0, 3.0, 7.0});
  EXPECT_DOUBLE_EQ(a.width_at(0.5), 1.0);
  EXPECT_DOUBLE_EQ(a.width_at(1.0), 2.0);  // a face belongs to the cell above it
  EXPECT_DOUBLE_EQ(a.width_at(6.9), 4.0);
  EXPECT_DOUBLE_EQ(a.width_at(-5.0), 1.0);
  EXPECT_DOUBLE_EQ(a.width_at(7.0), 4.0);
  EXPECT_DOUBLE_EQ(a.width_at(99.0), 4.0);
}

TEST(Axis, FaceInterpolationIsExactForLinearFunctions) {
  const Axis a({0.0, 1.0, 3.0, 7.0});  // centres 0.5, 2, 5
  EXPECT_DOUBLE_EQ(a.centre_distance(1), 1.5);
  EXPECT_DOUBLE_EQ(a.centre_distance(2), 3.0);
  // q(x) = 2 x + 1 at the centres, interpolated to faces 1 and 2.
  const auto q = [](double x) { return 2 * x + 1; };
  for (int f : {1, 2}) {
    const double w = a.lower_weight(f);
    EXPECT_NEAR(w * q(a.centre(f - 1)) + (1 - w) * q(a.centre(f)), q(a.face(f)), 1e-14) << "face " << f;
  }
}

TEST(Axis, RejectsNonIncreasingFaces) {
  EXPECT_THROW(Axis({0.0, 1.0, 1.0}), std::invalid_argument);
  EXPECT_THROW(Axis({0.0}), std::invalid_argument);
}

TEST(Axis, StretchedHasUniformCoreAndBoundedRatio) {
  const double h = 0.05, rmax = 1.1;
  const Axis a = Axis::stretched(-4.0, 10.0, -0.5, 1.5, h, rmax);
  EXPECT_DOUBLE_EQ(a.lo(), -4.0);
  EXPECT_DOUBLE_EQ(a.hi(), 10.0);
  EXPECT_LE(a.max_stretch_ratio(), rmax * (1 + 1e-12));
  int core = 0;
  for (int i = 0; i < a.size(); ++i) {
    const double c = a.centre(i);
    if (c > -0.5 && c < 1.5) {
      EXPECT_NEAR(a.width(i), h, 1e-12) << "core cell " << i;
      ++core;
    }
  }
  EXPECT_EQ(core, 40);
  // Cells grow monotonically away from the core on both sides, and the core faces are exact.
  for (int i = 1; i < a.size(); ++i) {
    if (a.face(i) <= -0.5 + 1e-12) {
      EXPECT_LE(a.width(i), a.width(i - 1) * (1 + 1e-12));
    }
    if (a.face(i) >= 1.5 - 1e-12) {
      EXPECT_GE(a.width(i), a.width(i - 1) * (1 - 1e-12));
    }
  }
  // The fewest cells: with one cell fewer per side the ratio would have to exceed rmax. A lower
  // bound on the count follows from the geometric sum with ratio rmax.
  const double left = 3.5, right = 8.5;
  auto min_cells = [&](double L) {
    int m = 0;
    double s = 0, w = h;
    while (s < L) w *= rmax, s += w, ++m;
    return m;
  };
  EXPECT_EQ(a.size(), 40 + min_cells(left) + min_cells(right));
}

TEST(Axis, StretchedCountGivesExactCount) {
  for (int n : {32, 64, 96, 128}) {
    const Axis a = Axis::stretched_count(-3.0, 6.0, -0.5, 1.0, n, 1.08);
    EXPECT_EQ(a.size(), n);
    EXPECT_DOUBLE_EQ(a.lo(), -3.0);
    EXPECT_DOUBLE_EQ(a.hi(), 6.0);
    EXPECT_LE(a.max_stretch_ratio(), 1.08 * (1 + 1e-9));
  }
  EXPECT_THROW(Axis::stretched_count(-100.0, 100.0, -0.5, 1.0, 8, 1.05), std::invalid_argument);
}

TEST(Axis, NestedHasFineCoreCoarserBoxAndBoundedRatios) {
  // A cylinder of diameter 0.1 at x = 0.2 in a channel [0, 2.2]: D/48 around the body, D/24 in the
  // wake box, 1.05 stretching to the ends.
  const double hc = 0.1 / 48, hb = 0.1 / 24;
  const Axis a = Axis::nested(0.0, 2.2, 0.125, 0.3, hc, 0.05, 0.6, hb, 1.1, 1.05, 8);
  EXPECT_DOUBLE_EQ(a.lo(), 0.0);
  EXPECT_DOUBLE_EQ(a.hi(), 2.2);
  EXPECT_EQ(a.size() % 8, 0);
  int core = 0, box = 0;
  for (int i = 0; i < a.size(); ++i) {
    const double c = a.centre(i);
    if (c > 0.125 && c < 0.3) {
      EXPECT_NEAR(a.width(i), hc, 1e-12) << "core cell " << i;
      ++core;
    } else if (c > 0.05 && c < 0.6) {
      EXPECT_GT(a.width(i), hc * (1 + 1e-9)) << "transition/box cell " << i;
      EXPECT_LT(a.width(i), hb * 1.1) << "transition/box cell " << i;
      if (std::abs(a.width(i) / hb - 1) < 0.1) ++box;
    }
  }
  EXPECT_EQ(core, 84);
  EXPECT_GE(box, 75);  // (0.6 - 0.3 + 0.125 - 0.05) / hb = 90 less the two transitions
  // Transition ratio 1.1 and the rounding of the box count; 1.05 outside.
  EXPECT_LE(a.max_stretch_ratio(), 1.1 * 1.1);
  bool face_on_core = false;
  for (double f : a.faces()) face_on_core = face_on_core || std::abs(f - 0.3) < 1e-14;
  EXPECT_TRUE(face_on_core);
  // h_core = h_box: no transition cells, one uniform region from box_lo to box_hi.
  const Axis u = Axis::nested(0.0, 2.2, 0.125, 0.3, hb, 0.05, 0.6, hb, 1.1, 1.05);
  for (int i = 0; i < u.size(); ++i) {
    if (u.centre(i) > 0.05 && u.centre(i) < 0.6) {
      EXPECT_NEAR(u.width(i), hb, 0.05 * hb);
    }
  }
  // A box side too close to the core is widened to hold the transition and one box cell; a domain
  // too short for it is rejected.
  const Axis w = Axis::nested(0.0, 2.2, 0.125, 0.3, hc, 0.12, 0.6, hb, 1.1, 1.05);
  EXPECT_LE(w.max_stretch_ratio(), 1.1 * 1.1);
  for (int i = 0; i < w.size(); ++i) {
    if (w.centre(i) > 0.125 && w.centre(i) < 0.3) {
      EXPECT_NEAR(w.width(i), hc, 1e-12);
    }
  }
  EXPECT_THROW(Axis::nested(0.11, 2.2, 0.125, 0.3, hc, 0.12, 0.6, hb, 1.1, 1.05), std::invalid_argument);
  EXPECT_THROW(Axis::nested(0.0, 2.2, 0.125, 0.3, hb, 0.05, 0.6, hc, 1.1, 1.05), std::invalid_argument);
}

TEST(Axis, CoarsenedTakesEveryOtherFace) {
  const Axis a = Axis::stretched_count(-3.0, 6.0, -0.5, 1.0, 64, 1.1);
  const Axis c = a.coarsened();
  ASSERT_EQ(c.size(), 32);
  for (int i = 0; i <= 32; ++i) EXPECT_EQ(c.face(i), a.face(2 * i));
  EXPECT_THROW(Axis::uniform(0, 1, 5).coarsened(), std::logic_error);
}

TEST(Axis, RefinedSamplesTheSameMapping) {
  const Axis a = Axis::stretched_count(-3.0, 6.0, -0.5, 1.0, 32, 1.2);
  const Axis r = a.refined(), rr = r.refined();
  ASSERT_EQ(r.size(), 64);
  ASSERT_EQ(rr.size(), 128);
  for (int i = 0; i <= 32; ++i) EXPECT_EQ(r.face(2 * i), a.face(i));
  // The uniform core stays uniform away from its ends (cubic interpolation is exact on linear data;
  // within two coarse cells of the junction the stencil reaches into the stretched part).
  int checked = 0;
  for (int i = 0; i < 64; ++i) {
    if (r.face(i) >= -0.5 + 0.3 && r.face(i + 1) <= 1.0 - 0.3) {
      EXPECT_NEAR(r.width(i), 0.5 * a.width(i / 2), 1e-12);
      ++checked;
    }
  }
  EXPECT_GT(checked, 4);
  // Smooth mapping: the neighbour ratio approaches 1 like the square root per refinement.
  EXPECT_NEAR(r.max_stretch_ratio() - 1, (a.max_stretch_ratio() - 1) / 2, 0.25 * (a.max_stretch_ratio() - 1));
  EXPECT_NEAR(rr.max_stretch_ratio() - 1, (r.max_stretch_ratio() - 1) / 2, 0.25 * (r.max_stretch_ratio() - 1));
}

TEST(StretchedGrid, TwoAndThreeDimensional) {
  const StretchedGrid g2(Axis::uniform(0, 2, 4), Axis::uniform(0, 1, 8));
  EXPECT_EQ(g2.dim(), 2);
  EXPECT_EQ(g2.nz(), 1);
  EXPECT_EQ(g2.cells(), 32u);
  EXPECT_DOUBLE_EQ(g2.volume(0, 0, 0), 0.5 * 0.125);
  EXPECT_DOUBLE_EQ(g2.max_aspect_ratio(), 4.0);

  const StretchedGrid g3(Axis::uniform(0, 1, 4), Axis::uniform(0, 1, 4), Axis::uniform(0, 1, 2));
  EXPECT_EQ(g3.cells(), 32u);
  const StretchedGrid c = g3.coarsened({true, true, false});
  EXPECT_EQ(c.nx(), 2);
  EXPECT_EQ(c.ny(), 2);
  EXPECT_EQ(c.nz(), 2);
}

TEST(Field, LayoutIsContiguousXFastestWithGhosts) {
  const StretchedGrid g(Axis::uniform(0, 1, 5), Axis::uniform(0, 1, 4), Axis::uniform(0, 1, 3));
  Field f(g, 1);
  EXPECT_EQ(f.stride_y(), 7);
  EXPECT_EQ(f.stride_z(), 7 * 6);
  EXPECT_EQ(f.index(1, 0, 0) - f.index(0, 0, 0), 1);
  EXPECT_EQ(f.index(-1, -1, -1), 0);
  EXPECT_EQ(f.index(5, 4, 3), 7 * 6 * 5 - 1);
  f.fill(2.0);
  EXPECT_DOUBLE_EQ(dot(f, f), 4.0 * 60);
  f(-1, 0, 0) = 1e9;  // ghosts never enter reductions
  EXPECT_DOUBLE_EQ(norm2(f), std::sqrt(4.0 * 60));

  const StretchedGrid g2(Axis::uniform(0, 1, 5), Axis::uniform(0, 1, 4));
  Field f2(g2, 1);
  EXPECT_EQ(f2.index(0, 0, 0), 7 + 1);  // no ghost layer in z for 2-D fields
}

// Every term once, whatever n is against the eight lanes (integers, so the sum is exact), and
// lines of 5, 8 and 13 cells give the inner product of the whole interior.
TEST(Field, LaneSumAddsEveryTermOnce) {
  for (int n = 0; n <= 27; ++n)
    EXPECT_EQ(lane_sum(n, [](int i) { return static_cast<double>(i + 1); }), n * (n + 1) / 2.0) << "n = " << n;
  for (int nx : {5, 8, 13}) {
    const StretchedGrid g(Axis::uniform(0, 1, nx), Axis::uniform(0, 1, 3), Axis::uniform(0, 1, 2));
    Field a(g, 1), b(g, 1);
    double expected = 0;
    for (int k = 0; k < 2; ++k)
      for (int j = 0; j < 3; ++j)
        for (int i = 0; i < nx; ++i) {
          a(i, j, k) = i + 10 * j + 100 * k;
          b(i, j, k) = 1 + (i % 3);
          expected += a(i, j, k) * b(i, j, k);
        }
    EXPECT_EQ(dot(a, b), expected) << "nx = " << nx;
  }
}

TEST(FaceCoefficients, MaskZeroesEveryFaceOfSolidCells) {
  const StretchedGrid g(Axis::uniform(0, 1, 4), Axis::uniform(0, 1, 4), Axis::uniform(0, 1, 4));
  FaceCoefficients beta(g, 1.0);
  const auto n = beta.mask_cells([](int i, int j, int k) { return i == 1 && j == 2 && k == 3; });
  EXPECT_EQ(n, 1u);
  EXPECT_EQ(beta(0, 1, 2, 3), 0.0);
  EXPECT_EQ(beta(0, 2, 2, 3), 0.0);
  EXPECT_EQ(beta(1, 1, 2, 3), 0.0);
  EXPECT_EQ(beta(1, 1, 3, 3), 0.0);
  EXPECT_EQ(beta(2, 1, 2, 3), 0.0);
  EXPECT_EQ(beta(2, 1, 2, 4), 0.0);
  EXPECT_EQ(beta(0, 3, 2, 3), 1.0);
  double sum = 0;
  for (int d = 0; d < 3; ++d)
    for (double v : beta.values(d)) sum += v;
  EXPECT_EQ(sum, 3 * 80 - 6);
}

}  // namespace
}  // namespace finverse::cfd
