// Element-level checks of the corotational beam: consistent tangent against finite differences
// of the internal force, zero force under rigid-body motion, mass sums to the total mass.
#include <random>

#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "fem/corotational_beam.hpp"
#include "fem/errors.hpp"

using namespace finverse::fem;

namespace {
struct Fixture {
  Material mat{"ray", 2.0e9, 0.3, 1100};
  TaperedRectangle sec{{0.02, 0.012}, {0.004, 0.0025}};
  Vec3 X1{0.01, -0.02, 0.03}, X2{0.31, 0.08, 0.05};
  CorotationalBeam beam{3, 7, X1, X2, Vec3(0, 0.3, 1), mat, sec};
  NodalState state() const {
    NodalState s;
    s.position.assign(8, Vec3::Zero());
    s.rotation.assign(8, Mat3::Identity());
    s.position[3] = X1;
    s.position[7] = X2;
    return s;
  }
};

Eigen::VectorXd force(const CorotationalBeam& b, const NodalState& s) {
  Eigen::VectorXd f(12);
  b.internal_force(s, f, nullptr);
  return f;
}

// The element's increment v (12) times h, applied to its two nodes inside an 8-node state.
NodalState moved(const NodalState& s, const Eigen::VectorXd& v, double h) {
  Eigen::VectorXd d = Eigen::VectorXd::Zero(6 * 8);
  d.segment<6>(6 * 3) = h * v.head<6>();
  d.segment<6>(6 * 7) = h * v.tail<6>();
  NodalState p = s;
  p.apply_increment(d);
  return p;
}

// Increment h of the element's freedom j.
NodalState perturbed(const NodalState& s, int j, double h) { return moved(s, Eigen::VectorXd::Unit(12, j), h); }
}  // namespace

TEST(CorotationalBeam, TangentMatchesFiniteDifferenceForLargeRandomDeformation) {
  Fixture fx;
  std::mt19937 rng(20240611);
  std::uniform_real_distribution<double> U(-1, 1);
  for (int trial = 0; trial < 5; ++trial) {
    NodalState s = fx.state();
    for (int n : {3, 7}) {
      s.position[n] += 0.03 * Vec3(U(rng), U(rng), U(rng));
      s.rotation[n] = exp_so3(0.9 * Vec3(U(rng), U(rng), U(rng)));
    }
    Eigen::VectorXd f(12);
    Eigen::MatrixXd K(12, 12);
    Element::MatrixRef Kr(K);
    fx.beam.internal_force(s, f, &Kr);
    Eigen::MatrixXd Kfd(12, 12);
    const double h = 1e-6;
    for (int j = 0; j < 12; ++j)
      Kfd.col(j) = (force(fx.beam, perturbed(s, j, h)) - force(fx.beam, perturbed(s, j, -h))) / (2 * h);
    EXPECT_LT((K - Kfd).norm() / K.norm(), 1e-8) << "trial " << trial;
    // The tangent is genuinely non-symmetric away from equilibrium (so the check above would
    // catch a symmetrised one).
    EXPECT_GT((K - K.transpose()).norm() / K.norm(), 1e-6);
  }
}

TEST(CorotationalBeam, RigidBodyMotionGivesZeroForceAndEnergy) {
  Fixture fx;
  NodalState s = fx.state();
  const Mat3 Q = exp_so3(Vec3(2.1, -0.7, 1.3));  // large rotation about the origin
  const Vec3 c(0.5, -1.0, 2.0);
  for (int n : {3, 7}) {
    s.position[n] = Q * s.position[n] + c;
    s.rotation[n] = Q;
  }
  const Eigen::VectorXd f = force(fx.beam, s);
  EXPECT_LT(f.norm(), 1e-9 * fx.mat.youngs_modulus * 1e-6);
  EXPECT_LT(fx.beam.strain_energy(s), 1e-20);
  // ... while a small real deformation does produce a force (the check is not vacuous).
  s.position[7] += 1e-6 * Vec3(0, 0, 1);
  EXPECT_GT(force(fx.beam, s).norm(), 0.1);
}

TEST(CorotationalBeam, MassMatrixCarriesTheTotalMassInEveryDirection) {
  Fixture fx;
  NodalState s = fx.state();
  s.rotation[3] = s.rotation[7] = exp_so3(Vec3(0.3, 0.2, -0.5));
  // Exact mass of the linearly tapered strip: rho L int b(x) t(x) dx.
  const double L = (fx.X2 - fx.X1).norm();
  const double b0 = 0.02, b1 = 0.012, t0 = 0.004, t1 = 0.0025;
  const double exact = fx.mat.density * L *
                       (b0 * t0 + 0.5 * (b0 * (t1 - t0) + t0 * (b1 - b0)) + (b1 - b0) * (t1 - t0) / 3.0);
  EXPECT_NEAR(fx.beam.total_mass(), exact, 1e-12 * exact);
  Eigen::MatrixXd M(12, 12);
  fx.beam.mass_matrix(s, M);
  EXPECT_LT((M - M.transpose()).norm(), 1e-15 * M.norm());
  for (int k = 0; k < 3; ++k) {
    Eigen::VectorXd v = Eigen::VectorXd::Zero(12);
    v(k) = v(6 + k) = 1.0;  // rigid translation with unit velocity
    EXPECT_NEAR(v.dot(M * v), exact, 1e-12 * exact) << "direction " << k;
  }
  EXPECT_GT(M.eigenvalues().real().minCoeff(), 0.0);
}

TEST(CorotationalBeam, RejectsDegenerateGeometry) {
  Fixture fx;
  EXPECT_THROW(CorotationalBeam(0, 1, fx.X1, fx.X1, Vec3(0, 0, 1), fx.mat, fx.sec), InvalidInput);
  EXPECT_THROW(CorotationalBeam(0, 1, fx.X1, fx.X2, fx.X2 - fx.X1, fx.mat, fx.sec), InvalidInput);
  TaperedRectangle bad{{0.01, 0.01}, {0.0, 0.01}};
  EXPECT_THROW(CorotationalBeam(0, 1, fx.X1, fx.X2, Vec3(0, 0, 1), fx.mat, bad), InvalidInput);
}

namespace {
Eigen::Matrix<double, 7, 1> local_deformation(const CorotationalBeam& b, const NodalState& s) {
  const CorotationalBeam::Local l = b.local_state(s);
  Eigen::Matrix<double, 7, 1> d;
  d << l.elongation, l.theta1, l.theta2;
  return d;
}
}  // namespace

TEST(CorotationalBeam, ViscousForceDampsTheDeformationRateOnly) {
  // Kelvin-Voigt damping f_d = eta B^T k_l B v: its power is eta d_dot^T k_l d_dot with d_dot the
  // rate of the local deformation (checked by central differences of the deformation along v at
  // a large deformation), and a rigid motion of the bent, loaded element is not damped at all.
  Fixture fx;
  std::mt19937 rng(4501);
  std::uniform_real_distribution<double> U(-1, 1);
  NodalState s = fx.state();
  for (int n : {3, 7}) {
    s.position[n] += 0.03 * Vec3(U(rng), U(rng), U(rng));
    s.rotation[n] = exp_so3(0.9 * Vec3(U(rng), U(rng), U(rng)));
  }
  const double eta = 0.01;
  Eigen::VectorXd v(12), f(12);
  for (int i = 0; i < 12; ++i) v(i) = U(rng);
  Eigen::MatrixXd C(12, 12);
  Element::MatrixRef Cr(C);
  fx.beam.viscous_force(s, v, eta, f, &Cr);
  const double h = 1e-6;
  const Eigen::Matrix<double, 7, 1> rate =
      (local_deformation(fx.beam, moved(s, v, h)) - local_deformation(fx.beam, moved(s, v, -h))) / (2 * h);
  const double power = eta * rate.dot(fx.beam.local_stiffness() * rate);
  EXPECT_NEAR(v.dot(f), power, 1e-7 * power);
  EXPECT_LT((C * v - f).norm(), 1e-12 * f.norm());
  EXPECT_LT((C - C.transpose()).norm(), 1e-14 * C.norm());

  // Rigid spin w about the origin and translation c: v_a = w x x_a + c, spins w.
  const Vec3 w(3.0, -1.0, 2.0), c(0.4, 0.1, -0.2);
  Eigen::VectorXd rigid(12);
  for (int a = 0; a < 2; ++a) {
    rigid.segment<3>(6 * a) = w.cross(s.position[a == 0 ? 3 : 7]) + c;
    rigid.segment<3>(6 * a + 3) = w;
  }
  Eigen::VectorXd fr(12);
  fx.beam.viscous_force(s, rigid, eta, fr, nullptr);
  EXPECT_LT(fr.norm(), 1e-12 * f.norm() * rigid.norm() / v.norm());
  // Rayleigh's eta K v with the current tangent does damp that rigid motion of the loaded element.
  Eigen::MatrixXd K(12, 12);
  Element::MatrixRef Kr(K);
  Eigen::VectorXd fi(12);
  fx.beam.internal_force(s, fi, &Kr);
  EXPECT_GT((eta * K * rigid).norm(), 1e-3 * f.norm() * rigid.norm() / v.norm());
}
