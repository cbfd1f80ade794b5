// Local linear flat shell triangle (OPT membrane + DKT plate): rigid modes, patch tests, in-plane
// bending, and plate deflections against Timoshenko & Woinowsky-Krieger.
#include <cmath>
#include <functional>
#include <numbers>
#include <random>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <Eigen/Sparse>
#include <gtest/gtest.h>

#include "fem/dkt_plate.hpp"
#include "fem/flat_shell_triangle.hpp"
#include "fem/opt_membrane.hpp"
#include "fem/rotation.hpp"

namespace finverse::fem {
namespace {

TriangleXY irregular_triangle() {
  TriangleXY xy;
  xy << 0.1, -0.2, 1.3, 0.15, 0.45, 0.9;
  return xy;
}

// Local freedoms of corner a at (x, y) for a rigid motion: translation t, rotation vector r.
Vec18 rigid_mode(const TriangleXY& xy, const Vec3& t, const Vec3& r) {
  Vec18 d;
  for (int a = 0; a < 3; ++a) {
    const Vec3 X(xy(a, 0), xy(a, 1), 0.0);
    d.segment<3>(6 * a) = t + r.cross(X);
    d.segment<3>(6 * a + 3) = r;
  }
  return d;
}

TEST(FlatShellTriangle, RigidModesCarryNoForce) {
  const TriangleXY xy = irregular_triangle();
  const Mat18 K = flat_shell_stiffness(xy, 2.0e9, 0.3, 0.01);
  EXPECT_LT((K - K.transpose()).norm(), 1e-12 * K.norm());
  for (int i = 0; i < 6; ++i) {
    Vec3 t = Vec3::Zero(), r = Vec3::Zero();
    (i < 3 ? t : r)(i % 3) = 1.0;
    EXPECT_LT((K * rigid_mode(xy, t, r)).norm(), 1e-10 * K.norm()) << "rigid mode " << i;
  }
  // Exactly six zero eigenvalues: no spurious mechanism (the drilling freedoms are stiff).
  Eigen::SelfAdjointEigenSolver<Mat18> eig(K);
  const auto& ev = eig.eigenvalues();
  EXPECT_LT(std::abs(ev(5)), 1e-10 * ev(17));
  EXPECT_GT(ev(6), 1e-8 * ev(17));
}

TEST(DktPlate, ReproducesQuadraticDeflectionExactly) {
  // w = c0 + c1 x + c2 y + k1 x^2/2 + k2 y^2/2 + k3 x y: kappa = -[w,xx w,yy 2 w,xy] everywhere.
  const TriangleXY xy = irregular_triangle();
  const double c0 = 0.3, c1 = -0.2, c2 = 0.7, k1 = 1.1, k2 = -0.4, k3 = 0.6;
  Eigen::Matrix<double, 9, 1> q;
  for (int a = 0; a < 3; ++a) {
    const double x = xy(a, 0), y = xy(a, 1);
    q(3 * a) = c0 + c1 * x + c2 * y + 0.5 * k1 * x * x + 0.5 * k2 * y * y + k3 * x * y;
    q(3 * a + 1) = c2 + k2 * y + k3 * x;     // theta_x = w,y
    q(3 * a + 2) = -(c1 + k1 * x + k3 * y);  // theta_y = -w,x
  }
  for (const auto& p : {std::array<double, 2>{1.0 / 3, 1.0 / 3}, {0.1, 0.7}, {0.8, 0.05}}) {
    const Eigen::Vector3d kappa = dkt_curvature_matrix(xy, p[0], p[1]) * q;
    EXPECT_NEAR(kappa(0), -k1, 1e-12);
    EXPECT_NEAR(kappa(1), -k2, 1e-12);
    EXPECT_NEAR(kappa(2), -2 * k3, 1e-12);
  }
}

// A patch of four distorted triangles around one interior node (MacNeal-Harder style).
struct Patch {
  std::vector<Eigen::Vector2d> nodes;
  std::vector<std::array<int, 3>> triangles;
};
Patch distorted_patch() {
  Patch p;
  p.nodes = {{0.0, 0.0}, {2.0, 0.0}, {2.4, 1.8}, {-0.3, 1.5}, {0.9, 0.6}};
  p.triangles = {{0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}};
  return p;
}

// Assembles the local stiffness over the patch (all in one plane: local = global), prescribes the
// boundary nodes from `exact`, solves for the interior node and returns its error.
double patch_error(const Patch& p, const std::function<Eigen::Matrix<double, 6, 1>(double, double)>& exact) {
  const int n = static_cast<int>(p.nodes.size());
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(6 * n, 6 * n);
  for (const auto& t : p.triangles) {
    TriangleXY xy;
    for (int a = 0; a < 3; ++a) xy.row(a) = p.nodes[t[a]].transpose();
    const Mat18 k = flat_shell_stiffness(xy, 1.0e7, 0.25, 0.05);
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) K.block<6, 6>(6 * t[a], 6 * t[b]) += k.block<6, 6>(6 * a, 6 * b);
  }
  Eigen::VectorXd d(6 * n);
  for (int i = 0; i < n; ++i) d.segment<6>(6 * i) = exact(p.nodes[i].x(), p.nodes[i].y());
  const int in = 4;  // interior node
  const Eigen::Matrix<double, 6, 1> d_exact = d.segment<6>(6 * in);
  Eigen::VectorXd rhs = -K.middleRows<6>(6 * in) * d + K.block<6, 6>(6 * in, 6 * in) * d_exact;
  const Eigen::Matrix<double, 6, 1> d_in = K.block<6, 6>(6 * in, 6 * in).ldlt().solve(rhs);
  return (d_in - d_exact).norm() / d_exact.norm();
}

TEST(FlatShellTriangle, MembranePatchTest) {
  // Linear in-plane field; the drilling rotation is the rigid rotation (v,x - u,y)/2.
  const double err = patch_error(distorted_patch(), [](double x, double y) {
    Eigen::Matrix<double, 6, 1> d;
    d << 1e-3 + 2e-3 * x - 1e-3 * y, -2e-3 + 0.5e-3 * x + 3e-3 * y, 0, 0, 0,
        0.5 * (0.5e-3 - (-1e-3));
    return d;
  });
  EXPECT_LT(err, 1e-10);
}

TEST(FlatShellTriangle, BendingPatchTest) {
  const double err = patch_error(distorted_patch(), [](double x, double y) {
    const double k1 = 0.02, k2 = -0.01, k3 = 0.015;
    Eigen::Matrix<double, 6, 1> d;
    d << 0, 0, 0.5 * k1 * x * x + 0.5 * k2 * y * y + k3 * x * y + 0.01 * x, k2 * y + k3 * x,
        -(k1 * x + k3 * y + 0.01), 0;
    return d;
  });
  EXPECT_LT(err, 1e-10);
}

// Sparse linear solve of a structured rectangular mesh of a x b split into 2 nx ny triangles,
// with the given fixed global DOFs and loads; returns the displacement vector.
struct Grid {
  int nx, ny;
  double a, b;
  int node(int i, int j) const { return j * (nx + 1) + i; }
  Eigen::Vector2d X(int i, int j) const { return {a * i / nx, b * j / ny}; }
};

Eigen::VectorXd solve_grid(const Grid& g, double E, double nu, double h,
                           const std::function<bool(int, int, int)>& fixed,
                           const std::function<void(const TriangleXY&, const std::array<int, 3>&,
                                                    Eigen::VectorXd&)>& load,
                           const Eigen::VectorXd* nodal_loads = nullptr) {
  const int n = (g.nx + 1) * (g.ny + 1), N = 6 * n;
  std::vector<Eigen::Triplet<double>> trip;
  Eigen::VectorXd f = nodal_loads ? *nodal_loads : Eigen::VectorXd::Zero(N);
  for (int j = 0; j < g.ny; ++j)
    for (int i = 0; i < g.nx; ++i) {
      // Alternate the diagonal so that the mesh has no preferred direction.
      const int n00 = g.node(i, j), n10 = g.node(i + 1, j), n01 = g.node(i, j + 1),
                n11 = g.node(i + 1, j + 1);
      const bool flip = (i + j) % 2;
      const std::array<std::array<int, 3>, 2> tris =
          flip ? std::array<std::array<int, 3>, 2>{{{n00, n10, n01}, {n10, n11, n01}}}
               : std::array<std::array<int, 3>, 2>{{{n00, n10, n11}, {n00, n11, n01}}};
      for (const auto& t : tris) {
        TriangleXY xy;
        for (int a = 0; a < 3; ++a) xy.row(a) = g.X(t[a] % (g.nx + 1), t[a] / (g.nx + 1)).transpose();
        const Mat18 k = flat_shell_stiffness(xy, E, nu, h);
        for (int a = 0; a < 3; ++a)
          for (int b = 0; b < 3; ++b)
            for (int r = 0; r < 6; ++r)
              for (int c = 0; c < 6; ++c) trip.emplace_back(6 * t[a] + r, 6 * t[b] + c, k(6 * a + r, 6 * b + c));
        load(xy, t, f);
      }
    }
  Eigen::SparseMatrix<double> K(N, N);
  K.setFromTriplets(trip.begin(), trip.end());
  // Fixed DOFs: unit diagonal, zero load (homogeneous conditions only).
  std::vector<bool> fix(N, false);
  for (int j = 0; j <= g.ny; ++j)
    for (int i = 0; i <= g.nx; ++i)
      for (int d = 0; d < 6; ++d) fix[6 * g.node(i, j) + d] = fixed(i, j, d);
  for (int k = 0; k < K.outerSize(); ++k)
    for (Eigen::SparseMatrix<double>::InnerIterator it(K, k); it; ++it)
      if (fix[it.row()] || fix[it.col()]) it.valueRef() = (it.row() == it.col()) ? 1.0 : 0.0;
  for (int i = 0; i < N; ++i)
    if (fix[i]) f(i) = 0;
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver(K);
  EXPECT_EQ(solver.info(), Eigen::Success);
  return solver.solve(f);
}

// Navier series for the simply supported square plate under uniform load q, centre deflection
// in units of q a^4 / D (Timoshenko & Woinowsky-Krieger 1959, sec. 30: 0.00406).
double navier_square_centre() {
  double w = 0;
  for (int m = 1; m < 400; m += 2)
    for (int n = 1; n < 400; n += 2) {
      const double s = ((m / 2 + n / 2) % 2 == 0) ? 1.0 : -1.0;  // sin(m pi/2) sin(n pi/2)
      w += s / (m * n * std::pow(m * m + n * n, 2));
    }
  return 16.0 / std::pow(std::numbers::pi, 6) * w;
}

double plate_centre_deflection(bool clamped, int n) {
  const double a = 1.0, E = 1.0e6, nu = 0.3, h = 0.01, q = 1.0;
  const Grid g{n, n, a, a};
  const Eigen::VectorXd d = solve_grid(
      g, E, nu, h,
      [&](int i, int j, int dof) {
        const bool edge = i == 0 || j == 0 || i == n || j == n;
        if (dof == 0 || dof == 1 || dof == 5) return true;  // membrane is not loaded
        return edge && (clamped || dof == 2);
      },
      [&](const TriangleXY& xy, const std::array<int, 3>& t, Eigen::VectorXd& f) {
        for (int k : t) f(6 * k + 2) += q * signed_area(xy) / 3.0;
      });
  const double D = E * h * h * h / (12.0 * (1.0 - nu * nu));
  return d(6 * g.node(n / 2, n / 2) + 2) / (q * a * a * a * a / D);
}

TEST(DktPlate, SimplySupportedSquarePlateMatchesNavierSeries) {
  const double reference = navier_square_centre();
  EXPECT_NEAR(reference, 0.00406, 0.000005);
  const double w = plate_centre_deflection(false, 16);
  EXPECT_LT(std::abs(w / reference - 1.0), 0.01) << "w = " << w << ", reference " << reference;
}

TEST(DktPlate, ClampedSquarePlateMatchesTimoshenko) {
  // Timoshenko & Woinowsky-Krieger (1959), table 35: 0.00126 q a^4 / D (nu = 0.3); more digits:
  // 0.00126532 (Taylor & Govindjee 2004, Commun. Numer. Meth. Engng 20:757).
  const double reference = 0.00126532;
  const double w = plate_centre_deflection(true, 16);
  EXPECT_LT(std::abs(w / reference - 1.0), 0.015) << "w = " << w;
}

TEST(OptMembrane, InPlaneBendingOfCantileverIsNearlyExact) {
  // Cantilever L x c in its own plane, end couple M as a linear traction; beam theory tip
  // deflection M L^2 / (2 E I) is exact for plane stress with nu = 0. OPT is exact for pure
  // bending of rectangles; on this triangulation it stays within 1 %, where constant-strain
  // triangles two across the depth would be several times too stiff.
  const double L = 10.0, c = 1.0, E = 1.0e4, h = 0.1, M = 1.0;
  const Grid g{10, 2, L, c};
  const double I = h * c * c * c / 12.0;
  // Consistent nodal forces of sigma_xx = M y / I on the end section (linear per edge).
  const int n = (g.nx + 1) * (g.ny + 1);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(6 * n);
  auto traction = [&](double y) { return M * y / I * h; };
  for (int j = 0; j < g.ny; ++j) {
    const double y0 = c * j / g.ny - 0.5 * c, y1 = c * (j + 1) / g.ny - 0.5 * c, l = y1 - y0;
    f(6 * g.node(g.nx, j)) += l * (2 * traction(y0) + traction(y1)) / 6.0;
    f(6 * g.node(g.nx, j + 1)) += l * (traction(y0) + 2 * traction(y1)) / 6.0;
  }
  // Root: u = v = 0 (exact for nu = 0); bending freedoms unused.
  const Eigen::VectorXd d = solve_grid(
      g, E, 0.0, h,
      [&](int i, int, int dof) { return dof == 2 || dof == 3 || dof == 4 || (i == 0 && dof < 2); },
      [](const TriangleXY&, const std::array<int, 3>&, Eigen::VectorXd&) {}, &f);
  const double v_tip = d(6 * g.node(g.nx, g.ny / 2) + 1);
  // Tension at y > 0 (sigma = M y / I) curls the strip towards -y.
  const double exact = -M * L * L / (2.0 * E * I);
  EXPECT_LT(std::abs(v_tip / exact - 1.0), 0.01) << "v_tip = " << v_tip << ", exact " << exact;
}

}  // namespace
}  // namespace finverse::fem
