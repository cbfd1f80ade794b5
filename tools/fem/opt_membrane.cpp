// ANDES OPT membrane stiffness (see opt_membrane.hpp).
#include "fem/opt_membrane.hpp"

#include <algorithm>

namespace finverse::fem {

namespace {
constexpr double kAlphaB = 1.5;
constexpr double kBeta[9] = {1, 2, 1, 0, 1, -1, -1, -1, -2};

struct Sides {
  double x12, x23, x31, y12, y23, y31;  // xij = xi - xj
  double x21() const { return -x12; }
  double x32() const { return -x23; }
  double x13() const { return -x31; }
  double y21() const { return -y12; }
  double y32() const { return -y23; }
  double y13() const { return -y31; }
};

Sides sides(const TriangleXY& xy) {
  return {xy(0, 0) - xy(1, 0), xy(1, 0) - xy(2, 0), xy(2, 0) - xy(0, 0),
          xy(0, 1) - xy(1, 1), xy(1, 1) - xy(2, 1), xy(2, 1) - xy(0, 1)};
}
}  // namespace

Eigen::Matrix<double, 3, 9> opt_membrane_strain_matrix(const TriangleXY& xy) {
  const Sides s = sides(xy);
  const double A = signed_area(xy);
  const double a = kAlphaB / 6.0;
  Eigen::Matrix<double, 3, 9> B;
  // Columns: the constant strain a unit value of each freedom produces (L^T / V, eq. 22). The
  // drilling columns are the quadratic in-plane modes of Allman type scaled by alpha_b.
  B.col(0) << s.y23, 0, s.x32();
  B.col(1) << 0, s.x32(), s.y23;
  B.col(2) << a * s.y23 * (s.y13() - s.y21()), a * s.x32() * (s.x31 - s.x12),
      2 * a * (s.x31 * s.y13() - s.x12 * s.y21());
  B.col(3) << s.y31, 0, s.x13();
  B.col(4) << 0, s.x13(), s.y31;
  B.col(5) << a * s.y31 * (s.y21() - s.y32()), a * s.x13() * (s.x12 - s.x23),
      2 * a * (s.x12 * s.y21() - s.x23 * s.y32());
  B.col(6) << s.y12, 0, s.x21();
  B.col(7) << 0, s.x21(), s.y12;
  B.col(8) << a * s.y12 * (s.y32() - s.y13()), a * s.x21() * (s.x23 - s.x31),
      2 * a * (s.x23 * s.y32() - s.x31 * s.y13());
  return B / (2.0 * A);
}

Eigen::Matrix<double, 9, 9> opt_membrane_stiffness(const TriangleXY& xy, double E, double nu,
                                                   double h) {
  const Sides s = sides(xy);
  const double A = signed_area(xy);
  const Eigen::Matrix3d C = plane_stress_matrix(E, nu);

  const Eigen::Matrix<double, 3, 9> B = opt_membrane_strain_matrix(xy);
  Eigen::Matrix<double, 9, 9> K = (A * h) * B.transpose() * C * B;

  // Deviatoric corner rotations: theta_tilde_i = theta_i - theta_CST, theta_CST = (v,x - u,y)/2
  // of the linear displacement field (eq. 16).
  Eigen::Matrix<double, 3, 9> Ttu = Eigen::Matrix<double, 3, 9>::Zero();
  const double r = 1.0 / (4.0 * A);
  const double row[9] = {s.x32() * r, s.y32() * r, 0, s.x13() * r, s.y13() * r, 0,
                         s.x21() * r, s.y21() * r, 0};
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 9; ++j) Ttu(i, j) = row[j];
    Ttu(i, 3 * i + 2) = 1.0;
  }

  // Natural (side) strains -> Cartesian strains (strain-gauge rosette, eq. 12).
  const double l21 = s.x12 * s.x12 + s.y12 * s.y12;
  const double l32 = s.x23 * s.x23 + s.y23 * s.y23;
  const double l13 = s.x31 * s.x31 + s.y31 * s.y31;
  Eigen::Matrix3d Te;
  Te << s.y23 * s.y13() * l21, s.y31 * s.y21() * l32, s.y12 * s.y32() * l13,  //
      s.x23 * s.x13() * l21, s.x31 * s.x21() * l32, s.x12 * s.x32() * l13,    //
      (s.y23 * s.x31 + s.x32() * s.y13()) * l21, (s.y31 * s.x12 + s.x13() * s.y21()) * l32,
      (s.y12 * s.x23 + s.x21() * s.y32()) * l13;
  Te /= 4.0 * A * A;
  const Eigen::Matrix3d Cnat = Te.transpose() * C * Te;

  // Natural strains at the corners from the deviatoric rotations (eq. 29): the corner-i matrix is
  // the corner-1 pattern of the betas with the corners cyclically permuted.
  const double* b = kBeta;
  auto Q = [&](int p0, int p1, int p2, int p3, int p4, int p5, int p6, int p7, int p8) {
    Eigen::Matrix3d q;
    q << b[p0] / l21, b[p1] / l21, b[p2] / l21, b[p3] / l32, b[p4] / l32, b[p5] / l32,
        b[p6] / l13, b[p7] / l13, b[p8] / l13;
    return Eigen::Matrix3d(q * (2.0 * A / 3.0));
  };
  const Eigen::Matrix3d Q1 = Q(0, 1, 2, 3, 4, 5, 6, 7, 8);
  const Eigen::Matrix3d Q2 = Q(8, 6, 7, 2, 0, 1, 5, 3, 4);
  const Eigen::Matrix3d Q3 = Q(4, 5, 3, 7, 8, 6, 1, 2, 0);
  const Eigen::Matrix3d Q4 = 0.5 * (Q1 + Q2), Q5 = 0.5 * (Q2 + Q3), Q6 = 0.5 * (Q3 + Q1);
  const double beta0 = std::max(0.5 * (1.0 - 4.0 * nu * nu), 0.01);
  const Eigen::Matrix3d Kt = (0.75 * beta0 * h * A) *
                             (Q4.transpose() * Cnat * Q4 + Q5.transpose() * Cnat * Q5 +
                              Q6.transpose() * Cnat * Q6);
  K += Ttu.transpose() * Kt * Ttu;
  return 0.5 * (K + K.transpose());
}

}  // namespace finverse::fem
