// The DFG benchmark's grid (dfg_benchmark.hpp, dfg_grid): the uniform box around the cylinder is
// symmetric about its centre, and wall_stretch_ratio sets the growth between the box and the
// channel walls on its own: 1 keeps the box's spacing out to the walls (the Stokes layers that the
// passing vortices drive there), while the default ratio 1.05 lets the cells grow, as it still
// does towards the outlet.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "cfd/dfg_benchmark.hpp"

namespace finverse::cfd {
namespace {

double widest(const Axis& a, double lo, double hi) {
  double w = 0;
  for (int i = 0; i < a.size(); ++i)
    if (a.face(i) >= lo - 1e-12 && a.face(i + 1) <= hi + 1e-12) w = std::max(w, a.width(i));
  return w;
}

TEST(DfgGrid, WallStretchRatioOfOneKeepsTheBoxSpacingOutToTheWalls) {
  DfgSetup ds;
  ds.variant = 2;
  ds.cells_per_diameter = 16;
  ds.core_cells_per_diameter = 32;
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

TEST(DfgGrid, BoxIsSymmetricAboutTheCylinder) {
  DfgSetup ds;
  ds.variant = 2;
  ds.cells_per_diameter = 16;
  ds.core_cells_per_diameter = 32;
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
