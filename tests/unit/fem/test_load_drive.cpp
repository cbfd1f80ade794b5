// Loads and drive from tabulated data: nodal loads interpolated in time (loads.h5), the ramp from
// rest, and prescribed root translation + rotation derived from tracked root positions.
#include <cmath>

#include <gtest/gtest.h>

#include "fem/errors.hpp"
#include "fem/load_history.hpp"
#include "fem/root_motion.hpp"
#include "fem/static_solver.hpp"
#include "fem_test_models.hpp"

using namespace finverse::fem;
using finverse::fem::test::cantilever;
using finverse::fem::test::lattice;

namespace {
constexpr double L = 0.5, E = 2e9, b = 0.01, t = 0.002;
constexpr int n = 8;
const double P = 2.0 * E * b * t * t * t / 12 / (L * L);  // PL^2/EI = 2: large deflection

Eigen::VectorXd tip_load(const Model& m, double value) {
  Eigen::VectorXd f = Eigen::VectorXd::Zero(kDofsPerNode * m.node_count());
  f(kDofsPerNode * n + 2) = value;
  return f;
}
}  // namespace

TEST(LoadHistory, InterpolatesLinearlyWithRampAndHold) {
  const LoadHistory h({1.0, 2.0, 4.0}, {Eigen::VectorXd::Constant(2, 1.0), Eigen::VectorXd::Constant(2, 3.0),
                                        Eigen::VectorXd::Constant(2, -1.0)}, 0.5);
  EXPECT_DOUBLE_EQ(h.at(0.0)(0), 0.0);    // before the ramp
  EXPECT_DOUBLE_EQ(h.at(0.75)(0), 0.5);   // half way up the ramp
  EXPECT_DOUBLE_EQ(h.at(1.5)(1), 2.0);
  EXPECT_DOUBLE_EQ(h.at(3.0)(0), 1.0);
  EXPECT_DOUBLE_EQ(h.at(9.0)(0), -1.0);   // held
  EXPECT_THROW(LoadHistory({0.0, 0.0}, {Eigen::VectorXd::Zero(1), Eigen::VectorXd::Zero(1)}), InvalidInput);
  Eigen::VectorXd bad = Eigen::VectorXd::Zero(12);
  bad(10) = std::nan("");
  try {
    LoadHistory({0.0}, {bad});
    FAIL() << "NaN load accepted";
  } catch (const InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("node 1 my"), std::string::npos) << e.what();
  }
}

TEST(LoadHistory, RampedCantileverEqualsDirectStaticSolution) {
  Model direct = cantilever(n, L, E, b, t, b, t);
  direct.add_nodal_load(n, 2, P);
  StaticSolver ds(direct, StaticOptions{.steps = 8});
  NodalState x_direct = direct.reference_state();
  ds.solve(x_direct, 0, 1);

  // Same load from a table: 0.4 P at t = 0.1, P at t = 0.3, reached through a 0.1 s ramp.
  Model m = cantilever(n, L, E, b, t, b, t);
  m.set_load_history(LoadHistory({0.1, 0.3}, {tip_load(m, 0.4 * P), tip_load(m, P)}, 0.1));
  StaticSolver solver(m, StaticOptions{.steps = 8});
  NodalState x = m.reference_state();
  solver.solve(x, 0.0, 0.3);
  EXPECT_LT((x.position[n] - x_direct.position[n]).norm(), 1e-9 * L);
  EXPECT_GT(std::abs(x.position[n].z()), 0.3 * L);  // really nonlinear
  // Half way between the samples: 0.7 P.
  Model half = cantilever(n, L, E, b, t, b, t);
  half.add_nodal_load(n, 2, 0.7 * P);
  StaticSolver hs(half, StaticOptions{.steps = 8});
  NodalState xh = half.reference_state();
  hs.solve(xh, 0, 1);
  NodalState y = m.reference_state();
  StaticSolver s2(m, StaticOptions{.steps = 8});
  s2.solve(y, 0.0, 0.2);
  EXPECT_LT((y.position[n] - xh.position[n]).norm(), 1e-9 * L);
}

TEST(RootMotion, RigidRotationFitRecoversPlanarAndCollinearSets) {
  const Vec3 theta(0.1, -0.3, 0.2);
  const Mat3 R = exp_so3(theta);
  const std::vector<Vec3> X{{0, 0, 0}, {0.1, 0, 0}, {0, 0.2, 0}, {0.05, 0.1, 0.01}};
  std::vector<Vec3> x;
  for (const auto& p : X) x.push_back(R * p + Vec3(1, 2, 3));
  EXPECT_LT((fit_rigid_rotation(X, x) - R).norm(), 1e-12);
  // Collinear along y, rotated about z (perpendicular to the line): recovered exactly.
  const Mat3 Rz = exp_so3(Vec3(0, 0, 0.3));
  const std::vector<Vec3> line{{0, 0, 0}, {0, 0.01, 0}, {0, 0.02, 0}};
  std::vector<Vec3> moved;
  for (const auto& p : line) moved.push_back(Rz * p);
  EXPECT_LT((fit_rigid_rotation(line, moved) - Rz).norm(), 1e-12);
  // ... while a spin about the line itself is not observable and taken as zero.
  const Mat3 Ry = exp_so3(Vec3(0, 0.4, 0));
  moved.clear();
  for (const auto& p : line) moved.push_back(Ry * p);
  EXPECT_LT((fit_rigid_rotation(line, moved) - Mat3::Identity()).norm(), 1e-12);
}

TEST(RootMotion, SupportPointsCarryThePitchAboutACollinearRoot) {
  // A fin base: root nodes on the z axis, pitched about that axis by 0.25 rad. The root nodes
  // alone see no rotation; with the rays' first nodes as support the pitch is recovered.
  const Mat3 R = exp_so3(Vec3(0, 0, 0.25));
  const std::vector<Vec3> root{{0, 0, 0}, {0, 0, 0.01}, {0, 0, 0.02}};
  const std::vector<Vec3> ray{{0.004, 0, 0}, {0.004, 0, 0.012}, {0.004, 0, 0.024}};
  std::vector<Vec3> root_moved, ray_moved;
  for (const auto& p : root) root_moved.push_back(R * p);
  for (const auto& p : ray) ray_moved.push_back(R * p);
  const RootMotion alone({0, 1, 2}, root, {0.0, 1.0}, {root, root_moved}, RootRotation::fit);
  EXPECT_LT(alone.rotation_vector(1.0).norm(), 1e-12);
  const RootMotion supported({0, 1, 2}, root, {0.0, 1.0}, {root, root_moved}, RootRotation::fit, 0,
                             RotationSupport{ray, {ray, ray_moved}});
  EXPECT_LT((supported.rotation_vector(1.0) - Vec3(0, 0, 0.25)).norm(), 1e-12);
  EXPECT_LT((supported.rotation_vector(0.5) - Vec3(0, 0, 0.125)).norm(), 1e-12);
  // The support must have one frame per sample and finite points.
  EXPECT_THROW(RootMotion({0, 1, 2}, root, {0.0, 1.0}, {root, root_moved}, RootRotation::fit, 0,
                          RotationSupport{ray, {ray}}),
               InvalidInput);
  std::vector<Vec3> bad = ray_moved;
  bad[1](0) = std::nan("");
  EXPECT_THROW(RootMotion({0, 1, 2}, root, {0.0, 1.0}, {root, root_moved}, RootRotation::fit, 0,
                          RotationSupport{ray, {ray, bad}}),
               InvalidInput);
}

TEST(RootMotion, TrackedRootMovesTheUnloadedStructureRigidly) {
  // 5 x 5 beam lattice clamped along x = 0 (root nodes 0, 5, 10, ... along y).
  Model m = lattice(5);
  std::vector<int> root;
  std::vector<Vec3> X;
  for (int j = 0; j < 5; ++j) root.push_back(5 * j), X.push_back(m.reference_positions()[5 * j]);
  const Vec3 shift(0.002, -0.001, 0.003);
  auto frame = [&](double s) {
    std::vector<Vec3> p;
    for (const auto& x0 : X) p.push_back(exp_so3(Vec3(0, 0, 0.2 * s)) * x0 + s * shift);
    return p;
  };
  const RootMotion motion(root, X, {0.0, 1.0}, {frame(0), frame(1)}, RootRotation::fit);
  motion.apply(m);
  StaticSolver solver(m, StaticOptions{.steps = 4});
  NodalState s = m.reference_state();
  solver.solve(s, 0.0, 1.0);
  const Mat3 R = exp_so3(Vec3(0, 0, 0.2));
  for (int i = 0; i < m.node_count(); ++i)
    EXPECT_LT((s.position[i] - (R * m.reference_positions()[i] + shift)).norm(), 1e-9) << "node " << i;
  EXPECT_LT((s.rotation[24] - R).norm(), 1e-9);
  // "zero": root translations only, root rotations held -> the lattice bends and is stressed.
  Model z = lattice(5);
  RootMotion(root, X, {0.0, 1.0}, {frame(0), frame(1)}, RootRotation::zero).apply(z);
  StaticSolver zs(z, StaticOptions{.steps = 4});
  NodalState sz = z.reference_state();
  zs.solve(sz, 0.0, 1.0);
  EXPECT_GT(zs.assembler().strain_energy(sz), 0.0);
  EXPECT_LT((sz.rotation[0] - Mat3::Identity()).norm(), 1e-12);
}
