// Motion transfer onto mesh nodes (fin-mesh's motion.h5): a rigid motion of the source surface is
// carried exactly, the binding reports how far nodes are from the source, and node velocities
// are second-order accurate.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "mesh/motion_transfer.hpp"
#include "mesh/planform_mesher.hpp"
#include "mesh/structural_mesh.hpp"

using namespace finverse;
using namespace finverse::mesh;

namespace {

NdArray<std::int32_t> triangles_of(const PlanformMesh& m) {
  NdArray<std::int32_t> t({m.triangles.size(), 3});
  for (std::size_t i = 0; i < m.triangles.size(); ++i)
    for (int k = 0; k < 3; ++k) t(i, k) = m.triangles[i][k];
  return t;
}

// Rotation about an oblique axis by angle a, then a translation: a rigid motion per frame.
std::array<double, 3> rigid(const std::array<double, 3>& p, double a, double shift) {
  const double ux = 0.36, uy = 0.48, uz = 0.8;  // unit axis
  const double c = std::cos(a), s = std::sin(a), d = ux * p[0] + uy * p[1] + uz * p[2];
  const double cx = uy * p[2] - uz * p[1], cy = uz * p[0] - ux * p[2], cz = ux * p[1] - uy * p[0];
  return {p[0] * c + cx * s + ux * d * (1 - c) + shift, p[1] * c + cy * s + uy * d * (1 - c) - 0.5 * shift,
          p[2] * c + cz * s + uz * d * (1 - c) + 0.25 * shift};
}

}  // namespace

TEST(MotionTransfer, RigidMotionIsCarriedExactly) {
  const auto fin = make_caudal_fin({});
  PlanformMeshOptions coarse;
  coarse.max_edge_over_chord = 0.1;
  const auto src = mesh_planform(fin, coarse);  // the source surface: another triangulation
  const auto dst = mesh_planform(fin, {});
  const auto src_rest = rest_points(src), dst_rest = rest_points(dst);
  const auto binding = bind_to_surface(src_rest, triangles_of(src), dst_rest);
  EXPECT_LT(binding.max_distance, 1e-15);
  for (const auto& w : binding.weights) {
    EXPECT_NEAR(w[0] + w[1] + w[2], 1.0, 1e-14);
    for (double x : w) EXPECT_GE(x, -1e-14);
  }
  const std::size_t nf = 7, nv = src.points.size(), n = dst.points.size();
  NdArray<double> frames({nf, nv, 3});
  for (std::size_t k = 0; k < nf; ++k)
    for (std::size_t i = 0; i < nv; ++i) {
      const auto q = rigid({src_rest(i, 0), src_rest(i, 1), src_rest(i, 2)}, 0.3 * k, 0.002 * k);
      for (int d = 0; d < 3; ++d) frames(k, i, d) = q[d];
    }
  const auto moved = carry_motion(binding, frames);
  ASSERT_EQ(moved.shape, (std::vector<std::size_t>{nf, n, 3}));
  double worst = 0;
  for (std::size_t k = 0; k < nf; ++k)
    for (std::size_t i = 0; i < n; ++i) {
      const auto q = rigid({dst_rest(i, 0), dst_rest(i, 1), dst_rest(i, 2)}, 0.3 * k, 0.002 * k);
      for (int d = 0; d < 3; ++d) worst = std::max(worst, std::abs(moved(k, i, d) - q[d]));
    }
  EXPECT_LT(worst, 1e-16 * 100);  // metres, on a 1 cm fin: rounding only
}

TEST(MotionTransfer, BindingMeasuresDistanceOffTheSurface) {
  NdArray<double> p({3, 3}, std::vector<double>{0, 0, 0, 1, 0, 0, 0, 0, 1});
  NdArray<std::int32_t> t({1, 3}, std::vector<std::int32_t>{0, 1, 2});
  NdArray<double> q({2, 3}, std::vector<double>{0.25, 0.5, 0.25, 2, 0, 0});
  const auto b = bind_to_surface(p, t, q);
  EXPECT_NEAR(b.weights[0][1], 0.25, 1e-15);
  EXPECT_NEAR(b.weights[0][2], 0.25, 1e-15);
  EXPECT_NEAR(b.weights[1][1], 1.0, 1e-15);  // clamped to the nearest vertex
  EXPECT_NEAR(b.max_distance, 1.0, 1e-15);
}

TEST(MotionTransfer, VelocitiesAreSecondOrder) {
  // x(t) = sin(2 pi t / T) sampled over one period: periodic and one-sided forms.
  auto error = [](std::size_t nf, bool periodic) {
    const double T = 0.2;
    std::vector<double> time(nf);
    NdArray<double> x({nf, 1, 3}, 0.0);
    for (std::size_t k = 0; k < nf; ++k) {
      time[k] = T * k / (periodic ? nf : nf - 1);
      x(k, 0, 1) = std::sin(2 * std::numbers::pi * time[k] / T);
    }
    const auto v = velocities(time, x, periodic ? std::optional<double>(T) : std::nullopt);
    double e = 0;
    for (std::size_t k = 0; k < nf; ++k)
      e = std::max(e, std::abs(v(k, 0, 1) - 2 * std::numbers::pi / T * std::cos(2 * std::numbers::pi * time[k] / T)));
    return e;
  };
  for (bool periodic : {true, false}) {
    const double e1 = error(50, periodic), e2 = error(100, periodic);
    EXPECT_GT(e1 / e2, 3.5) << (periodic ? "periodic" : "one-sided");
    EXPECT_LT(e1 / e2, 4.5) << (periodic ? "periodic" : "one-sided");
  }
  EXPECT_LT(error(100, true), 1e-3 * 2 * std::numbers::pi / 0.2);
}
