// Geometry of a flat triangle in its own plane and the isotropic plane-stress law: what the local
// membrane (opt_membrane.hpp) and plate (dkt_plate.hpp) triangles share.
#pragma once

#include <Eigen/Core>

namespace finverse::fem {

// Corner coordinates (x, y) in the element plane, one row per corner, counter-clockwise.
using TriangleXY = Eigen::Matrix<double, 3, 2>;

// Area, positive for counter-clockwise corners.
inline double signed_area(const TriangleXY& xy) {
  return 0.5 * ((xy(1, 0) - xy(0, 0)) * (xy(2, 1) - xy(0, 1)) -
                (xy(2, 0) - xy(0, 0)) * (xy(1, 1) - xy(0, 1)));
}

// sigma = C eps with eps = [eps_xx, eps_yy, gamma_xy] (engineering shear strain).
inline Eigen::Matrix3d plane_stress_matrix(double youngs_modulus, double poisson_ratio) {
  const double c = youngs_modulus / (1.0 - poisson_ratio * poisson_ratio);
  Eigen::Matrix3d C;
  C << c, c * poisson_ratio, 0, c * poisson_ratio, c, 0, 0, 0, 0.5 * c * (1.0 - poisson_ratio);
  return C;
}

}  // namespace finverse::fem
