// Discrete Kirchhoff triangle (DKT) plate bending element.
//
// Batoz, Bathe & Ho (1980), "A study of three-node triangular plate bending elements", Int. J.
// Numer. Meth. Engng 15:1771-1812. Freedoms per corner: w, theta_x, theta_y (rotation vector
// components of the normal, so that beta = -grad w = (theta_y, -theta_x) at the corners under the
// Kirchhoff constraint). The normal rotations beta are interpolated quadratically over the six
// corner and mid-side points; the mid-side values are eliminated by imposing the Kirchhoff
// constraint along each side (tangential component = -dw/ds of the cubic side interpolation of w)
// and a linear variation of the normal component. Curvatures
// kappa = [beta_x,x, beta_y,y, beta_x,y + beta_y,x] are linear, so the 3-point mid-side rule
// integrates K = int B^T D B dA exactly. Here B is built from that construction directly rather
// than from the closed-form H_x, H_y coefficients of the paper; the two are algebraically equal.
// DKT passes the constant-curvature patch test for any mesh and converges to thin-plate theory.
#pragma once

#include <Eigen/Core>

#include "fem/plane_stress.hpp"

namespace finverse::fem {

// Curvature matrix kappa = B q at area coordinates (L1, L2, 1 - L1 - L2), q = [w1 tx1 ty1 w2 ...].
Eigen::Matrix<double, 3, 9> dkt_curvature_matrix(const TriangleXY& xy, double L1, double L2);

// 9x9 stiffness with D = E h^3 / (12 (1 - nu^2)) [[1 nu 0] [nu 1 0] [0 0 (1 - nu)/2]].
Eigen::Matrix<double, 9, 9> dkt_plate_stiffness(const TriangleXY& xy, double youngs_modulus,
                                                double poisson_ratio, double thickness);

}  // namespace finverse::fem
