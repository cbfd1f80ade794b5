// Flat shell triangle = OPT membrane + DKT plate (see flat_shell_triangle.hpp).
#include "fem/flat_shell_triangle.hpp"

#include "fem/dkt_plate.hpp"
#include "fem/opt_membrane.hpp"

namespace finverse::fem {

Mat18 flat_shell_stiffness(const TriangleXY& xy, double E, double nu, double h) {
  const Eigen::Matrix<double, 9, 9> Km = opt_membrane_stiffness(xy, E, nu, h);
  const Eigen::Matrix<double, 9, 9> Kb = dkt_plate_stiffness(xy, E, nu, h);
  // Position of each sub-element freedom within a corner's 6 local freedoms.
  constexpr int membrane[3] = {0, 1, 5};  // u v theta_z
  constexpr int bending[3] = {2, 3, 4};   // w theta_x theta_y
  Mat18 K = Mat18::Zero();
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b)
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          K(6 * a + membrane[i], 6 * b + membrane[j]) = Km(3 * a + i, 3 * b + j);
          K(6 * a + bending[i], 6 * b + bending[j]) = Kb(3 * a + i, 3 * b + j);
        }
  return K;
}

}  // namespace finverse::fem
