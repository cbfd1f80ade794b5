// Linear flat shell triangle in its own plane: the local element of the corotational shell
// (corotational_shell.hpp).
//
// Membrane: ANDES OPT with drilling freedoms (opt_membrane.hpp); bending: DKT (dkt_plate.hpp).
// The two are uncoupled in the element's own frame (a flat, homogeneous, symmetric section);
// membrane-bending coupling of a curved shell comes from the facet orientation, and its geometric
// nonlinearity from the corotational wrapper. Freedoms per corner in the local frame
// [u v w theta_x theta_y theta_z] (theta_z the drilling rotation), the same order as a global node.
#pragma once

#include <Eigen/Core>

#include "fem/plane_stress.hpp"

namespace finverse::fem {

using Mat18 = Eigen::Matrix<double, 18, 18>;
using Vec18 = Eigen::Matrix<double, 18, 1>;

// 18x18 local stiffness; corners counter-clockwise in (x, y).
Mat18 flat_shell_stiffness(const TriangleXY& xy, double youngs_modulus, double poisson_ratio,
                           double thickness);

}  // namespace finverse::fem
