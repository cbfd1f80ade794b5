// Corotational shell triangle: rigid-body invariance, objectivity, consistent tangent against
// central differences (multiplicative rotation perturbation), mass and gravity, and one large-
// rotation solve (strip rolled into a half circle).
#include <cmath>
#include <numbers>
#include <random>
#include <sstream>
#include <string>
#include <algorithm>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "fem/corotational_shell.hpp"
#include "fem/errors.hpp"
#include "fem/model.hpp"
#include "fem/static_solver.hpp"

namespace finverse::fem {
namespace {

const Material kShellMaterial{"test", 7.0e7, 0.3, 1100.0};

struct ShellFixture {
  std::array<Vec3, 3> X;
  NodalState reference;
};

// A skew triangle, not aligned with any axis.
ShellFixture skew_triangle() {
  ShellFixture s;
  s.X = {Vec3(0.1, -0.2, 0.3), Vec3(1.2, 0.25, 0.1), Vec3(0.35, 0.95, 0.6)};
  s.reference.position.assign(s.X.begin(), s.X.end());
  s.reference.rotation.assign(3, Mat3::Identity());
  return s;
}

Vec3 random_vector(std::mt19937& rng, double scale) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  return scale * Vec3(u(rng), u(rng), u(rng));
}

// A large deformation: rigid rotation + translation plus deformational translations (strain ~1 %)
// and deformational rotations up to ~0.3 rad.
NodalState shell_deformed(const ShellFixture& s, std::mt19937& rng, double rigid_angle) {
  NodalState st = s.reference;
  const Mat3 Q = exp_so3(random_vector(rng, rigid_angle));
  const Vec3 t = random_vector(rng, 2.0);
  for (int a = 0; a < 3; ++a) {
    st.position[a] = Q * (s.X[a] + random_vector(rng, 0.01)) + t;
    st.rotation[a] = Q * exp_so3(random_vector(rng, 0.3));
  }
  return st;
}

Eigen::VectorXd shell_force(const CorotationalShell& e, const NodalState& s) {
  Eigen::VectorXd f(18);
  e.internal_force(s, f, nullptr);
  return f;
}

TEST(CorotationalShell, RigidMotionGivesNoForceOrEnergy) {
  const ShellFixture s = skew_triangle();
  const CorotationalShell e(0, 1, 2, s.X[0], s.X[1], s.X[2], kShellMaterial, 0.02);
  std::mt19937 rng(42);
  const double scale = kShellMaterial.youngs_modulus * 0.02;  // shell_force of a unit membrane strain
  for (int trial = 0; trial < 5; ++trial) {
    NodalState st = s.reference;
    const Mat3 Q = exp_so3(random_vector(rng, 3.0));  // up to ~5 rad: beyond pi as well
    const Vec3 t = random_vector(rng, 10.0);
    for (int a = 0; a < 3; ++a) {
      st.position[a] = Q * s.X[a] + t;
      st.rotation[a] = Q;
    }
    EXPECT_LT(shell_force(e, st).norm(), 1e-10 * scale) << "trial " << trial;
    EXPECT_LT(e.strain_energy(st), 1e-20 * scale);
  }
}

TEST(CorotationalShell, ForceIsObjectiveAndSelfEquilibrated) {
  const ShellFixture s = skew_triangle();
  const CorotationalShell e(0, 1, 2, s.X[0], s.X[1], s.X[2], kShellMaterial, 0.02);
  std::mt19937 rng(7);
  const NodalState st = shell_deformed(s, rng, 1.0);
  const Eigen::VectorXd f = shell_force(e, st);
  ASSERT_GT(f.norm(), 0.0);
  // Superposed rigid rotation: forces and moments rotate with it.
  const Mat3 Q = exp_so3(Vec3(0.4, -1.9, 0.8));
  NodalState rotated = st;
  for (int a = 0; a < 3; ++a) {
    rotated.position[a] = Q * st.position[a] + Vec3(1, 2, 3);
    rotated.rotation[a] = Q * st.rotation[a];
  }
  const Eigen::VectorXd fr = shell_force(e, rotated);
  for (int b = 0; b < 6; ++b)
    EXPECT_LT((fr.segment<3>(3 * b) - Q * f.segment<3>(3 * b)).norm(), 1e-10 * f.norm());
  // Resultant shell_force and moment (about the origin) vanish in the current configuration.
  Vec3 F = Vec3::Zero(), M = Vec3::Zero();
  for (int a = 0; a < 3; ++a) {
    F += f.segment<3>(6 * a);
    M += st.position[a].cross(f.segment<3>(6 * a)) + f.segment<3>(6 * a + 3);
  }
  EXPECT_LT(F.norm(), 1e-10 * f.norm());
  EXPECT_LT(M.norm(), 1e-10 * f.norm() * 3.0);
  // The shell_force is the gradient of the strain energy (with respect to translations and spins).
  Eigen::VectorXd dir(18);
  for (int i = 0; i < 18; ++i) dir(i) = std::sin(1.0 + 3.7 * i);
  const double eps = 1e-6;
  NodalState plus = st, minus = st;
  plus.apply_increment(eps * dir);
  minus.apply_increment(-eps * dir);
  const double dU = (e.strain_energy(plus) - e.strain_energy(minus)) / (2 * eps);
  EXPECT_NEAR(dU, f.dot(dir), 1e-6 * f.norm() * dir.norm());
}

// Central differences of the internal shell_force: translations perturbed additively, rotations by a
// spatial spin, R <- exp(skew(eps e_k)) R, matching the solvers' multiplicative update.
Eigen::MatrixXd finite_difference_tangent(const CorotationalShell& e, const NodalState& st,
                                          double h_trans, double h_rot) {
  Eigen::MatrixXd K(18, 18);
  for (int j = 0; j < 18; ++j) {
    const int node = j / 6, dof = j % 6;
    const double h = dof < 3 ? h_trans : h_rot;
    NodalState p = st, m = st;
    if (dof < 3) {
      p.position[node](dof) += h;
      m.position[node](dof) -= h;
    } else {
      p.rotation[node] = exp_so3(h * Vec3::Unit(dof - 3)) * st.rotation[node];
      m.rotation[node] = exp_so3(-h * Vec3::Unit(dof - 3)) * st.rotation[node];
    }
    K.col(j) = (shell_force(e, p) - shell_force(e, m)) / (2.0 * h);
  }
  return K;
}

TEST(CorotationalShell, TangentMatchesCentralDifferences) {
  const ShellFixture s = skew_triangle();
  const CorotationalShell e(0, 1, 2, s.X[0], s.X[1], s.X[2], kShellMaterial, 0.02);
  std::mt19937 rng(2024);
  double worst = 0;
  for (int trial = 0; trial < 6; ++trial) {
    const NodalState st = shell_deformed(s, rng, 2.5);
    Eigen::VectorXd f(18);
    Eigen::MatrixXd K(18, 18);
    Element::MatrixRef Kref(K);
    e.internal_force(st, f, &Kref);
    const Eigen::MatrixXd Kfd = finite_difference_tangent(e, st, 1e-6, 1e-6);
    const double err = (K - Kfd).norm() / K.norm();
    EXPECT_LT(err, 1e-6) << "trial " << trial;
    worst = std::max(worst, err);
    // The geometric terms matter here: the tangent at the reference configuration (material
    // part only, rotated) would be far off, so the check above is not vacuous.
    Eigen::MatrixXd K0(18, 18);
    Element::MatrixRef K0ref(K0);
    Eigen::VectorXd f0(18);
    e.internal_force(s.reference, f0, &K0ref);
    EXPECT_GT((K0 - Kfd).norm() / Kfd.norm(), 1e-3);
  }
  std::ostringstream os;
  os << std::scientific << worst;
  RecordProperty("worst_relative_error", os.str());
}

TEST(CorotationalShell, MassAndGravity) {
  const ShellFixture s = skew_triangle();
  const double h = 0.02;
  const CorotationalShell e(0, 1, 2, s.X[0], s.X[1], s.X[2], kShellMaterial, h);
  const double area = 0.5 * (s.X[1] - s.X[0]).cross(s.X[2] - s.X[0]).norm();
  EXPECT_NEAR(e.area(), area, 1e-14);
  EXPECT_NEAR(e.total_mass(), kShellMaterial.density * h * area, 1e-12);
  Eigen::MatrixXd M(18, 18);
  e.mass_matrix(s.reference, M);
  EXPECT_LT((M - M.transpose()).norm(), 1e-15 * M.norm());
  // A rigid translation carries the whole mass; the matrix is positive definite.
  Eigen::VectorXd v = Eigen::VectorXd::Zero(18);
  for (int a = 0; a < 3; ++a) v.segment<3>(6 * a) = Vec3(0.3, -1.2, 0.5);
  EXPECT_NEAR(v.dot(M * v), e.total_mass() * Vec3(0.3, -1.2, 0.5).squaredNorm(), 1e-12);
  EXPECT_GT(Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(M).eigenvalues().minCoeff(), 0.0);
  Eigen::VectorXd g(18);
  e.gravity_force(s.reference, Vec3(0, 0, -9.81), g);
  Vec3 total = Vec3::Zero();
  for (int a = 0; a < 3; ++a) total += g.segment<3>(6 * a);
  EXPECT_LT((total - e.total_mass() * Vec3(0, 0, -9.81)).norm(), 1e-12);
}

TEST(CorotationalShell, PerElementStiffnessScalesLinearly) {
  const ShellFixture s = skew_triangle();
  Material stiff = kShellMaterial;
  stiff.youngs_modulus *= 3.0;
  const CorotationalShell a(0, 1, 2, s.X[0], s.X[1], s.X[2], kShellMaterial, 0.02);
  const CorotationalShell b(0, 1, 2, s.X[0], s.X[1], s.X[2], stiff, 0.02);
  std::mt19937 rng(3);
  const NodalState st = shell_deformed(s, rng, 1.0);
  EXPECT_LT((shell_force(b, st) - 3.0 * shell_force(a, st)).norm(), 1e-12 * shell_force(b, st).norm());
  EXPECT_THROW(CorotationalShell(0, 1, 2, s.X[0], s.X[1], s.X[2], kShellMaterial, 0.0), InvalidInput);
  EXPECT_THROW(CorotationalShell(0, 1, 2, s.X[0], s.X[1], s.X[0], kShellMaterial, 0.02), InvalidInput);
}

TEST(CorotationalShell, StripRollsIntoHalfCircleUnderEndMoment) {
  // Cantilever strip L x b under an end moment M = pi EI / L: exact shape a half circle. Each
  // corotational element keeps its chord length l = L / n and turns it by M l / EI = pi / n, so
  // the nodes lie on the circle through the chord polygon: tip at x = 0, z = l / sin(pi / 2n)
  // (0.64 % above the arc's 2 L / pi for n = 8). Flat facets across the diagonals of a curved
  // strip add a small lateral drift, which vanishes with refinement.
  const double L = 1.0, b = 0.1, h = 0.01, E = 1.0e7;
  const int n = 8;
  Model model;
  const int mat = model.add_material({"strip", E, 0.0, 1000.0});
  for (int i = 0; i <= n; ++i) {
    model.add_node(Vec3(L * i / n, 0, 0));
    model.add_node(Vec3(L * i / n, b, 0));
  }
  for (int i = 0; i < n; ++i) {
    const int a0 = 2 * i, a1 = 2 * i + 1, b0 = 2 * i + 2, b1 = 2 * i + 3;
    const auto& X = model.reference_positions();
    // Alternating diagonals: a mesh without a preferred direction.
    const std::array<std::array<int, 3>, 2> tris =
        i % 2 == 0 ? std::array<std::array<int, 3>, 2>{{{a0, b0, b1}, {a0, b1, a1}}}
                   : std::array<std::array<int, 3>, 2>{{{a0, b0, a1}, {b0, b1, a1}}};
    for (const auto& t : tris)
      model.add_element(std::make_unique<CorotationalShell>(t[0], t[1], t[2], X[t[0]], X[t[1]],
                                                            X[t[2]], model.materials()[mat], h));
  }
  model.fix_node(0);
  model.fix_node(1);
  const double EI = E * b * h * h * h / 12.0;
  const double M = std::numbers::pi * EI / L;
  // The moment about -y bends the strip towards +z.
  model.add_nodal_load(2 * n, 4, -0.5 * M);
  model.add_nodal_load(2 * n + 1, 4, -0.5 * M);
  StaticOptions opt;
  opt.steps = 4;
  StaticSolver solver(model, opt);
  NodalState st = model.reference_state();
  solver.solve(st, 0.0, 1.0);
  const Vec3 tip = 0.5 * (st.position[2 * n] + st.position[2 * n + 1]);
  const double z_polygon = (L / n) / std::sin(0.5 * std::numbers::pi / n);
  EXPECT_NEAR(tip.x() / L, 0.0, 1e-4);
  EXPECT_NEAR(tip.z() / z_polygon, 1.0, 1e-4);
  EXPECT_NEAR(tip.y() / b, 0.5, 2e-3);
}

TEST(CorotationalShell, ViscousForceDampsTheDeformationRateOnly) {
  // Kelvin-Voigt damping f_d = eta D^T K_l D v (D = H P E^T): its power is eta d_dot^T K_l d_dot
  // with d_dot the rate of the local freedoms (central differences along v at a large
  // deformation), and a rigid motion of the deformed, loaded triangle is not damped.
  const ShellFixture s = skew_triangle();
  const CorotationalShell e(0, 1, 2, s.X[0], s.X[1], s.X[2], kShellMaterial, 0.02);
  std::mt19937 rng(4502);
  const NodalState st = shell_deformed(s, rng, 1.0);
  const double eta = 0.01;
  Eigen::VectorXd v(18), f(18);
  for (int i = 0; i < 18; ++i) v(i) = std::cos(0.3 + 2.9 * i);
  Eigen::MatrixXd C(18, 18);
  Element::MatrixRef Cr(C);
  e.viscous_force(st, v, eta, f, &Cr);
  const double h = 1e-6;
  NodalState plus = st, minus = st;
  plus.apply_increment(h * v);
  minus.apply_increment(-h * v);
  const Vec18 rate = (e.local_deformation(plus) - e.local_deformation(minus)) / (2 * h);
  const double power = eta * rate.dot(e.local_stiffness() * rate);
  EXPECT_NEAR(v.dot(f), power, 1e-7 * power);
  EXPECT_LT((C * v - f).norm(), 1e-12 * f.norm());

  const Vec3 w(-2.0, 0.5, 1.5), c(0.3, -0.1, 0.2);
  Eigen::VectorXd rigid(18);
  for (int a = 0; a < 3; ++a) {
    rigid.segment<3>(6 * a) = w.cross(st.position[a]) + c;
    rigid.segment<3>(6 * a + 3) = w;
  }
  Eigen::VectorXd fr(18);
  e.viscous_force(st, rigid, eta, fr, nullptr);
  EXPECT_LT(fr.norm(), 1e-12 * f.norm() * rigid.norm() / v.norm());
}

}  // namespace
}  // namespace finverse::fem
