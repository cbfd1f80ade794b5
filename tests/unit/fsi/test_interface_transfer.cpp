// Test (c): the conservative load transfer (interface_transfer.hpp) keeps total force and total
// moment about an arbitrary point between the flow's samples and the structure's nodal loads, in
// 2-D (polyline, random samples) and 3-D (triangulated surface, random barycentric samples), to
// round-off; the interface power is the same on both sides; the motion map; bad input throws.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include <Eigen/Geometry>

#include "core/error.hpp"
#include "fsi/interface_transfer.hpp"

namespace finverse::fsi {
namespace {

double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) { return a(0) * b(1) - a(1) * b(0); }

TEST(InterfaceTransfer, TwoDimensionalLoadsKeepForceMomentAndPower) {
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g;
  // A closed wavy polyline of 60 nodes (a flag-like surface), numbered in shuffled order.
  const int n = 60;
  Eigen::Matrix2Xd nodes(2, n);
  for (int i = 0; i < n; ++i) {
    const double s = 2.0 * M_PI * i / n;
    nodes.col(i) << 3.0 * std::cos(s) + 0.2 * std::sin(5 * s), 0.4 * std::sin(s);
  }
  std::vector<std::array<int, 2>> segments;
  for (int i = 0; i < n; ++i) segments.push_back({i, (i + 1) % n});
  const WetSurface2D surface(n, segments);

  std::vector<WetSurface2D::Sample> samples(500);
  for (auto& q : samples) {
    q.segment = static_cast<int>(u(rng) * n) % n;
    q.xi = u(rng);
    q.force << 1e3 * g(rng), 1e3 * g(rng);
  }
  samples[0].xi = 0.0;  // ends of a segment
  samples[1].xi = 1.0;
  const Eigen::Matrix2Xd loads = surface.nodal_loads(samples);

  Eigen::Vector2d force_flow = Eigen::Vector2d::Zero();
  double moment_flow = 0.0, scale = 0.0;
  const Eigen::Vector2d c(1.7, -2.3);  // any point
  for (const auto& q : samples) {
    force_flow += q.force;
    moment_flow += cross2(surface.point(q, nodes) - c, q.force);
    scale += q.force.norm() * ((surface.point(q, nodes) - c).norm() + 1.0);
  }
  const Eigen::Vector2d force_nodes = loads.rowwise().sum();
  double moment_nodes = 0.0;
  for (int i = 0; i < n; ++i) moment_nodes += cross2(nodes.col(i) - c, loads.col(i));
  const double force_scale = scale;  // sum |F| (1 + |arm|) bounds both sums
  std::printf("[ transfer ] 2-D, %zu samples: |dF| / sum|F| = %.1e, |dM| / sum|F||r| = %.1e\n",
              samples.size(), (force_nodes - force_flow).norm() / force_scale,
              std::abs(moment_nodes - moment_flow) / scale);
  EXPECT_LT((force_nodes - force_flow).norm(), 1e-12 * force_scale);
  EXPECT_LT(std::abs(moment_nodes - moment_flow), 1e-12 * scale);

  // Power: nodal F . v equals the flow side's F . v(p) with v interpolated linearly.
  Eigen::Matrix2Xd velocity(2, n);
  for (int i = 0; i < n; ++i) velocity.col(i) << g(rng), g(rng);
  double power_flow = 0.0, power_scale = 0.0;
  for (const auto& q : samples) {
    const auto& seg = segments[static_cast<std::size_t>(q.segment)];
    const Eigen::Vector2d v = (1.0 - q.xi) * velocity.col(seg[0]) + q.xi * velocity.col(seg[1]);
    power_flow += q.force.dot(v);
    power_scale += q.force.norm() * v.norm();
  }
  EXPECT_LT(std::abs(interface_power(loads, velocity) - power_flow), 1e-12 * power_scale);
}

TEST(InterfaceTransfer, ThreeDimensionalLoadsKeepForceAndMoment) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g;
  // A curved plate: a 9 x 6 grid of nodes, two triangles per cell.
  const int nx = 9, ny = 6, n = nx * ny;
  Eigen::Matrix3Xd nodes(3, n);
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i)
      nodes.col(j * nx + i) << 0.1 * i, 0.08 * j, 0.05 * std::sin(0.7 * i) * std::cos(0.5 * j);
  std::vector<std::array<int, 3>> triangles;
  for (int j = 0; j + 1 < ny; ++j)
    for (int i = 0; i + 1 < nx; ++i) {
      const int a = j * nx + i;
      triangles.push_back({a, a + 1, a + nx + 1});
      triangles.push_back({a, a + nx + 1, a + nx});
    }
  const WetSurface3D surface(n, triangles);
  std::vector<WetSurface3D::Sample> samples(2000);
  for (auto& q : samples) {
    q.triangle = static_cast<int>(u(rng) * static_cast<double>(triangles.size())) %
                 static_cast<int>(triangles.size());
    double a = u(rng), b = u(rng);
    if (a + b > 1.0) {  // fold into the triangle: uniform barycentric sampling
      a = 1.0 - a;
      b = 1.0 - b;
    }
    q.local << a, b;
    q.force << g(rng), g(rng), g(rng);
  }
  const Eigen::Matrix3Xd loads = surface.nodal_loads(samples);
  const Eigen::Vector3d c(-0.3, 0.9, 0.4);
  Eigen::Vector3d force_flow = Eigen::Vector3d::Zero(), moment_flow = Eigen::Vector3d::Zero();
  double scale = 0.0;
  for (const auto& q : samples) {
    const Eigen::Vector3d arm = surface.point(q, nodes) - c;
    force_flow += q.force;
    moment_flow += arm.cross(q.force);
    scale += q.force.norm() * (arm.norm() + 1.0);
  }
  Eigen::Vector3d moment_nodes = Eigen::Vector3d::Zero();
  for (int i = 0; i < n; ++i) moment_nodes += (nodes.col(i) - c).cross(loads.col(i));
  const double df = (loads.rowwise().sum() - force_flow).norm();
  const double dm = (moment_nodes - moment_flow).norm();
  std::printf("[ transfer ] 3-D, %zu samples: |dF| / scale = %.1e, |dM| / scale = %.1e\n",
              samples.size(), df / scale, dm / scale);
  EXPECT_LT(df, 1e-12 * scale);
  EXPECT_LT(dm, 1e-12 * scale);
  // An interior vertex only takes load from its own triangles: a sample at a node's corner
  // puts all its force there.
  WetSurface3D::Sample corner{5, Eigen::Vector2d(1.0, 0.0), Eigen::Vector3d(1, 2, 3)};
  const Eigen::Matrix3Xd one = surface.nodal_loads({corner});
  EXPECT_EQ(one.col(triangles[5][1]), Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(one.cwiseAbs().sum(), 6.0);
}

TEST(InterfaceTransfer, MotionMapAndBadInput) {
  // Flow vertices are a permutation of a subset of the structure's nodes.
  const MotionMap map(5, {4, 0, 2});
  Eigen::MatrixXd node_values(3, 5);
  for (int i = 0; i < 5; ++i) node_values.col(i) << i, 10 * i, 100 * i;
  const Eigen::MatrixXd v = map.to_vertices(node_values);
  ASSERT_EQ(v.cols(), 3);
  EXPECT_EQ(v.col(0), node_values.col(4));
  EXPECT_EQ(v.col(2), node_values.col(2));
  // to_nodes is the transpose: <to_vertices(u), f> = <u, to_nodes(f)> (the power is kept).
  const Eigen::MatrixXd f = Eigen::MatrixXd::Random(3, 3);
  EXPECT_NEAR(interface_power(f, v), interface_power(map.to_nodes(f), node_values), 1e-12);
  EXPECT_NEAR(map.to_nodes(f).sum(), f.sum(), 1e-14);

  EXPECT_THROW(MotionMap(5, {0, 5}), Error);   // out of range
  EXPECT_THROW(MotionMap(5, {-1}), Error);
  EXPECT_THROW(MotionMap(5, {}), Error);
  EXPECT_THROW((void)map.to_vertices(Eigen::MatrixXd::Zero(3, 4)), Error);
  EXPECT_THROW((void)map.to_nodes(Eigen::MatrixXd::Zero(3, 5)), Error);
  EXPECT_THROW((void)interface_power(Eigen::MatrixXd::Zero(3, 2), Eigen::MatrixXd::Zero(2, 3)), Error);

  EXPECT_THROW(WetSurface2D(3, {{0, 3}}), Error);  // node out of range
  EXPECT_THROW(WetSurface2D(3, {{1, 1}}), Error);  // degenerate segment
  EXPECT_THROW(WetSurface2D(3, {}), Error);
  EXPECT_THROW(WetSurface3D(4, {{0, 1, 4}}), Error);
  const WetSurface2D line(3, {{0, 1}, {1, 2}});
  EXPECT_THROW((void)line.nodal_loads({{2, 0.5, Eigen::Vector2d(1, 0)}}), Error);   // no segment 2
  EXPECT_THROW((void)line.nodal_loads({{0, 1.5, Eigen::Vector2d(1, 0)}}), Error);   // xi > 1
  EXPECT_THROW((void)line.nodal_loads({{0, 0.5, Eigen::Vector2d(NAN, 0)}}), Error);
  EXPECT_THROW((void)line.point({0, 0.5, Eigen::Vector2d::Zero()}, Eigen::Matrix2Xd::Zero(2, 2)), Error);
  const WetSurface3D tri(3, {{0, 1, 2}});
  EXPECT_THROW((void)tri.nodal_loads({{0, Eigen::Vector2d(0.7, 0.6), Eigen::Vector3d::Zero()}}), Error);
  EXPECT_THROW((void)tri.nodal_loads({{0, Eigen::Vector2d(-0.1, 0.2), Eigen::Vector3d::Zero()}}), Error);
  try {
    (void)line.nodal_loads({{0, 1.5, Eigen::Vector2d(1, 0)}});
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("expected local coordinates in [0, 1]"), std::string::npos);
  }
}

}  // namespace
}  // namespace finverse::fsi
