// The truth surface covers exactly the template's planform and follows its rays.
#include <gtest/gtest.h>

#include <cmath>

#include "vision/fin_surface.hpp"

using namespace finverse;

TEST(FinSurface, CoversThePlanformExactly) {
  const auto fin = mesh::make_caudal_fin({});
  const auto f = vision::make_fin_surface(fin, 4);
  double area = 0;
  for (std::size_t t = 0; t < f.triangles.dim(0); ++t) {
    const auto a = f.triangles(t, 0), b = f.triangles(t, 1), c = f.triangles(t, 2);
    const double A = 0.5 * ((f.rest(b, 0) - f.rest(a, 0)) * (f.rest(c, 2) - f.rest(a, 2)) -
                            (f.rest(b, 2) - f.rest(a, 2)) * (f.rest(c, 0) - f.rest(a, 0)));
    EXPECT_GT(A, 0);  // counter-clockwise in (x, z), no folds
    area += A;
  }
  EXPECT_NEAR(area, fin.area(), 1e-12 * fin.area());
  // Ray vertices: on the ray (distance 0), eta +1 .. -1, half width from the template's section.
  const std::size_t m = fin.rays[0].points.size();
  for (std::size_t r = 0; r < fin.ray_count(); ++r)
    for (std::size_t k = 0; k < m; ++k) {
      const std::size_t i = r * 4 * m + k;
      EXPECT_EQ(f.rest(i, 0), fin.rays[r].points[k][0]);
      EXPECT_EQ(f.rest(i, 2), fin.rays[r].points[k][1]);
      EXPECT_EQ(f.ray_distance[i], 0.0);
      EXPECT_NEAR(f.eta[i], 1.0 - 2.0 * r / 19, 1e-15);
      EXPECT_NEAR(f.ray_half_width[i], 0.5 * fin.rays[r].sections[k].width, 1e-15);
    }
}
