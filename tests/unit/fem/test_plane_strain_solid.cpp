// Q9 St. Venant-Kirchhoff plane-strain solid: consistent tangent, frame invariance, patch test,
// mass, pure bending (exact for Q9), cantilever against Timoshenko beam theory, per-element
// materials, and the structured strip mesh.
#include <cmath>
#include <numbers>
#include <random>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include "fem/errors.hpp"
#include "fem/model.hpp"
#include "fem/plane_strain_solid.hpp"
#include "fem/static_solver.hpp"
#include "fem/structured_mesh.hpp"
#include "fem/validation/turek_hron_csm.hpp"

namespace finverse::fem {
namespace {

using Mat2 = PlaneStrainSolid::Mat2;

const Material kMaterial{"solid", 1.4e6, 0.4, 1000.0};

// A general Q9: a non-parallelogram quadrilateral with curved edges and an off-centre centre node.
std::array<Vec3, 9> distorted_element() {
  return {Vec3(0.0, 0.0, 0.3), Vec3(1.1, 0.1, 0.3),  Vec3(1.0, 0.9, 0.3), Vec3(-0.1, 0.8, 0.3),
          Vec3(0.55, 0.1, 0.3), Vec3(1.1, 0.5, 0.3), Vec3(0.45, 0.9, 0.3), Vec3(-0.02, 0.4, 0.3),
          Vec3(0.52, 0.46, 0.3)};
}

std::array<int, 9> first_nine() { return {0, 1, 2, 3, 4, 5, 6, 7, 8}; }

NodalState state_at(const std::array<Vec3, 9>& x) {
  NodalState s;
  s.position.assign(x.begin(), x.end());
  s.rotation.assign(9, Mat3::Identity());
  return s;
}

Mat3 rotation_z(double angle) {
  return Eigen::AngleAxisd(angle, Vec3::UnitZ()).toRotationMatrix();
}

// A large deformation: stretch, shear, a rotation of 0.7 rad and a random perturbation.
std::array<Vec3, 9> solid_deformed(const std::array<Vec3, 9>& X, unsigned seed = 1) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-0.08, 0.08);
  Mat3 A = Mat3::Identity();
  A(0, 0) = 1.25;
  A(0, 1) = 0.2;
  A(1, 1) = 0.85;
  A = rotation_z(0.7) * A;
  std::array<Vec3, 9> x;
  for (int k = 0; k < 9; ++k) x[k] = A * X[k] + Vec3(u(rng), u(rng), 0) + Vec3(0.3, -0.2, 0);
  for (auto& p : x) p.z() = 0.3;
  return x;
}

Eigen::VectorXd solid_force(const PlaneStrainSolid& e, const NodalState& s) {
  Eigen::VectorXd f(e.size());
  e.internal_force(s, f, nullptr);
  return f;
}

TEST(PlaneStrainSolid, TangentMatchesFiniteDifferencesOfInternalForce) {
  const auto X = distorted_element();
  const PlaneStrainSolid e(first_nine(), X, kMaterial);
  for (unsigned seed : {1u, 2u, 3u}) {
    const NodalState s = state_at(solid_deformed(X, seed));
    Eigen::VectorXd f(18);
    Eigen::MatrixXd K(18, 18);
    Element::MatrixRef Kref(K);
    e.internal_force(s, f, &Kref);
    // f is a cubic polynomial of the positions: central differences err by h^2 f''' / 6 only.
    const double h = 1e-5;
    Eigen::MatrixXd Kfd(18, 18);
    for (int c = 0; c < 18; ++c) {
      NodalState sp = s, sm = s;
      sp.position[c / 2](c % 2) += h;
      sm.position[c / 2](c % 2) -= h;
      Kfd.col(c) = (solid_force(e, sp) - solid_force(e, sm)) / (2 * h);
    }
    EXPECT_LT((K - Kfd).norm() / K.norm(), 1e-7) << "seed " << seed;
    EXPECT_LT((K - K.transpose()).norm() / K.norm(), 1e-14);
  }
}

TEST(PlaneStrainSolid, InternalForceIsGradientOfStrainEnergy) {
  const auto X = distorted_element();
  const PlaneStrainSolid e(first_nine(), X, kMaterial);
  const NodalState s = state_at(solid_deformed(X, 4));
  const Eigen::VectorXd f = solid_force(e, s);
  // W is a quartic polynomial of the positions: central differences err by h^2 W''' / 6.
  const double h = 1e-5;
  Eigen::VectorXd ffd(18);
  for (int c = 0; c < 18; ++c) {
    NodalState sp = s, sm = s;
    sp.position[c / 2](c % 2) += h;
    sm.position[c / 2](c % 2) -= h;
    ffd(c) = (e.strain_energy(sp) - e.strain_energy(sm)) / (2 * h);
  }
  EXPECT_LT((f - ffd).norm() / f.norm(), 1e-7);
}

TEST(PlaneStrainSolid, RigidMotionGivesNoForceAndForceIsObjective) {
  const auto X = distorted_element();
  const PlaneStrainSolid e(first_nine(), X, kMaterial);
  const double scale = kMaterial.youngs_modulus * e.volume();  // solid_force of a unit strain
  for (double angle : {0.3, 1.2, 2.5, -3.0}) {
    const Mat3 Q = rotation_z(angle);
    std::array<Vec3, 9> x;
    for (int k = 0; k < 9; ++k) x[k] = Q * X[k] + Vec3(1.5, -0.7, 0);
    for (auto& p : x) p.z() = 0.3;
    const NodalState s = state_at(x);
    EXPECT_LT(solid_force(e, s).norm(), 1e-12 * scale) << angle;
    EXPECT_LT(std::abs(e.strain_energy(s)), 1e-14 * scale) << angle;

    // A rotated solid_deformed state: the same strain energy, and forces rotated with it.
    const auto xd = solid_deformed(X, 5);
    std::array<Vec3, 9> xr;
    for (int k = 0; k < 9; ++k) xr[k] = Q * xd[k];
    for (auto& p : xr) p.z() = 0.3;
    const Eigen::VectorXd f0 = solid_force(e, state_at(xd)), f1 = solid_force(e, state_at(xr));
    Eigen::VectorXd f0r(18);
    for (int a = 0; a < 9; ++a) f0r.segment<2>(2 * a) = Q.topLeftCorner<2, 2>() * f0.segment<2>(2 * a);
    EXPECT_LT((f1 - f0r).norm(), 1e-12 * f0.norm()) << angle;
    EXPECT_NEAR(e.strain_energy(state_at(xr)), e.strain_energy(state_at(xd)),
                1e-12 * e.strain_energy(state_at(xd)));
  }
}

TEST(PlaneStrainSolid, MassMatrixAndGravityCarryTheMass) {
  // Straight-sided quadrilateral (geometry bilinear): its area is the shoelace formula.
  const Vec3 c[4] = {Vec3(0, 0, 0), Vec3(2.0, 0.2, 0), Vec3(1.8, 1.5, 0), Vec3(0.1, 1.0, 0)};
  const std::array<Vec3, 9> X = {c[0], c[1], c[2], c[3], 0.5 * (c[0] + c[1]), 0.5 * (c[1] + c[2]),
                                 0.5 * (c[2] + c[3]), 0.5 * (c[3] + c[0]),
                                 0.25 * (c[0] + c[1] + c[2] + c[3])};
  double area = 0;
  for (int k = 0; k < 4; ++k) area += 0.5 * (c[k].x() * c[(k + 1) % 4].y() - c[(k + 1) % 4].x() * c[k].y());
  const double thickness = 0.5;
  const PlaneStrainSolid e(first_nine(), X, kMaterial, thickness);
  const double mass = kMaterial.density * area * thickness;
  EXPECT_NEAR(e.total_mass(), mass, 1e-12 * mass);

  Eigen::MatrixXd M(18, 18);
  e.mass_matrix(state_at(X), M);
  Eigen::VectorXd ones_x = Eigen::VectorXd::Zero(18), ones_y = Eigen::VectorXd::Zero(18);
  for (int a = 0; a < 9; ++a) ones_x(2 * a) = ones_y(2 * a + 1) = 1;
  EXPECT_NEAR(ones_x.dot(M * ones_x), mass, 1e-12 * mass);  // rigid translation: m |v|^2
  EXPECT_NEAR(ones_y.dot(M * ones_y), mass, 1e-12 * mass);
  EXPECT_NEAR(ones_x.dot(M * ones_y), 0.0, 1e-14 * mass);
  EXPECT_LT((M - M.transpose()).norm(), 1e-14 * M.norm());
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(M);
  EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);  // consistent Q9 mass is positive definite

  Eigen::VectorXd fg(18);
  e.gravity_force(state_at(X), Vec3(0.5, -2.0, 7.0), fg);
  EXPECT_NEAR(ones_x.dot(fg), 0.5 * mass, 1e-12 * mass);
  EXPECT_NEAR(ones_y.dot(fg), -2.0 * mass, 1e-12 * mass);
  // The load is distributed like the mass: f = M g.
  Eigen::VectorXd g(18);
  for (int a = 0; a < 9; ++a) g.segment<2>(2 * a) << 0.5, -2.0;
  EXPECT_LT((fg - M * g).norm(), 1e-12 * fg.norm());
}

// Strip [0, L] x [-h/2, h/2] of Q9 elements in a model; returns mesh node -> model node.
struct Strip {
  Model model;
  StructuredMeshQ9 mesh;
  std::vector<int> id;
};
void make_strip(Strip& s, double L, double h, int nx, int ny, double grading, const Material& m) {
  StripSpec spec;
  spec.x_end = L;
  spec.y0 = -0.5 * h;
  spec.y1 = 0.5 * h;
  spec.nx = nx;
  spec.ny = ny;
  spec.grading_x = grading;
  s.mesh = mesh_strip_q9(spec);
  s.model.add_material(m);
  s.id = add_plane_strain_mesh(s.model, s.mesh, m);
}

TEST(PlaneStrainSolid, PatchTestHomogeneousDeformationIsExact) {
  // Distorted patch: interior nodes moved off the grid (curved element edges). Boundary nodes
  // follow x = F0 X; a homogeneous deformation is in the Q9 space for any isoparametric
  // geometry, so the interior must follow it exactly, with the exact uniform SVK stress.
  StripSpec spec;
  spec.x_end = 1.0;
  spec.y0 = 0;
  spec.y1 = 0.6;
  spec.nx = 3;
  spec.ny = 2;
  StructuredMeshQ9 mesh = mesh_strip_q9(spec);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-0.04, 0.04);
  const int ni = 2 * mesh.nx + 1, nj = 2 * mesh.ny + 1;
  std::vector<bool> boundary(mesh.nodes.size(), false);
  for (int j = 0; j < nj; ++j)
    for (int i = 0; i < ni; ++i) {
      const bool b = i == 0 || j == 0 || i == ni - 1 || j == nj - 1;
      boundary[mesh.node(i, j)] = b;
      if (!b) mesh.nodes[mesh.node(i, j)] += Vec3(u(rng), u(rng), 0);
    }
  Model model;
  model.add_material(kMaterial);
  const std::vector<int> id = add_plane_strain_mesh(model, mesh, kMaterial);
  Mat2 F0;
  F0 << 1.15, 0.12, -0.06, 0.92;  // stretch, shear and some rotation
  for (std::size_t k = 0; k < mesh.nodes.size(); ++k) {
    if (!boundary[k]) continue;
    const Eigen::Vector2d X = mesh.nodes[k].head<2>();
    const Eigen::Vector2d d = F0 * X - X;
    for (int dof = 0; dof < 2; ++dof)
      model.prescribe(id[k], dof, [v = d(dof)](double t) { return t * v; });
  }
  StaticOptions so;
  so.steps = 2;
  StaticSolver solver(model, so);
  NodalState state = model.reference_state();
  solver.solve(state, 0.0, 1.0);

  for (std::size_t k = 0; k < mesh.nodes.size(); ++k) {
    const Eigen::Vector2d X = mesh.nodes[k].head<2>();
    EXPECT_LT((state.position[id[k]].head<2>() - F0 * X).norm(), 1e-10) << "node " << k;
  }
  const Mat2 E0 = 0.5 * (F0.transpose() * F0 - Mat2::Identity());
  const auto& any = dynamic_cast<const PlaneStrainSolid&>(model.element(0));
  const double lambda = any.lame_lambda(), mu = any.lame_mu();
  const Mat2 S0 = lambda * E0.trace() * Mat2::Identity() + 2 * mu * E0;
  const Mat2 sigma0 = F0 * S0 * F0.transpose() / F0.determinant();
  const double szz0 = lambda * E0.trace() / F0.determinant();
  for (const auto& el : model.elements()) {
    const auto& solid = dynamic_cast<const PlaneStrainSolid&>(*el);
    for (const auto& p : solid.stresses(state)) {
      EXPECT_LT((p.second_piola_kirchhoff - S0).norm(), 1e-8 * S0.norm());
      EXPECT_LT((p.cauchy - sigma0).norm(), 1e-8 * sigma0.norm());
      EXPECT_NEAR(p.cauchy_zz, szz0, 1e-8 * sigma0.norm());
    }
  }
}

// Consistent nodal loads of a traction t(y) on the tip edge x = L (grid line i = 2 nx): per
// element edge, 3-point Gauss on the quadratic edge shape functions (exact up to degree 5).
void add_tip_traction(Strip& s, int dof, const std::function<double(double)>& t) {
  const double gp[3] = {-std::sqrt(0.6), 0.0, std::sqrt(0.6)}, gw[3] = {5. / 9, 8. / 9, 5. / 9};
  const int i = 2 * s.mesh.nx;
  for (int ey = 0; ey < s.mesh.ny; ++ey) {
    const int n[3] = {s.mesh.node(i, 2 * ey), s.mesh.node(i, 2 * ey + 1), s.mesh.node(i, 2 * ey + 2)};
    const double y0 = s.mesh.nodes[n[0]].y(), y2 = s.mesh.nodes[n[2]].y();
    double f[3] = {0, 0, 0};
    for (int q = 0; q < 3; ++q) {
      const double r = gp[q], y = 0.5 * (y0 + y2) + 0.5 * (y2 - y0) * r;
      const double N[3] = {0.5 * r * (r - 1), 1 - r * r, 0.5 * r * (r + 1)};
      for (int k = 0; k < 3; ++k) f[k] += gw[q] * 0.5 * (y2 - y0) * N[k] * t(y);
    }
    for (int k = 0; k < 3; ++k) s.model.add_nodal_load(s.id[n[k]], dof, f[k]);
  }
}

TEST(PlaneStrainSolid, PureBendingIsReproducedExactly) {
  // End moment as the linear traction sigma_xx = -M y / I. The plane-strain elasticity solution
  // u = -kappa x y, v = kappa x^2 / 2 + nu/(1-nu) kappa y^2 / 2, kappa = M / (E' I),
  // E' = E / (1 - nu^2), is quadratic, hence in the Q9 space: one element through the thickness
  // reproduces it (no shear locking). The load is small (kappa L = 1e-6), so the geometrically
  // nonlinear solution deviates from the linear one by ~1e-6 relatively.
  const double L = 1.0, h = 0.1, nu = 0.3;
  const Material m{"steel", 2e11, nu, 7800};
  Strip s;
  make_strip(s, L, h, 4, 1, 2.0, m);
  const double I = h * h * h / 12, Ep = m.youngs_modulus / (1 - nu * nu);
  const double kappa = 1e-6 / L, M = kappa * Ep * I;
  add_tip_traction(s, 0, [&](double y) { return -M * y / I; });
  for (int j = 0; j <= 2 * s.mesh.ny; ++j) s.model.fix(s.id[s.mesh.node(0, j)], 0);
  s.model.fix(s.id[s.mesh.node(0, s.mesh.ny)], 1);
  StaticSolver solver(s.model, StaticOptions{.steps = 1});
  NodalState state = s.model.reference_state();
  solver.solve(state, 0.0, 1.0);
  const double nup = nu / (1 - nu);
  for (std::size_t k = 0; k < s.mesh.nodes.size(); ++k) {
    const Vec3& X = s.mesh.nodes[k];
    const Vec3 u = state.position[s.id[k]] - X;
    EXPECT_NEAR(u.x(), -kappa * X.x() * X.y(), 1e-5 * kappa * L * h);
    EXPECT_NEAR(u.y(), 0.5 * kappa * (X.x() * X.x() + nup * X.y() * X.y()), 1e-5 * kappa * L * L);
  }
  const double sigma_max = M * 0.5 * h / I;
  for (const auto& el : s.model.elements())
    for (const auto& p : dynamic_cast<const PlaneStrainSolid&>(*el).stresses(state)) {
      EXPECT_NEAR(p.cauchy(0, 0), -M * p.X.y() / I, 1e-5 * sigma_max);
      EXPECT_NEAR(p.cauchy(1, 1), 0.0, 1e-5 * sigma_max);
      EXPECT_NEAR(p.cauchy(0, 1), 0.0, 1e-5 * sigma_max);
      EXPECT_NEAR(p.cauchy_zz, -nu * M * p.X.y() / I, 1e-5 * sigma_max);
    }
}

TEST(PlaneStrainSolid, CantileverTipLoadMatchesTimoshenkoBeam) {
  // Cantilever with a parabolic shear traction of resultant P at the tip, small load (linear
  // range). The plane-strain elasticity solution (Timoshenko & Goodier, "Theory of Elasticity",
  // sec. 21, with E' = E/(1-nu^2), nu' = nu/(1-nu)) is prescribed on the clamped edge, with its
  // constants chosen so that the centroid is fixed and the mean section rotation
  // phi = -int u y dA / I vanishes: the clamp of Timoshenko beam theory. The tip deflection is then
  //   delta = P L^3 / (3 E' I) + P L / (k G A) + 0.3 nu' P L / (E' A),  k = 5/6
  // (Timoshenko beam with shear correction, plus the Poisson coupling of the section warping).
  // The shear term is 1.3 % of delta here (L/h = 8), far above the tolerance.
  const double L = 0.4, h = 0.05, nu = 0.3;
  const Material m{"steel", 2e11, nu, 7800};
  Strip s;
  make_strip(s, L, h, 16, 2, 1.0, m);
  const double I = h * h * h / 12, A = h, Ep = m.youngs_modulus / (1 - nu * nu);
  const double nup = nu / (1 - nu), G = m.shear_modulus();
  const double P = 1e-6 * 3 * Ep * I / (L * L * L) * L;  // tip deflection ~ 1e-6 L
  add_tip_traction(s, 1, [&](double y) { return 1.5 * P / h * (1 - 4 * y * y / (h * h)); });
  const double a = P / (Ep * I), b = P / (G * I);
  const double C2 = (b - nup * a) / 6 * (3 * h * h / 20);
  for (int j = 0; j <= 2 * s.mesh.ny; ++j) {
    const double y = s.mesh.nodes[s.mesh.node(0, j)].y();
    const double u0 = (nup * a - b) / 6 * y * y * y + C2 * y, v0 = nup * a * L * y * y / 2;
    s.model.prescribe(s.id[s.mesh.node(0, j)], 0, [u0](double t) { return t * u0; });
    s.model.prescribe(s.id[s.mesh.node(0, j)], 1, [v0](double t) { return t * v0; });
  }
  StaticSolver solver(s.model, StaticOptions{.steps = 1});
  NodalState state = s.model.reference_state();
  solver.solve(state, 0.0, 1.0);
  const int k = s.mesh.node(2 * s.mesh.nx, s.mesh.ny);
  const double delta = state.position[s.id[k]].y() - s.mesh.nodes[k].y();
  const double bending = P * L * L * L / (3 * Ep * I), shear = P * L / (5.0 / 6.0 * G * A);
  const double poisson = 0.3 * nup * P * L / (Ep * A);
  EXPECT_NEAR(delta, bending + shear + poisson, 2e-4 * delta);
  EXPECT_NEAR(delta - bending, shear + poisson, 0.02 * shear);  // shear flexibility resolved
}

TEST(PlaneStrainSolid, PerElementMaterialsInSeries) {
  // Two elements of different E and density in series under an end tension (nu = 0: uniaxial
  // plane strain is then uniaxial stress and exact for Q9): elongation P L1 / (E1 A) +
  // P L2 / (E2 A), mass rho1 A1 + rho2 A2.
  const double h = 0.1, L1 = 0.4, L2 = 0.6;
  const Material m1{"soft", 1e6, 0.0, 1000}, m2{"stiff", 4e6, 0.0, 3000};
  StripSpec spec;
  spec.x_end = L1 + L2;
  spec.y0 = 0;
  spec.y1 = h;
  spec.nx = 2;
  spec.ny = 1;
  spec.grading_x = L2 / L1;
  const StructuredMeshQ9 mesh = mesh_strip_q9(spec);
  Model model;
  model.add_material(m1);
  model.add_material(m2);
  std::vector<int> id;
  for (const auto& X : mesh.nodes) id.push_back(model.add_node(X));
  for (int e = 0; e < 2; ++e) {
    std::array<int, 9> nodes;
    std::array<Vec3, 9> X;
    for (int k = 0; k < 9; ++k) nodes[k] = id[mesh.elements[e][k]], X[k] = mesh.nodes[mesh.elements[e][k]];
    model.add_element(std::make_unique<PlaneStrainSolid>(nodes, X, e == 0 ? m1 : m2));
  }
  EXPECT_NEAR(model.total_mass(), (m1.density * L1 + m2.density * L2) * h, 1e-12);
  const double P = 1e-3;  // strain ~ 1e-8: linear range
  for (int j = 0; j <= 2; ++j) {
    model.fix(id[mesh.node(0, j)], 0);
    model.add_nodal_load(id[mesh.node(4, j)], 0, P * (j == 1 ? 4.0 : 1.0) / 6.0);
  }
  model.fix(id[mesh.node(0, 0)], 1);
  StaticSolver solver(model, StaticOptions{.steps = 1});
  NodalState state = model.reference_state();
  solver.solve(state, 0.0, 1.0);
  const double expected = P * L1 / (m1.youngs_modulus * h) + P * L2 / (m2.youngs_modulus * h);
  for (int j = 0; j <= 2; ++j) {
    const int k = mesh.node(4, j);
    EXPECT_NEAR(state.position[id[k]].x() - mesh.nodes[k].x(), expected, 1e-6 * expected);
  }
}

TEST(PlaneStrainSolid, RejectsBadInput) {
  auto X = distorted_element();
  EXPECT_THROW(PlaneStrainSolid(first_nine(), X, kMaterial, 0.0), InvalidInput);
  EXPECT_THROW(PlaneStrainSolid(first_nine(), X, Material{"bad", 1e6, 0.5, 1000}), InvalidInput);
  auto flipped = X;  // clockwise corners: negative Jacobian
  std::swap(flipped[1], flipped[3]);
  std::swap(flipped[4], flipped[7]);
  std::swap(flipped[5], flipped[6]);
  EXPECT_THROW(PlaneStrainSolid(first_nine(), flipped, kMaterial), InvalidInput);
  auto tilted = X;
  tilted[2].z() += 0.1;
  EXPECT_THROW(PlaneStrainSolid(first_nine(), tilted, kMaterial), InvalidInput);
}

TEST(StructuredMesh, GradedStripWithCurvedLeftEdge) {
  StripSpec spec;
  spec.x_begin = [](double y) { return 0.2 + std::sqrt(0.05 * 0.05 - y * y); };
  spec.x_end = 0.6;
  spec.y0 = -0.01;
  spec.y1 = 0.01;
  spec.nx = 6;
  spec.ny = 2;
  spec.grading_x = 4.0;
  const StructuredMeshQ9 m = mesh_strip_q9(spec);
  ASSERT_EQ(m.nodes.size(), 13u * 5u);
  ASSERT_EQ(m.elements.size(), 12u);
  for (int j = 0; j <= 4; ++j) {
    const double y = m.nodes[m.node(0, j)].y();
    EXPECT_NEAR(y, -0.01 + 0.005 * j, 1e-15);
    EXPECT_NEAR(m.nodes[m.node(0, j)].x(), spec.x_begin(y), 1e-15);
    EXPECT_NEAR(m.nodes[m.node(12, j)].x(), 0.6, 1e-15);
  }
  // Along the centre line: geometric growth by 4^(1/5) per element, mid-sides at midpoints.
  const auto x = [&](int i) { return m.nodes[m.node(i, 2)].x(); };
  EXPECT_NEAR((x(12) - x(10)) / (x(2) - x(0)), 4.0, 1e-12);
  for (int e = 0; e + 1 < 6; ++e)
    EXPECT_NEAR((x(2 * e + 4) - x(2 * e + 2)) / (x(2 * e + 2) - x(2 * e)), std::pow(4.0, 0.2), 1e-12);
  for (int e = 0; e < 6; ++e) EXPECT_NEAR(x(2 * e + 1), 0.5 * (x(2 * e) + x(2 * e + 2)), 1e-15);
  // The elements tile the strip: their area is int (x_end - x_begin(y)) dy, up to the quadratic
  // interpolation of the arc (~2e-9 here, falling as dy^4).
  Model model;
  const Material mat{"m", 1e6, 0.3, 1.0};
  model.add_material(mat);
  add_plane_strain_mesh(model, m, mat);
  const double r = 0.05, c = 0.01;
  const double arc = c * std::sqrt(r * r - c * c) + r * r * std::asin(c / r);  // int sqrt(r^2-y^2)
  EXPECT_NEAR(model.total_mass(), 0.4 * 0.02 - arc, 5e-9);
  StripSpec bad = spec;
  bad.nx = 0;
  EXPECT_THROW(mesh_strip_q9(bad), InvalidInput);
  bad = spec;
  bad.x_end = 0.2;  // left of the arc
  EXPECT_THROW(mesh_strip_q9(bad), InvalidInput);
}

TEST(TurekHronCsm, LastPeriodMeanAmplitudeAndFrequency) {
  // A sampled anharmonic oscillation with a small fast ripple: mean and amplitude of the main
  // component plus the ripple's share, frequency of the main one.
  const double f = 1.1, dt = 1e-3;
  std::vector<double> t, y;
  for (int k = 0; k <= 10000; ++k) {
    const double tk = k * dt, w = 2 * std::numbers::pi * f * tk;
    t.push_back(tk);
    y.push_back(-0.06 - 0.065 * std::cos(w) + 0.004 * std::cos(2 * w));
  }
  const auto p = validation::last_period(t, y);
  EXPECT_NEAR(p.frequency, f, 1e-5);
  EXPECT_NEAR(p.mean_frequency, f, 1e-5);
  EXPECT_EQ(p.periods, 10);
  const auto ma = validation::mean_amplitude(t, y, p.t_begin, p.t_end);
  // Extremes of -0.065 cos w + 0.004 cos 2w: at w = 0 (-0.061) and w = pi (0.069).
  EXPECT_NEAR(ma.mean, -0.06 + 0.004, 1e-7);
  EXPECT_NEAR(ma.amplitude, 0.065, 1e-7);
  EXPECT_THROW(validation::last_period({0, 1, 2}, {0, 1, 2}), NotConverged);
}

}  // namespace
}  // namespace finverse::fem
