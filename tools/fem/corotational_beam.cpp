// Corotational beam: local flexibility-based stiffness, Battini-Pacoste corotational
// transformation and consistent tangent, consistent mass (see corotational_beam.hpp).
#include "fem/corotational_beam.hpp"

#include <cmath>
#include <sstream>

#include <Eigen/Geometry>
#include <Eigen/LU>

#include "fem/errors.hpp"
#include "fem/rotation.hpp"

namespace finverse::fem {

namespace {
constexpr std::array<int, 6> kBeamDofs = {0, 1, 2, 3, 4, 5};

// E A E^T with E = blockdiag(R, R, R, R), block by block (a 12x12 GEMM costs more than the
// rest of the element).
CorotationalBeam::Mat12 rotate_blocks(const Mat3& R, const CorotationalBeam::Mat12& A) {
  CorotationalBeam::Mat12 out;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j)
      out.block<3, 3>(3 * i, 3 * j).noalias() =
          R * A.block<3, 3>(3 * i, 3 * j).lazyProduct(R.transpose());
  return out;
}
}  // namespace

std::span<const int> CorotationalBeam::active_dofs() const { return kBeamDofs; }

CorotationalBeam::CorotationalBeam(int node1, int node2, const Vec3& X1, const Vec3& X2,
                                   const Vec3& y_axis_hint, const Material& material,
                                   const TaperedRectangle& section, Options options)
    : nodes_{node1, node2}, material_(material), section_(section) {
  validate(material_);
  section_.validate();
  const Vec3 chord = X2 - X1;
  l0_ = chord.norm();
  if (!(l0_ > 0) || !std::isfinite(l0_)) {
    std::ostringstream os;
    os << "beam between nodes " << node1 << " and " << node2 << " has zero or non-finite length";
    throw InvalidInput(os.str());
  }
  const Vec3 e1 = chord / l0_;
  Vec3 e2 = y_axis_hint - y_axis_hint.dot(e1) * e1;
  if (!(e2.norm() > 1e-8 * y_axis_hint.norm())) {
    std::ostringstream os;
    os << "beam between nodes " << node1 << " and " << node2
       << ": section y-axis hint is parallel to the beam axis";
    throw InvalidInput(os.str());
  }
  e2.normalize();
  R0_.col(0) = e1;
  R0_.col(1) = e2;
  R0_.col(2) = e1.cross(e2);

  const double E = material_.youngs_modulus, G = material_.shear_modulus(), rho = material_.density;

  // Flexibilities (see header): axial, torsion, bending about local z (xy-plane), about local y.
  double fa = 0, ft = 0;
  Eigen::Matrix2d fz = Eigen::Matrix2d::Zero(), fy = Eigen::Matrix2d::Zero();
  const GaussRule ks = gauss_legendre_01(options.stiffness_gauss_points);
  for (size_t g = 0; g < ks.points.size(); ++g) {
    const double xi = ks.points[g], w = ks.weights[g] * l0_;
    const SectionConstants s = section_.at(xi);
    fa += w / (E * s.area);
    ft += w / (G * s.j);
    const Eigen::Vector2d b(xi - 1.0, xi);
    fz += (w / (E * s.iz)) * b * b.transpose();
    fy += (w / (E * s.iy)) * b * b.transpose();
  }
  const Eigen::Matrix2d kz = fz.inverse(), ky = fy.inverse();
  kl_.setZero();
  kl_(0, 0) = 1.0 / fa;
  const double kt = 1.0 / ft;
  // d_a = [u, t1x, t1y, t1z, t2x, t2y, t2z]
  kl_(1, 1) = kt, kl_(1, 4) = -kt, kl_(4, 1) = -kt, kl_(4, 4) = kt;
  kl_(2, 2) = ky(0, 0), kl_(2, 5) = ky(0, 1), kl_(5, 2) = ky(1, 0), kl_(5, 5) = ky(1, 1);
  kl_(3, 3) = kz(0, 0), kl_(3, 6) = kz(0, 1), kl_(6, 3) = kz(1, 0), kl_(6, 6) = kz(1, 1);

  // Consistent mass in the local frame; dofs [u v w tx ty tz] x 2 nodes.
  ml_.setZero();
  mass_ = 0;
  gravity_share_ = {0, 0};
  const GaussRule ms = gauss_legendre_01(options.mass_gauss_points);
  const double L = l0_;
  for (size_t g = 0; g < ms.points.size(); ++g) {
    const double xi = ms.points[g], w = ms.weights[g] * L;
    const SectionConstants s = section_.at(xi);
    const double x2 = xi * xi, x3 = x2 * xi;
    const double H1 = 1 - 3 * x2 + 2 * x3, H2 = xi - 2 * x2 + x3, H3 = 3 * x2 - 2 * x3,
                 H4 = -x2 + x3;
    const double dH1 = -6 * xi + 6 * x2, dH2 = 1 - 4 * xi + 3 * x2, dH3 = 6 * xi - 6 * x2,
                 dH4 = -2 * xi + 3 * x2;
    Eigen::Matrix<double, 6, 12> N = Eigen::Matrix<double, 6, 12>::Zero();
    N(0, 0) = 1 - xi, N(0, 6) = xi;                                           // u
    N(1, 1) = H1, N(1, 5) = L * H2, N(1, 7) = H3, N(1, 11) = L * H4;          // v
    N(2, 2) = H1, N(2, 4) = -L * H2, N(2, 8) = H3, N(2, 10) = -L * H4;        // w
    N(3, 3) = 1 - xi, N(3, 9) = xi;                                           // theta_x
    N(4, 2) = -dH1 / L, N(4, 4) = dH2, N(4, 8) = -dH3 / L, N(4, 10) = dH4;    // theta_y = -w'
    N(5, 1) = dH1 / L, N(5, 5) = dH2, N(5, 7) = dH3 / L, N(5, 11) = dH4;      // theta_z = v'
    Eigen::Matrix<double, 6, 1> d;
    d << s.area, s.area, s.area, s.polar(), s.iy, s.iz;
    d *= rho;
    ml_ += w * N.transpose() * d.asDiagonal() * N;
    mass_ += w * rho * s.area;
    gravity_share_[0] += w * rho * s.area * (1 - xi);
    gravity_share_[1] += w * rho * s.area * xi;
  }
}

// Everything the force, tangent and energy need from one configuration.
struct CorotationalBeam::Kinematics {
  Mat3 Rr;          // corotated frame [r1 r2 r3]
  double ln = 0;    // current chord length
  Vec3 q1l, q2l, ql;  // auxiliary vectors in the corotated frame
  Eigen::Matrix<double, 7, 1> da;  // [u_bar, theta_bar_1, theta_bar_2]
};

CorotationalBeam::Kinematics CorotationalBeam::kinematics(const NodalState& s) const {
  Kinematics k;
  const Vec3 d = s.position[nodes_[1]] - s.position[nodes_[0]];
  k.ln = d.norm();
  if (!(k.ln > 1e-12 * l0_) || !std::isfinite(k.ln)) {
    std::ostringstream os;
    os << "beam between nodes " << nodes_[0] << " and " << nodes_[1]
       << " collapsed to zero length (or NaN position); the solution diverged";
    throw NotConverged(os.str());
  }
  const Vec3 r1 = d / k.ln;
  const Mat3& R1 = s.rotation[nodes_[0]];
  const Mat3& R2 = s.rotation[nodes_[1]];
  const Vec3 q1 = R1 * R0_.col(1), q2 = R2 * R0_.col(1);
  const Vec3 q = 0.5 * (q1 + q2);
  Vec3 r3 = r1.cross(q);
  const double n3 = r3.norm();
  if (!(n3 > 1e-12)) {
    std::ostringstream os;
    os << "beam between nodes " << nodes_[0] << " and " << nodes_[1]
       << ": corotated frame undefined (nodal y axes parallel to the chord)";
    throw NotConverged(os.str());
  }
  r3 /= n3;
  const Vec3 r2 = r3.cross(r1);
  k.Rr.col(0) = r1, k.Rr.col(1) = r2, k.Rr.col(2) = r3;
  k.q1l = k.Rr.transpose() * q1;
  k.q2l = k.Rr.transpose() * q2;
  k.ql = k.Rr.transpose() * q;
  k.da(0) = k.ln - l0_;
  k.da.segment<3>(1) = log_so3(k.Rr.transpose() * R1 * R0_);
  k.da.segment<3>(4) = log_so3(k.Rr.transpose() * R2 * R0_);
  return k;
}

CorotationalBeam::Local CorotationalBeam::local_state(const NodalState& s) const {
  const Kinematics k = kinematics(s);
  const Eigen::Matrix<double, 7, 1> fa = kl_ * k.da;
  Local l;
  l.elongation = k.da(0);
  l.theta1 = k.da.segment<3>(1), l.theta2 = k.da.segment<3>(4);
  l.axial_force = fa(0);
  l.moment1 = fa.segment<3>(1), l.moment2 = fa.segment<3>(4);
  return l;
}

double CorotationalBeam::strain_energy(const NodalState& s) const {
  const Kinematics k = kinematics(s);
  return 0.5 * k.da.dot(kl_ * k.da);
}

// The variations of the local freedoms in terms of the global ones (Battini & Pacoste eqs.
// (37)-(48)): the frame spin G^T, the projector P, B = [r; P E^T] (local spins) and Ba = dtheta_bar
// / d(local spin) = blockdiag(1, Ts^-1, Ts^-1). What internal_force and viscous_force share.
struct CorotationalBeam::Projection {
  Eigen::Matrix<double, 3, 12> GT;
  Eigen::Matrix<double, 6, 12> P;
  Eigen::Matrix<double, 7, 12> B;
  Eigen::Matrix<double, 7, 7> Ba;
  Mat3 Ti1, Ti2;
  Vec12 r;
  double eta, eta11, eta12, eta21, eta22;
};

CorotationalBeam::Projection CorotationalBeam::projection(const Kinematics& k) const {
  Projection p;
  const double ln = k.ln;
  const Vec3 r1 = k.Rr.col(0);
  p.Ti1 = tangent_inverse(k.da.segment<3>(1));
  p.Ti2 = tangent_inverse(k.da.segment<3>(4));
  p.Ba.setZero();
  p.Ba(0, 0) = 1;
  p.Ba.block<3, 3>(1, 1) = p.Ti1;
  p.Ba.block<3, 3>(4, 4) = p.Ti2;

  // G^T (3x12): spin of the corotated frame in terms of the local-frame global dofs.
  p.eta = k.ql(0) / k.ql(1);
  p.eta11 = k.q1l(0) / k.ql(1), p.eta12 = k.q1l(1) / k.ql(1);
  p.eta21 = k.q2l(0) / k.ql(1), p.eta22 = k.q2l(1) / k.ql(1);
  auto& GT = p.GT;
  GT.setZero();
  GT(0, 2) = p.eta / ln, GT(0, 3) = p.eta12 / 2, GT(0, 4) = -p.eta11 / 2;
  GT(0, 8) = -p.eta / ln, GT(0, 9) = p.eta22 / 2, GT(0, 10) = -p.eta21 / 2;
  GT(1, 2) = 1 / ln, GT(1, 8) = -1 / ln;
  GT(2, 1) = -1 / ln, GT(2, 7) = 1 / ln;
  p.P.setZero();
  p.P.block<3, 3>(0, 3).setIdentity();
  p.P.block<3, 3>(3, 9).setIdentity();
  p.P.block<3, 12>(0, 0) -= GT;
  p.P.block<3, 12>(3, 0) -= GT;

  // B = [r; P E^T]; applying E^T = blockdiag(Rr^T) column-block by column-block.
  p.r.setZero();
  p.r.segment<3>(0) = -r1;
  p.r.segment<3>(6) = r1;
  p.B.row(0) = p.r.transpose();
  for (int b = 0; b < 4; ++b) p.B.block<6, 3>(1, 3 * b) = p.P.block<6, 3>(0, 3 * b) * k.Rr.transpose();
  return p;
}

void CorotationalBeam::viscous_force(const NodalState& s, const Eigen::Ref<const Eigen::VectorXd>& v, double eta,
                                     VectorRef f, MatrixRef* C) const {
  // theta_bar_dot = Ba B v: the rate of the local deformation, zero for a rigid motion.
  const Projection p = projection(kinematics(s));
  const Eigen::Matrix<double, 7, 12> D = p.Ba * p.B;
  f = D.transpose() * (eta * (kl_ * (D * v)));
  if (C) *C = D.transpose() * (eta * kl_) * D;
}

void CorotationalBeam::internal_force(const NodalState& s, VectorRef f_out,
                                      MatrixRef* K_out) const {
  const Kinematics k = kinematics(s);
  using Mat7 = Eigen::Matrix<double, 7, 7>;
  using Vec7 = Eigen::Matrix<double, 7, 1>;
  const double ln = k.ln;
  const Vec3 r1 = k.Rr.col(0);
  const Projection p = projection(k);
  const auto& [GT, P, B, Ba, Ti1, Ti2, r, eta, eta11, eta12, eta21, eta22] = p;

  // Local forces conjugate to theta_bar (fa) and to the local spins (fl = Ba^T fa).
  const Vec7 fa = kl_ * k.da;
  const Vec3 th1 = k.da.segment<3>(1), th2 = k.da.segment<3>(4);
  const Vec7 fl = Ba.transpose() * fa;

  f_out = B.transpose() * fl;
  if (!K_out) return;

  // Kh: derivative of Ts^-T(theta_bar) m with respect to theta_bar.
  Mat7 Kl = Ba.transpose() * kl_ * Ba;
  Kl.block<3, 3>(1, 1) += tangent_inverse_derivative(th1, fa.segment<3>(1));
  Kl.block<3, 3>(4, 4) += tangent_inverse_derivative(th2, fa.segment<3>(4));

  const Eigen::Matrix<double, 7, 12> KlB = Kl.lazyProduct(B);
  Mat12 K = B.transpose().lazyProduct(KlB);

  // Km = D N - E Q G^T E^T + E G a r^T
  const double N = fl(0);
  const Mat3 D3 = (Mat3::Identity() - r1 * r1.transpose()) / ln;
  K.block<3, 3>(0, 0) += N * D3;
  K.block<3, 3>(0, 6) -= N * D3;
  K.block<3, 3>(6, 0) -= N * D3;
  K.block<3, 3>(6, 6) += N * D3;

  const Vec12 Ptm = P.transpose() * fl.segment<6>(1);
  Eigen::Matrix<double, 12, 3> EQ;  // E Q
  Eigen::Matrix<double, 12, 3> EG;  // E G
  for (int b = 0; b < 4; ++b) {
    EQ.block<3, 3>(3 * b, 0) = k.Rr * skew(Ptm.segment<3>(3 * b));
    EG.block<3, 3>(3 * b, 0) = k.Rr * GT.block<3, 3>(0, 3 * b).transpose();
  }
  Eigen::Matrix<double, 3, 12> GTET;  // G^T E^T
  for (int b = 0; b < 4; ++b) GTET.block<3, 3>(0, 3 * b) = GT.block<3, 3>(0, 3 * b) * k.Rr.transpose();
  const Vec3 m1 = fl.segment<3>(1), m2 = fl.segment<3>(4);
  const Vec3 a(0, (eta * (m1(0) + m2(0)) + m1(1) + m2(1)) / ln, (m1(2) + m2(2)) / ln);
  K.noalias() -= EQ.lazyProduct(GTET);
  K.noalias() += (EG * a).lazyProduct(r.transpose());

  // Variation of eta, eta_ij (the q vectors seen from the rotating frame), which the published
  // Km omits; without it the tangent is off by O(|q_x/q_y| |m|) and Newton loses its quadratic
  // rate for twisted rays. dq_i,local = -skew(q_i,local) (dw_i,local - dw_r,local).
  {
    Eigen::Matrix<double, 3, 12> S1 = -GT, S2 = -GT;
    S1.block<3, 3>(0, 3) += Mat3::Identity();
    S2.block<3, 3>(0, 9) += Mat3::Identity();
    const Eigen::Matrix<double, 3, 12> A1 = -skew(k.q1l) * S1, A2 = -skew(k.q2l) * S2;
    const Eigen::Matrix<double, 3, 12> A = 0.5 * (A1 + A2);
    const double qy = k.ql(1);
    auto d_ratio = [&](const Eigen::Matrix<double, 1, 12>& num_row, double ratio) {
      return Eigen::Matrix<double, 1, 12>((num_row - ratio * A.row(1)) / qy);
    };
    Eigen::Matrix<double, 12, 12> Dg = Eigen::Matrix<double, 12, 12>::Zero();
    const auto d_eta = d_ratio(A.row(0), eta);
    Dg.row(2) = d_eta / ln;
    Dg.row(8) = -d_eta / ln;
    Dg.row(3) = 0.5 * d_ratio(A1.row(1), eta12);
    Dg.row(4) = -0.5 * d_ratio(A1.row(0), eta11);
    Dg.row(9) = 0.5 * d_ratio(A2.row(1), eta22);
    Dg.row(10) = -0.5 * d_ratio(A2.row(0), eta21);
    // f_g contains -E g0^T m_sx; its variation through g0 acts on E^T dd.
    K -= (m1(0) + m2(0)) * rotate_blocks(k.Rr, Dg);
  }
  *K_out = K;
}

void CorotationalBeam::mass_matrix(const NodalState& s, MatrixRef M) const {
  M = rotate_blocks(kinematics(s).Rr, ml_);
}

void CorotationalBeam::gravity_force(const NodalState&, const Vec3& g, VectorRef f) const {
  f.setZero();
  f.segment<3>(0) = gravity_share_[0] * g;
  f.segment<3>(6) = gravity_share_[1] * g;
}

}  // namespace finverse::fem
