// Tests of the quasi-steady loads (fem/io/quasi_steady_loads.hpp) on a 2 mm square plate held by
// two ray roots: a heaving plate feels the resistive drag 1/2 rho C_D v^2 A against its velocity
// and the added mass C_a rho c a A against its acceleration; the element pressures and the nodal
// forces agree; a mesh without triangles is refused.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "fem/errors.hpp"
#include "fem/io/quasi_steady_loads.hpp"
#include "fem/io/root_drive_file.hpp"

namespace finverse::fem::io {
namespace {

stage::Mesh square_plate() {
  // Root nodes 0 (z = +1 mm) and 1 (z = -1 mm); rays along x to nodes 2 and 3; normal +y.
  stage::Mesh m;
  m.points = NdArray<double>({4, 3}, {0, 0, 0.001, 0, 0, -0.001, 0.002, 0, 0.001, 0.002, 0, -0.001});
  m.root_nodes = NdArray<std::int32_t>({2}, {0, 1});
  m.beam_elements = NdArray<std::int32_t>({2, 2}, {0, 2, 1, 3});
  m.beam_ray = NdArray<std::int32_t>({2}, {1, 2});
  m.triangles = NdArray<std::int32_t>({2, 3}, {0, 2, 3, 0, 3, 1});
  m.chord = 0.01;
  return m;
}

RootDrive heave_only(const stage::Mesh& m, double f) {
  RootDriveSpec spec;
  spec.pitch.center_deg = spec.pitch.edge_deg = 0;
  spec.ramp_periods = 0;
  return make_root_drive(m, spec, f, 0.01, "plate");
}

TEST(QuasiSteadyLoads, DragAgainstVelocityAddedMassAgainstAcceleration) {
  const auto m = square_plate();
  const double f = 2, w = 2 * std::numbers::pi * f, h0 = 0.44 * 0.01, area = 4e-6;
  const auto drive = heave_only(m, f);
  QuasiSteadyLoadOptions drag;
  drag.speed = 0;
  drag.added_mass_coefficient = 0;
  // t = 0: y = 0, velocity +h0 w along the normal: the drag pushes back along -y.
  auto L = quasi_steady_loads(m, drive, {0.0, 0.25 / f}, drag);
  const double v = h0 * w;
  EXPECT_NEAR(L.force_total(0, 1), -0.5 * 1000 * 2.0 * v * v * area, 1e-4 * 0.5 * 1000 * 2 * v * v * area);
  EXPECT_NEAR(L.force_total(0, 0), 0, 1e-15);
  EXPECT_NEAR(L.force_total(1, 1), 0, 1e-9);  // at rest at the top of the stroke
  double summed = 0;
  for (std::size_t n = 0; n < 4; ++n) summed += L.nodal_force(0, n, 1);
  EXPECT_NEAR(summed, L.force_total(0, 1), 1e-15);
  EXPECT_NEAR((L.pressure_jump(0, 0) + L.pressure_jump(0, 1)) * area / 2, L.force_total(0, 1), 1e-15);

  QuasiSteadyLoadOptions mass;
  mass.speed = mass.drag_coefficient = 0;
  // t = T/4: top of the stroke, acceleration -h0 w^2: the added mass resists it along +y.
  L = quasi_steady_loads(m, drive, {0.25 / f}, mass);
  const double expected = mass.added_mass_coefficient * 1000 * 0.01 * h0 * w * w * area;
  EXPECT_NEAR(L.force_total(0, 1), expected, 1e-4 * expected);
  ASSERT_TRUE(L.period.has_value());
  EXPECT_NEAR(*L.period, 0.5, 1e-15);
}

TEST(QuasiSteadyLoads, RefusesAMeshWithoutTriangles) {
  auto m = square_plate();
  const auto drive = heave_only(m, 2);
  m.triangles = NdArray<std::int32_t>();
  EXPECT_THROW(quasi_steady_loads(m, drive, {0.0}, {}), InvalidInput);
}

}  // namespace
}  // namespace finverse::fem::io
