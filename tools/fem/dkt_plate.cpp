// DKT plate stiffness (see dkt_plate.hpp).
#include "fem/dkt_plate.hpp"

namespace finverse::fem {

namespace {
// beta at corner i in terms of q: beta = (theta_y, -theta_x).
Eigen::Matrix<double, 2, 9> corner_beta(int i) {
  Eigen::Matrix<double, 2, 9> m = Eigen::Matrix<double, 2, 9>::Zero();
  m(0, 3 * i + 2) = 1.0;
  m(1, 3 * i + 1) = -1.0;
  return m;
}

// beta at the mid-point of side i -> j: tangential part from the Kirchhoff constraint on the
// cubic (Hermite) side interpolation of w, normal part the mean of the corners.
Eigen::Matrix<double, 2, 9> midside_beta(const TriangleXY& xy, int i, int j) {
  const Eigen::Vector2d e = xy.row(j).transpose() - xy.row(i).transpose();
  const double l = e.norm();
  const Eigen::Vector2d s = e / l, n(s.y(), -s.x());
  const Eigen::Matrix<double, 2, 9> bi = corner_beta(i), bj = corner_beta(j);
  // w,s(mid) = 3/(2l) (w_j - w_i) - (w,s_i + w,s_j)/4 and w,s = -beta.s at the corners.
  Eigen::Matrix<double, 1, 9> beta_s = -0.25 * s.transpose() * (bi + bj);
  beta_s(3 * j) -= 1.5 / l;
  beta_s(3 * i) += 1.5 / l;
  const Eigen::Matrix<double, 1, 9> beta_n = 0.5 * n.transpose() * (bi + bj);
  return s * beta_s + n * beta_n;
}
}  // namespace

Eigen::Matrix<double, 3, 9> dkt_curvature_matrix(const TriangleXY& xy, double L1, double L2) {
  const double L[3] = {L1, L2, 1.0 - L1 - L2};
  const double A2 = 2.0 * signed_area(xy);
  // dL_i/dx = b_i / 2A, dL_i/dy = c_i / 2A
  double b[3], c[3];
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    b[i] = (xy(j, 1) - xy(k, 1)) / A2;
    c[i] = (xy(k, 0) - xy(j, 0)) / A2;
  }
  // Quadratic shape functions: corners L_i (2 L_i - 1), mid-side of (j, k): 4 L_j L_k.
  Eigen::Matrix<double, 2, 9> dbeta_dx = Eigen::Matrix<double, 2, 9>::Zero(), dbeta_dy = dbeta_dx;
  for (int i = 0; i < 3; ++i) {
    const double dN = 4.0 * L[i] - 1.0;
    dbeta_dx += dN * b[i] * corner_beta(i);
    dbeta_dy += dN * c[i] * corner_beta(i);
  }
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;  // side (j, k) is opposite corner i
    const Eigen::Matrix<double, 2, 9> bm = midside_beta(xy, j, k);
    dbeta_dx += 4.0 * (b[j] * L[k] + L[j] * b[k]) * bm;
    dbeta_dy += 4.0 * (c[j] * L[k] + L[j] * c[k]) * bm;
  }
  Eigen::Matrix<double, 3, 9> B;
  B.row(0) = dbeta_dx.row(0);
  B.row(1) = dbeta_dy.row(1);
  B.row(2) = dbeta_dy.row(0) + dbeta_dx.row(1);
  return B;
}

Eigen::Matrix<double, 9, 9> dkt_plate_stiffness(const TriangleXY& xy, double E, double nu,
                                                double h) {
  const Eigen::Matrix3d D = plane_stress_matrix(E, nu) * (h * h * h / 12.0);
  const double A = signed_area(xy);
  Eigen::Matrix<double, 9, 9> K = Eigen::Matrix<double, 9, 9>::Zero();
  // Mid-side points, weight A/3 each: exact for the quadratic integrand.
  const double pts[3][2] = {{0.5, 0.5}, {0.0, 0.5}, {0.5, 0.0}};
  for (const auto& p : pts) {
    const Eigen::Matrix<double, 3, 9> B = dkt_curvature_matrix(xy, p[0], p[1]);
    K += (A / 3.0) * B.transpose() * D * B;
  }
  return 0.5 * (K + K.transpose());
}

}  // namespace finverse::fem
