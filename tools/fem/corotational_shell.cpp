// Corotational flat shell triangle: EICR kinematics, internal force, consistent tangent, mass
// (see corotational_shell.hpp).
#include "fem/corotational_shell.hpp"

#include <cmath>
#include <sstream>

#include <Eigen/Geometry>

#include "fem/errors.hpp"
#include "fem/rotation.hpp"

namespace finverse::fem {

namespace {
constexpr std::array<int, 6> kShellDofs = {0, 1, 2, 3, 4, 5};

// Side-aligned frame of a triangle; returns false when the triangle is degenerate.
bool side_aligned_frame(const Vec3& x1, const Vec3& x2, const Vec3& x3, Mat3& R) {
  const Vec3 a = x2 - x1, b = x3 - x1;
  const Vec3 n = a.cross(b);
  const double ln = n.norm(), la = a.norm();
  if (!(ln > 1e-14 * la * b.norm()) || !std::isfinite(ln)) return false;
  R.col(0) = a / la;
  R.col(2) = n / ln;
  R.col(1) = R.col(2).cross(R.col(0));
  return true;
}

std::string describe(const std::array<int, 3>& n) {
  std::ostringstream os;
  os << "shell triangle (" << n[0] << ", " << n[1] << ", " << n[2] << ")";
  return os.str();
}
}  // namespace

std::span<const int> CorotationalShell::active_dofs() const { return kShellDofs; }

CorotationalShell::CorotationalShell(int node1, int node2, int node3, const Vec3& X1,
                                     const Vec3& X2, const Vec3& X3, const Material& material,
                                     double thickness)
    : nodes_{node1, node2, node3}, material_(material), thickness_(thickness) {
  validate(material_);
  if (!(thickness > 0) || !std::isfinite(thickness))
    throw InvalidInput(describe(nodes_) + ": thickness must be finite and > 0");
  if (!side_aligned_frame(X1, X2, X3, R0_))
    throw InvalidInput(describe(nodes_) + ": degenerate (zero-area or non-finite) triangle");
  const Vec3 Xc = (X1 + X2 + X3) / 3.0;
  const std::array<Vec3, 3> X = {X1, X2, X3};
  TriangleXY xy;
  for (int a = 0; a < 3; ++a) {
    xbar0_[a] = R0_.transpose() * (X[a] - Xc);
    xy(a, 0) = xbar0_[a].x();
    xy(a, 1) = xbar0_[a].y();
  }
  area_ = signed_area(xy);
  mass_ = material_.density * thickness_ * area_;
  kl_ = flat_shell_stiffness(xy, material_.youngs_modulus, material_.poisson_ratio, thickness_);
}

struct CorotationalShell::Kinematics {
  Mat3 Rr;
  std::array<Vec3, 3> xbar;  // current corners in Rr, relative to the centroid
  Vec18 dl;                  // [u_bar_a, theta_bar_a]
};

CorotationalShell::Kinematics CorotationalShell::kinematics(const NodalState& s) const {
  Kinematics k;
  const Vec3& x1 = s.position[nodes_[0]];
  const Vec3& x2 = s.position[nodes_[1]];
  const Vec3& x3 = s.position[nodes_[2]];
  if (!side_aligned_frame(x1, x2, x3, k.Rr))
    throw NotConverged(describe(nodes_) +
                       " collapsed to zero area (or NaN position); the solution diverged");
  const Vec3 xc = (x1 + x2 + x3) / 3.0;
  const std::array<const Vec3*, 3> x = {&x1, &x2, &x3};
  for (int a = 0; a < 3; ++a) {
    k.xbar[a] = k.Rr.transpose() * (*x[a] - xc);
    k.dl.segment<3>(6 * a) = k.xbar[a] - xbar0_[a];
    k.dl.segment<3>(6 * a + 3) = log_so3(k.Rr.transpose() * s.rotation[nodes_[a]] * R0_);
  }
  return k;
}

Vec18 CorotationalShell::local_deformation(const NodalState& s) const { return kinematics(s).dl; }

Mat3 CorotationalShell::corotated_frame(const NodalState& s) const { return kinematics(s).Rr; }

double CorotationalShell::strain_energy(const NodalState& s) const {
  const Kinematics k = kinematics(s);
  return 0.5 * k.dl.dot(kl_ * k.dl);
}

// The variations of the local freedoms in terms of the global ones: the frame spin w_r = G dd_bar
// and the projector P = I - T_c - S G (see the header), and H = blockdiag(I, Ts^-1(theta_bar_a)).
// What internal_force and viscous_force share.
struct CorotationalShell::Projection {
  std::array<Mat3, 3> Ti;  // Ts^-1(theta_bar_a)
  Eigen::Matrix<double, 3, 18> G;
  Eigen::Matrix<double, 18, 3> S;
  Mat18 P;
  double x21, x31, y31, x32, A2;
};

CorotationalShell::Projection CorotationalShell::projection(const Kinematics& k) const {
  Projection p;
  for (int a = 0; a < 3; ++a) p.Ti[a] = tangent_inverse(k.dl.segment<3>(6 * a + 3));
  // In Rr, y21 = 0 and all z = 0, so
  //   w_1 = (x32 w1 - x31 w2 + x21 w3) / (x21 y31), w_2 = (w1 - w2) / x21, w_3 = (v2 - v1) / x21.
  p.x21 = k.xbar[1].x() - k.xbar[0].x();
  p.x31 = k.xbar[2].x() - k.xbar[0].x();
  p.y31 = k.xbar[2].y() - k.xbar[0].y();
  p.x32 = p.x31 - p.x21, p.A2 = p.x21 * p.y31;
  auto& G = p.G;
  G.setZero();
  G(0, 2) = p.x32 / p.A2, G(0, 8) = -p.x31 / p.A2, G(0, 14) = p.x21 / p.A2;
  G(1, 2) = 1.0 / p.x21, G(1, 8) = -1.0 / p.x21;
  G(2, 1) = -1.0 / p.x21, G(2, 7) = 1.0 / p.x21;
  p.P.setIdentity();
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) p.P.block<3, 3>(6 * a, 6 * b) -= Mat3::Identity() / 3.0;
    p.S.block<3, 3>(6 * a, 0) = -skew(k.xbar[a]);
    p.S.block<3, 3>(6 * a + 3, 0) = Mat3::Identity();
  }
  p.P -= p.S * G;
  return p;
}

void CorotationalShell::viscous_force(const NodalState& s, const Eigen::Ref<const Eigen::VectorXd>& v, double eta,
                                      VectorRef f, MatrixRef* C) const {
  // d_l_dot = H P E^T v: the rate of the local deformation, zero for a rigid motion.
  const Kinematics k = kinematics(s);
  const Projection p = projection(k);
  Mat18 D = p.P;
  for (int a = 0; a < 3; ++a) D.middleRows<3>(6 * a + 3) = (p.Ti[a] * D.middleRows<3>(6 * a + 3)).eval();
  for (int b = 0; b < 6; ++b) D.middleCols<3>(3 * b) = (D.middleCols<3>(3 * b) * k.Rr.transpose()).eval();
  f = D.transpose() * (eta * (kl_ * (D * v)));
  if (C) *C = D.transpose() * (eta * kl_) * D;
}

void CorotationalShell::internal_force(const NodalState& s, VectorRef f_out,
                                       MatrixRef* K_out) const {
  const Kinematics k = kinematics(s);
  const Vec18 fl = kl_ * k.dl;
  const Projection p = projection(k);
  const auto& [Ti, G, S, P, x21, x31, y31, x32, A2] = p;

  // h = H^T f_l: moments conjugate to the local spins.
  Vec18 h = fl;
  for (int a = 0; a < 3; ++a) h.segment<3>(6 * a + 3) = Ti[a].transpose() * fl.segment<3>(6 * a + 3);

  const Vec18 ft = P.transpose() * h;  // projected (self-equilibrated) local force
  for (int a = 0; a < 6; ++a) f_out.segment<3>(3 * a) = k.Rr * ft.segment<3>(3 * a);
  if (!K_out) return;

  // Material part and the derivative of Ts^-T (K_M).
  // H^T K_l H without forming H: scale the rotational row/column blocks.
  Mat18 KlH = kl_;
  for (int a = 0; a < 3; ++a) {
    KlH.middleCols<3>(6 * a + 3) = (KlH.middleCols<3>(6 * a + 3) * Ti[a]).eval();
  }
  for (int a = 0; a < 3; ++a) {
    KlH.middleRows<3>(6 * a + 3) = (Ti[a].transpose() * KlH.middleRows<3>(6 * a + 3)).eval();
    KlH.block<3, 3>(6 * a + 3, 6 * a + 3) +=
        tangent_inverse_derivative(k.dl.segment<3>(6 * a + 3), fl.segment<3>(6 * a + 3));
  }
  Mat18 Kh = P.transpose() * KlH * P;

  // K_GR = -F_nm G: the projected forces turn with the frame.
  Eigen::Matrix<double, 18, 3> Fnm;
  for (int a = 0; a < 6; ++a) Fnm.block<3, 3>(3 * a, 0) = skew(ft.segment<3>(3 * a));
  Kh -= Fnm * G;

  // K_GP = G^T F_n P: the lever arms x_bar_a in S move with the deformational translations.
  Eigen::Matrix<double, 3, 18> FnP = Eigen::Matrix<double, 3, 18>::Zero();
  for (int a = 0; a < 3; ++a) FnP += skew(h.segment<3>(6 * a)) * P.middleRows<3>(6 * a);
  Kh += G.transpose() * FnP;

  // Variation of G acting on v = S^T h (see header). G depends on x21, x31, y31 only, whose
  // variations are rows of P.
  const Vec3 v = S.transpose() * h;
  Eigen::Matrix<double, 18, 3> dGv = Eigen::Matrix<double, 18, 3>::Zero();
  const double x21s = x21 * x21, y31s = y31 * y31;
  // d/dx21
  dGv(2, 0) = -v(0) * x31 / (x21s * y31) - v(1) / x21s;
  dGv(8, 0) = v(0) * x31 / (x21s * y31) + v(1) / x21s;
  dGv(1, 0) = v(2) / x21s;
  dGv(7, 0) = -v(2) / x21s;
  // d/dx31
  dGv(2, 1) = v(0) / A2;
  dGv(8, 1) = -v(0) / A2;
  // d/dy31
  dGv(2, 2) = -v(0) * x32 / (x21 * y31s);
  dGv(8, 2) = v(0) * x31 / (x21 * y31s);
  dGv(14, 2) = -v(0) / y31s;
  Eigen::Matrix<double, 3, 18> J;
  J.row(0) = P.row(6) - P.row(0);
  J.row(1) = P.row(12) - P.row(0);
  J.row(2) = P.row(13) - P.row(1);
  Kh -= dGv * J;

  // K = E Kh E^T
  auto& K = *K_out;
  for (int a = 0; a < 6; ++a)
    for (int b = 0; b < 6; ++b)
      K.block<3, 3>(3 * a, 3 * b) = k.Rr * Kh.block<3, 3>(3 * a, 3 * b) * k.Rr.transpose();
}

void CorotationalShell::mass_matrix(const NodalState&, MatrixRef M) const {
  M.setZero();
  const double m = mass_ / 12.0;
  const double rotary = mass_ * thickness_ * thickness_ / 36.0;
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b)
      M.block<3, 3>(6 * a, 6 * b).diagonal().setConstant(a == b ? 2.0 * m : m);
    M.block<3, 3>(6 * a + 3, 6 * a + 3).diagonal().setConstant(rotary);
  }
}

void CorotationalShell::gravity_force(const NodalState&, const Vec3& g, VectorRef f) const {
  f.setZero();
  for (int a = 0; a < 3; ++a) f.segment<3>(6 * a) = (mass_ / 3.0) * g;
}

}  // namespace finverse::fem
