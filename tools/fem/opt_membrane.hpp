// ANDES optimal membrane triangle "OPT" with corner drilling freedoms.
//
// Felippa (2003), "A study of optimal membrane triangles with drilling freedoms", Comput. Methods
// Appl. Mech. Engrg. 192:2125-2168 (equation numbers below refer to it). Freedoms per corner:
// u, v and the drilling rotation theta_z (counter-clockwise about the normal). K = K_b + K_h:
//   K_b = V B^T C B, B = L^T / V: basic (constant-stress) stiffness from the force-lumping matrix L
//         of eq. (22) with alpha_b = 3/2; it alone passes the membrane patch test;
//   K_h = (3/4) beta_0 h A T_tu^T (Q4^T C_nat Q4 + Q5^T C_nat Q5 + Q6^T C_nat Q6) T_tu: the
//         higher-order stiffness of the deviatoric corner rotations theta_tilde = T_tu u (eq. 16,
//         corner rotation minus the CST rotation), natural strains at the midpoints from the
//         optimal beta_1..9 = (1, 2, 1, 0, 1, -1, -1, -1, -2) (eq. 29), C_nat = Te^T C Te (eq. 12),
//         beta_0 = max(1/2 (1 - 4 nu^2), 0.01).
// Why OPT and not the CST or Allman's triangle: the drilling freedom is needed anyway (6 DOF nodes
// shared with beams), and OPT is exact for in-plane pure bending of rectangular meshes, so a fin
// membrane bent in its own plane does not lock the way a CST does; K_h vanishes on constant-strain
// states, so the patch test is not disturbed.
#pragma once

#include <Eigen/Core>

#include "fem/plane_stress.hpp"

namespace finverse::fem {

// 9x9 stiffness, DOFs ordered [u1 v1 tz1 u2 v2 tz2 u3 v3 tz3]; corners counter-clockwise.
Eigen::Matrix<double, 9, 9> opt_membrane_stiffness(const TriangleXY& xy, double youngs_modulus,
                                                   double poisson_ratio, double thickness);

// Constant (mean) strain [eps_xx, eps_yy, gamma_xy] = B d of the basic part.
Eigen::Matrix<double, 3, 9> opt_membrane_strain_matrix(const TriangleXY& xy);

}  // namespace finverse::fem
