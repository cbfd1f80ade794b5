// Q9 total-Lagrangian St. Venant-Kirchhoff plane-strain solid (see plane_strain_solid.hpp).
#include "fem/plane_strain_solid.hpp"

#include <cmath>
#include <sstream>

#include <Eigen/LU>

#include "fem/errors.hpp"

namespace finverse::fem {

namespace {

constexpr std::array<int, 2> kInPlaneDofs = {0, 1};

// Position of each node in the 3 x 3 tensor grid of 1-D quadratic Lagrange functions.
constexpr std::array<int, 9> kGridI = {0, 2, 2, 0, 1, 2, 1, 0, 1};
constexpr std::array<int, 9> kGridJ = {0, 0, 2, 2, 0, 1, 2, 1, 1};

// 3 x 3 Gauss-Legendre (full integration): exact to degree 5 per direction, so the mass and the
// small-strain stiffness of an affine element (both degree 4 per direction) are integrated
// exactly, and no zero-energy mode appears (2 x 2 would leave spurious hourglass modes in Q9).
const double kGaussPoint[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)};
constexpr double kGaussWeight[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};

// 1-D quadratic Lagrange functions on nodes -1, 0, 1 and their derivatives.
Eigen::Vector3d lagrange(double s) {
  return {0.5 * s * (s - 1.0), 1.0 - s * s, 0.5 * s * (s + 1.0)};
}
Eigen::Vector3d lagrange_derivative(double s) { return {s - 0.5, -2.0 * s, s + 0.5}; }

using Mat2 = PlaneStrainSolid::Mat2;

Mat2 svk_stress(const Mat2& E, double lambda, double mu) {
  return lambda * E.trace() * Mat2::Identity() + 2.0 * mu * E;
}

}  // namespace

Eigen::Matrix<double, 9, 1> PlaneStrainSolid::shape(double xi, double eta) {
  const Eigen::Vector3d a = lagrange(xi), b = lagrange(eta);
  Eigen::Matrix<double, 9, 1> N;
  for (int k = 0; k < kNodes; ++k) N(k) = a(kGridI[k]) * b(kGridJ[k]);
  return N;
}

Eigen::Matrix<double, 9, 2> PlaneStrainSolid::shape_derivatives(double xi, double eta) {
  const Eigen::Vector3d a = lagrange(xi), b = lagrange(eta);
  const Eigen::Vector3d da = lagrange_derivative(xi), db = lagrange_derivative(eta);
  Eigen::Matrix<double, 9, 2> dN;
  for (int k = 0; k < kNodes; ++k) {
    dN(k, 0) = da(kGridI[k]) * b(kGridJ[k]);
    dN(k, 1) = a(kGridI[k]) * db(kGridJ[k]);
  }
  return dN;
}

PlaneStrainSolid::PlaneStrainSolid(const std::array<int, kNodes>& nodes,
                                   const std::array<Vec3, kNodes>& X, const Material& material,
                                   double thickness)
    : nodes_(nodes), material_(material), thickness_(thickness) {
  validate(material_);
  if (!(thickness_ > 0) || !std::isfinite(thickness_)) {
    std::ostringstream os;
    os << "plane-strain solid (nodes " << nodes_[0] << ".." << nodes_[8] << "): thickness "
       << thickness_ << ", expected > 0";
    throw InvalidInput(os.str());
  }
  const double nu = material_.poisson_ratio, E = material_.youngs_modulus;
  lambda_ = E * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
  mu_ = E / (2.0 * (1.0 + nu));

  Positions P;
  double extent = 0;
  for (int k = 0; k < kNodes; ++k) {
    P.row(k) = X[k].head<2>().transpose();
    extent = std::max(extent, (X[k] - X[0]).norm());
  }
  for (int k = 1; k < kNodes; ++k)
    if (std::abs(X[k].z() - X[0].z()) > 1e-12 * std::max(extent, 1.0)) {
      std::ostringstream os;
      os << "plane-strain solid (nodes " << nodes_[0] << ".." << nodes_[8] << "): node " << nodes_[k]
         << " has z = " << X[k].z() << " but node " << nodes_[0] << " has z = " << X[0].z()
         << "; the element must lie in a plane z = const";
      throw InvalidInput(os.str());
    }

  int g = 0;
  for (int j = 0; j < 3; ++j)
    for (int i = 0; i < 3; ++i, ++g) {
      const double xi = kGaussPoint[i], eta = kGaussPoint[j];
      const Eigen::Matrix<double, 9, 2> dN = shape_derivatives(xi, eta);
      const Mat2 J = P.transpose() * dN;  // dX/d(xi, eta)
      const double detJ = J.determinant();
      if (!(detJ > 1e-12 * extent * extent)) {
        std::ostringstream os;
        os << "plane-strain solid (nodes " << nodes_[0] << ".." << nodes_[8]
           << "): Jacobian determinant " << detJ << " at a Gauss point, expected > 0 "
           << "(nodes must be counter-clockwise, corners first, and the element not inverted)";
        throw InvalidInput(os.str());
      }
      grad_[g] = dN * J.inverse();
      N_[g] = shape(xi, eta);
      weight_[g] = kGaussWeight[i] * kGaussWeight[j] * detJ * thickness_;
      Xg_[g] = P.transpose() * N_[g];
      volume_ += weight_[g];
    }
}

std::span<const int> PlaneStrainSolid::active_dofs() const { return kInPlaneDofs; }

PlaneStrainSolid::Positions PlaneStrainSolid::current_positions(const NodalState& state) const {
  Positions x;
  for (int k = 0; k < kNodes; ++k) x.row(k) = state.position[nodes_[k]].head<2>().transpose();
  return x;
}

void PlaneStrainSolid::internal_force(const NodalState& state, VectorRef f, MatrixRef* K) const {
  const Positions x = current_positions(state);
  Eigen::Matrix<double, 9, 2> fn = Eigen::Matrix<double, 9, 2>::Zero();
  Eigen::Matrix<double, 18, 18> Ke;
  if (K) Ke.setZero();
  Eigen::Matrix3d D;
  D << lambda_ + 2 * mu_, lambda_, 0, lambda_, lambda_ + 2 * mu_, 0, 0, 0, mu_;
  Eigen::Matrix<double, 3, 18> B;
  for (int g = 0; g < kGauss; ++g) {
    const auto& G = grad_[g];
    const Mat2 F = x.transpose() * G;
    const Mat2 E = 0.5 * (F.transpose() * F - Mat2::Identity());
    const Mat2 S = svk_stress(E, lambda_, mu_);
    const double w = weight_[g];
    fn.noalias() += w * G * (F * S).transpose();
    if (!K) continue;
    for (int a = 0; a < kNodes; ++a)
      for (int i = 0; i < 2; ++i) {
        const int c = 2 * a + i;
        B(0, c) = F(i, 0) * G(a, 0);
        B(1, c) = F(i, 1) * G(a, 1);
        B(2, c) = F(i, 0) * G(a, 1) + F(i, 1) * G(a, 0);
      }
    Ke.noalias() += w * B.transpose() * D * B;
    const Eigen::Matrix<double, 9, 9> H = w * G * S * G.transpose();
    for (int a = 0; a < kNodes; ++a)
      for (int b = 0; b < kNodes; ++b) {
        Ke(2 * a, 2 * b) += H(a, b);
        Ke(2 * a + 1, 2 * b + 1) += H(a, b);
      }
  }
  for (int a = 0; a < kNodes; ++a) {
    f(2 * a) = fn(a, 0);
    f(2 * a + 1) = fn(a, 1);
  }
  if (K) *K = Ke;
}

void PlaneStrainSolid::mass_matrix(const NodalState&, MatrixRef M) const {
  Eigen::Matrix<double, 9, 9> m = Eigen::Matrix<double, 9, 9>::Zero();
  for (int g = 0; g < kGauss; ++g) m.noalias() += (material_.density * weight_[g]) * N_[g] * N_[g].transpose();
  M.setZero();
  for (int a = 0; a < kNodes; ++a)
    for (int b = 0; b < kNodes; ++b) {
      M(2 * a, 2 * b) = m(a, b);
      M(2 * a + 1, 2 * b + 1) = m(a, b);
    }
}

void PlaneStrainSolid::gravity_force(const NodalState&, const Vec3& g, VectorRef f) const {
  Eigen::Matrix<double, 9, 1> n = Eigen::Matrix<double, 9, 1>::Zero();
  for (int q = 0; q < kGauss; ++q) n += (material_.density * weight_[q]) * N_[q];
  for (int a = 0; a < kNodes; ++a) {
    f(2 * a) = n(a) * g.x();
    f(2 * a + 1) = n(a) * g.y();
  }
}

double PlaneStrainSolid::strain_energy(const NodalState& state) const {
  const Positions x = current_positions(state);
  double W = 0;
  for (int g = 0; g < kGauss; ++g) {
    const Mat2 F = x.transpose() * grad_[g];
    const Mat2 E = 0.5 * (F.transpose() * F - Mat2::Identity());
    const double tr = E.trace();
    W += weight_[g] * (0.5 * lambda_ * tr * tr + mu_ * (E.array() * E.array()).sum());
  }
  return W;
}

std::array<PlaneStrainSolid::PointStress, PlaneStrainSolid::kGauss> PlaneStrainSolid::stresses(
    const NodalState& state) const {
  const Positions x = current_positions(state);
  std::array<PointStress, kGauss> out;
  for (int g = 0; g < kGauss; ++g) {
    const Mat2 F = x.transpose() * grad_[g];
    const Mat2 E = 0.5 * (F.transpose() * F - Mat2::Identity());
    const Mat2 S = svk_stress(E, lambda_, mu_);
    const double J = F.determinant();  // F_zz = 1 in plane strain
    out[g].X = Xg_[g];
    out[g].second_piola_kirchhoff = S;
    out[g].cauchy = F * S * F.transpose() / J;
    out[g].cauchy_zz = lambda_ * E.trace() / J;
  }
  return out;
}

}  // namespace finverse::fem
