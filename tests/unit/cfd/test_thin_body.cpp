// Tests of the closed thin body (core/thin_body.hpp), its placement around a deforming mid-surface
// (cfd/immersed/thin_body.hpp) and its motion (cfd/immersed/fin_surface_motion.hpp): fin-mesh's /ibm
// reproduced, watertightness, the normals' analytic time derivatives against finite differences.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cfd/immersed/fin_surface_motion.hpp"
#include "cfd/io/fin_input.hpp"
#include "cfd/validation/thin_plate_case.hpp"
#include "cfd/immersed/thin_body.hpp"
#include "core/error.hpp"
#include "core/stage_files.hpp"

namespace finverse::cfd {
namespace {

std::vector<std::array<int, 3>> triangles_of(const NdArray<std::int32_t>& t) {
  std::vector<std::array<int, 3>> out(t.dim(0));
  for (std::size_t i = 0; i < out.size(); ++i)
    for (std::size_t k = 0; k < 3; ++k) out[i][k] = t(i, k);
  return out;
}
std::vector<Vec3> points_of(const NdArray<double>& p) {
  std::vector<Vec3> out(p.dim(0));
  for (std::size_t i = 0; i < out.size(); ++i)
    for (std::size_t d = 0; d < 3; ++d) out[i][d] = p(i, d);
  return out;
}

// fin-mesh's output (the golden coarse fin): the construction gives the golden /ibm connectivity,
// sources and signs, and the placement along the computed vertex normals gives /ibm/points.
TEST(ThinBody, ReproducesFinMeshIbmSurface) {
  const auto mesh = stage::read<stage::Mesh>(FINVERSE_COARSE_FIN_MESH);
  ASSERT_TRUE(mesh.ibm_thickness.has_value());
  const auto mid = triangles_of(mesh.triangles);
  const int nv = static_cast<int>(mesh.points.dim(0));
  const ThinBody b = build_thin_body(mid, nv, *mesh.ibm_thickness);
  ASSERT_EQ(b.triangles, triangles_of(mesh.ibm_triangles));
  ASSERT_EQ(b.source_node, std::vector<int>(mesh.ibm_source_node.data.begin(), mesh.ibm_source_node.data.end()));
  ASSERT_EQ(b.offset_sign, std::vector<int>(mesh.ibm_offset_sign.data.begin(), mesh.ibm_offset_sign.data.end()));
  const SurfaceState s = place_thin_body(b, points_of(mesh.points), {}, {}, mid);
  const auto ibm = points_of(mesh.ibm_points);
  double worst = 0;
  for (std::size_t i = 0; i < ibm.size(); ++i)
    for (int d = 0; d < 3; ++d) worst = std::max(worst, std::abs(s.surface.points[i][d] - ibm[i][d]));
  EXPECT_LE(worst, 1e-15 * *mesh.chord);
  // The reader derives the same side convention from the data and finds the same placement.
  double mismatch = 1;
  const ThinBody r = io::thin_body_from_mesh(mesh, "mesh.h5", &mismatch);
  EXPECT_EQ(r.normal_sign, -1);
  EXPECT_DOUBLE_EQ(r.thickness, *mesh.ibm_thickness);
  EXPECT_LE(mismatch, 1e-15 * *mesh.chord);
  EXPECT_NO_THROW(check_watertight(r.triangles, static_cast<int>(ibm.size()), "ibm"));
}

double enclosed_volume(const TriangulatedSurface& s) {
  double v = 0;
  for (const auto& t : s.triangles) {
    const Vec3 &a = s.points[t[0]], &b = s.points[t[1]], &c = s.points[t[2]];
    v += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) + a[2] * (b[0] * c[1] - b[1] * c[0])) / 6;
  }
  return v;
}

TEST(ThinBody, PlateBodyIsClosedAndOutward) {
  const auto f = io::make_thin_plate({});
  const auto ibm = points_of(f.mesh.ibm_points);
  const auto tri = triangles_of(f.mesh.ibm_triangles);
  EXPECT_NO_THROW(check_watertight(tri, static_cast<int>(ibm.size()), "plate"));
  const TriangulatedSurface s{ibm, tri};
  const io::ThinPlateSetup d;
  EXPECT_NEAR(enclosed_volume(s), d.chord * d.span * d.thickness, 1e-12 * d.chord * d.span * d.thickness);
}

TEST(ThinBody, WatertightCheckRejectsOpenAndMisorientedSurfaces) {
  auto tri = triangles_of(io::make_thin_plate({}).mesh.ibm_triangles);
  const int n = static_cast<int>(io::make_thin_plate({}).mesh.ibm_points.dim(0));
  auto open = tri;
  open.pop_back();
  EXPECT_THROW(check_watertight(open, n, "open"), Error);
  auto flipped = tri;
  std::swap(flipped[0][1], flipped[0][2]);
  EXPECT_THROW(check_watertight(flipped, n, "flipped"), Error);
  auto bad = tri;
  bad[3][0] = n;
  EXPECT_THROW(check_watertight(bad, n, "index"), Error);
}

// A smoothly bending, stretching mid-surface x(t): the analytic dn/dt, d2n/dt2 and the placed
// vertex velocity/acceleration agree with central differences of the placement.
TEST(ThinBody, NormalDerivativesMatchFiniteDifferences) {
  const auto f = io::make_thin_plate({});
  const auto rest = points_of(f.mesh.points);
  const auto mid = triangles_of(f.mesh.triangles);
  const ThinBody body = build_thin_body(mid, static_cast<int>(rest.size()), 0.001);
  auto at = [&](double t, int order) {
    std::vector<Vec3> x(rest.size());
    for (std::size_t i = 0; i < rest.size(); ++i) {
      const double X = rest[i][0] / 0.01, Z = rest[i][2] / 0.015;
      // y = 0.003 sin(3t) X^2 Z + 0.001 cos(2t) Z^2 ; x stretched by (1 + 0.1 sin t).
      const double s3 = std::sin(3 * t), c3 = std::cos(3 * t), c2 = std::cos(2 * t), s2 = std::sin(2 * t);
      if (order == 0)
        x[i] = {rest[i][0] * (1 + 0.1 * std::sin(t)), 0.003 * s3 * X * X * Z + 0.001 * c2 * Z * Z, rest[i][2]};
      else if (order == 1)
        x[i] = {rest[i][0] * 0.1 * std::cos(t), 0.009 * c3 * X * X * Z - 0.002 * s2 * Z * Z, 0};
      else
        x[i] = {-rest[i][0] * 0.1 * std::sin(t), -0.027 * s3 * X * X * Z - 0.004 * c2 * Z * Z, 0};
    }
    return x;
  };
  const double t = 0.7, h = 1e-4;
  const SurfaceState s = place_thin_body(body, at(t, 0), at(t, 1), at(t, 2), mid);
  const SurfaceState sp = place_thin_body(body, at(t + h, 0), {}, {}, mid);
  const SurfaceState sm = place_thin_body(body, at(t - h, 0), {}, {}, mid);
  double ev = 0, ea = 0, vmax = 0, amax = 0;
  for (std::size_t i = 0; i < s.surface.points.size(); ++i)
    for (int d = 0; d < 3; ++d) {
      const double fv = (sp.surface.points[i][d] - sm.surface.points[i][d]) / (2 * h);
      const double fa = (sp.surface.points[i][d] - 2 * s.surface.points[i][d] + sm.surface.points[i][d]) / (h * h);
      ev = std::max(ev, std::abs(fv - s.velocity[i][d]));
      ea = std::max(ea, std::abs(fa - s.acceleration[i][d]));
      vmax = std::max(vmax, std::abs(s.velocity[i][d]));
      amax = std::max(amax, std::abs(s.acceleration[i][d]));
    }
  EXPECT_LE(ev, 1e-7 * vmax);
  EXPECT_LE(ea, 1e-4 * amax);  // FD round-off ~ eps |x| / h^2
  EXPECT_GT(amax, 1e-3);
}

// Rigid motion: the placed body is the rigidly moved /ibm/points (normals rotate with the plate).
TEST(FinSurfaceMotion, RigidPlateMovesItsRestSurfaceRigidly) {
  io::ThinPlateSetup d;
  const auto f = io::make_thin_plate(d);
  const auto in = io::make_fin_input(f.mesh, f.motion, "plate/mesh.h5", "plate/motion.h5");
  ASSERT_TRUE(in.layout.wrap.has_value());
  const auto ibm = points_of(f.mesh.ibm_points);
  for (std::size_t k : {0, 7, 23}) {
    const double t = f.motion.time(k);
    const SurfaceState s = in.motion->state(t);
    const double th = d.pitch * std::sin(2 * std::numbers::pi * t / d.period + d.phase);
    const double y = d.heave * std::sin(2 * std::numbers::pi * t / d.period);
    double worst = 0;
    for (std::size_t i = 0; i < ibm.size(); ++i) {
      const double rx = ibm[i][0] - d.pivot, ry = ibm[i][1];
      const Vec3 e{d.pivot + rx * std::cos(th) - ry * std::sin(th), y + rx * std::sin(th) + ry * std::cos(th), ibm[i][2]};
      for (int q = 0; q < 3; ++q) worst = std::max(worst, std::abs(s.surface.points[i][q] - e[q]));
    }
    EXPECT_LE(worst, 1e-15 * 10 * d.chord) << "frame " << k;
  }
}

}  // namespace
}  // namespace finverse::cfd
