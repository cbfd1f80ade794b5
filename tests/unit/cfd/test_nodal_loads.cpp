// Tests of the surface-to-mid-surface load mapping (cfd/nodal_loads.hpp): the total is conserved,
// a uniform pressure on the closed rest body gives no net force, the pressure jump recovers the
// two sides' pressures with the documented sign.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "cfd/io/fin_input.hpp"
#include "cfd/validation/thin_plate_case.hpp"
#include "cfd/forces/nodal_loads.hpp"

namespace finverse::cfd {
namespace {

struct Plate {
  io::FinInput in;
  SurfaceState rest;
};

Plate plate() {
  const auto f = io::make_thin_plate({});
  Plate p{io::make_fin_input(f.mesh, f.motion, "mesh.h5", "motion.h5"), {}};
  p.rest = place_thin_body(p.in.motion->body(), p.in.rest, {}, {}, p.in.mid_triangles);
  return p;
}

Vec3 area_vector(const TriangulatedSurface& s, std::size_t t) {
  const auto& tri = s.triangles[t];
  const Vec3 &a = s.points[tri[0]], &b = s.points[tri[1]], &c = s.points[tri[2]];
  const Vec3 e1{b[0] - a[0], b[1] - a[1], b[2] - a[2]}, e2{c[0] - a[0], c[1] - a[1], c[2] - a[2]};
  return {0.5 * (e1[1] * e2[2] - e1[2] * e2[1]), 0.5 * (e1[2] * e2[0] - e1[0] * e2[2]), 0.5 * (e1[0] * e2[1] - e1[1] * e2[0])};
}

TEST(NodalLoads, ConservesTheTotalForce) {
  const Plate p = plate();
  const ThinBody& b = p.in.motion->body();
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  SurfaceForces f;
  for (std::size_t t = 0; t < b.triangles.size(); ++t) {
    f.pressure.push_back({u(rng), u(rng), u(rng)});
    f.viscous.push_back({0.1 * u(rng), 0.1 * u(rng), 0.1 * u(rng)});
  }
  const auto nodal = nodal_forces(b, f);
  ASSERT_EQ(nodal.size(), p.in.rest.size());
  const Vec3 total = triangle_force_sum(f);
  Vec3 sum{};
  double scale = 0;
  for (const auto& q : nodal)
    for (int d = 0; d < 3; ++d) sum[d] += q[d], scale += std::abs(q[d]);
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(sum[d], total[d], 1e-13 * scale);
}

TEST(NodalLoads, UniformPressureOnTheClosedBodyHasNoNetForce) {
  const Plate p = plate();
  const ThinBody& b = p.in.motion->body();
  const double pressure = 1234.5;
  SurfaceForces f;
  double scale = 0;
  for (std::size_t t = 0; t < b.triangles.size(); ++t) {
    const Vec3 a = area_vector(p.rest.surface, t);
    f.pressure.push_back({-pressure * a[0], -pressure * a[1], -pressure * a[2]});
    f.viscous.push_back({0, 0, 0});
    scale += pressure * std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
  }
  const auto nodal = nodal_forces(b, f);
  Vec3 sum{};
  for (const auto& q : nodal)
    for (int d = 0; d < 3; ++d) sum[d] += q[d];
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(sum[d], 0.0, 1e-14 * scale);
  // Same pressure on both sides: no jump anywhere.
  const auto jump = pressure_jump(b, p.in.mid_triangles, p.rest.surface, f);
  for (double j : jump) EXPECT_NEAR(j, 0.0, 1e-9 * pressure);
}

// Pressures p+ on the offset_sign +1 face, p- on the -1 face, rim anything: the jump is
// p_back - p_front, and jump * area * (right-hand normal) summed over the shell triangles is the
// net pressure force of the two faces.
TEST(NodalLoads, PressureJumpHasTheDocumentedSign) {
  const Plate p = plate();
  const ThinBody& b = p.in.motion->body();
  const double p_plus = 300, p_minus = -50;
  SurfaceForces f;
  Vec3 faces{};
  for (std::size_t t = 0; t < b.triangles.size(); ++t) {
    const auto& tri = b.triangles[t];
    const int s = b.offset_sign[tri[0]] == b.offset_sign[tri[1]] && b.offset_sign[tri[1]] == b.offset_sign[tri[2]]
                      ? b.offset_sign[tri[0]]
                      : 0;
    const double q = s > 0 ? p_plus : s < 0 ? p_minus : 77.0;
    const Vec3 a = area_vector(p.rest.surface, t);
    f.pressure.push_back({-q * a[0], -q * a[1], -q * a[2]});
    f.viscous.push_back({0, 0, 0});
    if (s != 0)
      for (int d = 0; d < 3; ++d) faces[d] += f.pressure.back()[d];
  }
  const auto jump = pressure_jump(b, p.in.mid_triangles, p.rest.surface, f);
  // fin-mesh convention (normal_sign -1): the -1 side is the front.
  ASSERT_EQ(b.normal_sign, -1);
  Vec3 net{};
  TriangulatedSurface mid{p.in.rest, p.in.mid_triangles};
  for (std::size_t e = 0; e < jump.size(); ++e) {
    EXPECT_NEAR(jump[e], p_plus - p_minus, 1e-9 * p_plus);
    const Vec3 a = area_vector(mid, e);
    for (int d = 0; d < 3; ++d) net[d] += jump[e] * a[d];
  }
  for (int d = 0; d < 3; ++d) EXPECT_NEAR(net[d], faces[d], 1e-9 * std::abs(faces[1]));
  EXPECT_GT(std::abs(faces[1]), 0.0);
  // A shell triangle with no facing surface triangle (the other diagonal of the first cell, nodes
  // 0, 1 and 9 of the 9-node rows) falls back to the nodes' area-weighted side pressures.
  const auto other = pressure_jump(b, {{0, 1, 9}}, p.rest.surface, f);
  ASSERT_EQ(other.size(), 1u);
  EXPECT_NEAR(other[0], p_plus - p_minus, 1e-9 * p_plus);
}

TEST(NodalLoads, RejectsForcesOfAnotherSurface) {
  const Plate p = plate();
  SurfaceForces f;
  f.pressure.resize(3);
  f.viscous.resize(3);
  EXPECT_THROW(nodal_forces(p.in.motion->body(), f), Error);
}

}  // namespace
}  // namespace finverse::cfd
