// Finite rotations on SO(3) with the rotation vector as parametrisation.
//
// Conventions (Battini & Pacoste 2002, Comput. Methods Appl. Mech. Engrg. 191:1755):
//   R = exp(skew(theta))                                   (Rodrigues)
//   a variation is a *spatial spin* dw:  dR = skew(dw) R    (rotations updated multiplicatively,
//                                                            R <- exp(skew(dw)) R)
//   dw = Ts(theta) dtheta,  Ts^-1 as in Battini & Pacoste eq. (13).
// Small-angle branches use series so that the element is smooth through theta = 0 (every element
// starts there).
#pragma once

#include <Eigen/Core>

namespace finverse::fem {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

Mat3 skew(const Vec3& v);
Vec3 unskew(const Mat3& m);         // axial vector of the skew part of m
Mat3 exp_so3(const Vec3& theta);    // Rodrigues
Vec3 log_so3(const Mat3& R);        // |result| in [0, pi]
Mat3 tangent_inverse(const Vec3& theta);  // Ts^-1(theta)

// d(Ts^-T(theta) m)/dtheta * Ts^-1(theta): the "Kh" term of the corotational tangent
// (Battini & Pacoste 2002, eq. (20)).
Mat3 tangent_inverse_derivative(const Vec3& theta, const Vec3& m);

}  // namespace finverse::fem
