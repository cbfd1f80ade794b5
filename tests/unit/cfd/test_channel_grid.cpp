// The grid of the cylinder-in-a-channel benchmarks (cylinder_channel.hpp, channel_grid; the DFG
// driver's dfg_grid): the core and box hold their spacings, the counts allow three multigrid
// halvings, the uniform box around the cylinder is symmetric about its centre, and
// wall_stretch_ratio sets the growth between the box and the channel walls on its own: 1 keeps the
// box's spacing out to the walls (the Stokes layers that the passing vortices drive there), while
// the default ratio 1.05 lets the cells grow, as it still does towards the outlet, and a ratio
// below 1 makes them shrink towards the walls.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "cfd/validation/cylinder_channel.hpp"
#include "cfd/validation/dfg_benchmark.hpp"
#include "core/error.hpp"

namespace finverse::cfd {
namespace {

double widest(const Axis& a, double lo, double hi) {
  double w = 0;
  for (int i = 0; i < a.size(); ++i)
    if (a.face(i) >= lo - 1e-12 && a.face(i + 1) <= hi + 1e-12) w = std::max(w, a.width(i));
  return w;
}

// DFG 2D-2 set up on a D/box box with a D/core core.
DfgSetup dfg2d2(int box, int core) {
  DfgSetup ds;
  ds.variant = 2;
  ds.cells_per_diameter = box;
  ds.core_cells_per_diameter = core;
  return ds;
}

// The Turek-Hron channel with its flag: box from 1 D before the cylinder to 2 D behind the tip.
ChannelGridSpec turek_hron_like(double h, double h_core) {
  return {.length = 2.5, .height = 0.41, .box_x0 = 0.1, .box_x1 = 0.8, .box_y0 = 0.1, .box_y1 = 0.3, .h = h,
          .core_x0 = 0.125, .core_x1 = 0.65, .core_y0 = 0.125, .core_y1 = 0.275, .h_core = h_core};
}

TEST(ChannelGrid, CoreAndBoxKeepTheirSpacingsAndTheCountsHalveThreeTimes) {
  const double h = 0.1 / 16, hc = 0.1 / 32;
  const StretchedGrid g = channel_grid(turek_hron_like(h, hc));
  const double lo[2] = {0.125, 0.125}, hi[2] = {0.65, 0.275}, blo[2] = {0.1, 0.1}, bhi[2] = {0.8, 0.3};
  const double end[2] = {2.5, 0.41};
  for (int d = 0; d < 2; ++d) {
    const Axis& a = g.axis(d);
    EXPECT_EQ(a.size() % 8, 0) << "axis " << d;
    EXPECT_DOUBLE_EQ(a.face(0), 0.0);
    EXPECT_DOUBLE_EQ(a.face(a.size()), end[d]);
    EXPECT_LE(widest(a, lo[d], hi[d]), 1.02 * hc) << "axis " << d;
    EXPECT_LE(widest(a, blo[d], bhi[d]), 1.02 * h) << "axis " << d;
    EXPECT_LE(a.max_stretch_ratio(), 1.1 + 1e-9) << "axis " << d;
  }
}

TEST(ChannelGrid, WithoutACoreTheBoxIsUniformAndAZeroWallRatioMeansTheOuterRatio) {
  ChannelGridSpec s = turek_hron_like(0.1 / 16, 0);
  const StretchedGrid plain = channel_grid(s);
  for (int d = 0; d < 2; ++d) EXPECT_EQ(plain.axis(d).size() % 8, 0);
  EXPECT_LE(widest(plain.axis(0), 0.1, 0.8), 1.02 * s.h);
  // A core no finer than the box is no core.
  s.h_core = s.h;
  EXPECT_EQ(channel_grid(s).axis(0).faces(), plain.axis(0).faces());
  s.h_core = 0;
  s.wall_ratio = s.ratio;
  EXPECT_EQ(channel_grid(s).axis(1).faces(), plain.axis(1).faces());
  // The wall ratio acts on y alone; ratio 1 leaves the wall cells as wide as the box spacing up
  // to the rounding of the count to a multiple of 8.
  s.wall_ratio = 1.0;
  const StretchedGrid walls = channel_grid(s);
  EXPECT_EQ(walls.axis(0).faces(), plain.axis(0).faces());
  EXPECT_LE(widest(walls.axis(1), 0.0, 0.41), 1.1 * s.h);
  EXPECT_GT(widest(plain.axis(1), 0.0, 0.41), 1.3 * s.h);
}

TEST(DfgGrid, WallStretchRatioOfOneKeepsTheBoxSpacingOutToTheWalls) {
  DfgSetup ds = dfg2d2(16, 32);
  const double h = 0.1 / 16;
  const StretchedGrid stretched = dfg_grid(ds);
  ds.wall_stretch_ratio = 1.0;
  const StretchedGrid uniform = dfg_grid(ds);
  const Axis &ys = stretched.axis(1), &yu = uniform.axis(1);
  EXPECT_DOUBLE_EQ(ys.face(0), 0.0);
  EXPECT_DOUBLE_EQ(yu.face(yu.size()), 0.41);
  // Ratio 1.05: the wall cells are clearly wider than the box's; ratio 1: none is.
  EXPECT_GT(widest(ys, 0.0, 0.1), 1.3 * h);
  EXPECT_GT(widest(ys, 0.3, 0.41), 1.3 * h);
  EXPECT_LE(widest(yu, 0.0, 0.41), 1.02 * h);
  EXPECT_GT(yu.size(), ys.size());
  // The x axis, and the multigrid-friendly counts, are untouched.
  EXPECT_EQ(uniform.axis(0).size(), stretched.axis(0).size());
  EXPECT_EQ(yu.size() % 8, 0);
}

TEST(DfgGrid, WallRatioBelowOneRefinesTheCellsTowardsTheWalls) {
  // 0.97 from a D/24 box: the cells shrink monotonically from the box edge to the walls, the
  // outermost is several times finer than the box (the walls' Stokes layers, about D/10 thick at
  // the shedding frequency), and the box and core keep their spacings.
  DfgSetup ds = dfg2d2(24, 48);
  ds.wall_stretch_ratio = 0.97;
  const double h = 0.1 / 24;
  const Axis y = dfg_grid(ds).axis(1);
  EXPECT_DOUBLE_EQ(y.face(0), 0.0);
  EXPECT_DOUBLE_EQ(y.face(y.size()), 0.41);
  EXPECT_EQ(y.size() % 8, 0);
  EXPECT_LT(y.width(0), 0.35 * h);
  EXPECT_LT(y.width(y.size() - 1), 0.35 * h);
  for (int i = 0; i + 1 < y.size(); ++i) {
    if (y.face(i + 2) <= 0.1 + 1e-12) {
      EXPECT_LT(y.width(i), y.width(i + 1)) << "lower wall region, cell " << i;
    }
    if (y.face(i) >= 0.3 - 1e-12) {
      EXPECT_GT(y.width(i), y.width(i + 1)) << "upper wall region, cell " << i;
    }
  }
  EXPECT_LE(y.max_stretch_ratio(), 1.1 + 1e-9);
  EXPECT_LE(widest(y, 0.1, 0.3), 1.02 * h);
  // A shrinking series that cannot reach the wall is refused.
  ds.wall_stretch_ratio = 0.9;
  EXPECT_THROW(dfg_grid(ds), std::invalid_argument);
}

TEST(DfgGrid, CoreWakeSetsHowFarTheCoreReachesBehindTheCylinder) {
  // Default: the core ends 0.75 D behind the cylinder's rear (x = 0.325); core_wake 2 carries its
  // spacing to x = 0.45, and the cells between are then no wider than the core's.
  DfgSetup ds = dfg2d2(16, 32);
  const double hc = 0.1 / 32;
  const Axis x_default = dfg_grid(ds).axis(0);
  ds.core_wake = 2.0;
  const Axis x_long = dfg_grid(ds).axis(0);
  EXPECT_LE(widest(x_long, 0.125, 0.45), 1.02 * hc);
  EXPECT_GT(widest(x_default, 0.125, 0.45), 1.3 * hc);
  EXPECT_LE(widest(x_default, 0.125, 0.325), 1.02 * hc);
  EXPECT_GT(x_long.size(), x_default.size());
  EXPECT_EQ(x_long.size() % 8, 0);
  // The core must end inside the uniform box.
  ds.core_wake = 5.0;
  EXPECT_THROW(dfg_grid(ds), Error);
}

TEST(DfgGrid, BoxIsSymmetricAboutTheCylinder) {
  DfgSetup ds = dfg2d2(16, 32);
  ds.wall_stretch_ratio = 1.0;
  const Axis y = dfg_grid(ds).axis(1);
  // Every face inside [0.1, 0.3] has its mirror image about y = 0.2.
  for (int i = 0; i <= y.size(); ++i) {
    const double f = y.face(i);
    if (f < 0.1 - 1e-12 || f > 0.3 + 1e-12) continue;
    double nearest = 1;
    for (int j = 0; j <= y.size(); ++j) nearest = std::min(nearest, std::abs(y.face(j) - (0.4 - f)));
    EXPECT_LT(nearest, 1e-12) << "face " << f;
  }
}

}  // namespace
}  // namespace finverse::cfd
