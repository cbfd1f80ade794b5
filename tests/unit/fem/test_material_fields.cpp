// Material fields: per-element and per-region Young's modulus against the analytic two-segment
// cantilever, the periodic modulation E(t) = E0 (1 + a sin(2 pi f t + phi)), and bad values.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "fem/errors.hpp"
#include "fem/generalized_alpha.hpp"
#include "fem/static_solver.hpp"
#include "fem_test_models.hpp"

using namespace finverse::fem;
using finverse::fem::test::cantilever;

namespace {
constexpr double L = 0.4, E0 = 2e9, b = 0.01, t = 0.002;
constexpr int n = 8;
const double I = b * t * t * t / 12;
const double P = 1e-6 * E0 * I / (L * L);  // linear range

double tip_deflection(Model& m, double time = 1.0) {
  m.add_nodal_load(n, 2, P);
  m.set_load_factor([](double) { return 1.0; });  // the static "time" then only drives E(t)
  StaticSolver solver(m, StaticOptions{.steps = 1});
  NodalState s = m.reference_state();
  solver.solve(s, time - 1.0, time);
  return s.position[n].z() - m.reference_positions()[n].z();
}

// Tip load P on a cantilever whose proximal part [0, a] has E1 and distal part [a, L] has E2:
// w = P/I [ (L^3 - (L-a)^3) / (3 E1) + (L-a)^3 / (3 E2) ].
double two_segment(double a, double E1, double E2) {
  const double d = L - a;
  return P / I * ((L * L * L - d * d * d) / (3 * E1) + d * d * d / (3 * E2));
}
}  // namespace

TEST(MaterialFields, PerElementModulusMatchesTwoSegmentBeam) {
  Model m = cantilever(n, L, E0, b, t, b, t);
  const double E2 = 0.2 * E0;  // softer distal half, as along a fin ray
  for (int e = n / 2; e < n; ++e) m.set_element_youngs_modulus(e, E2);
  EXPECT_DOUBLE_EQ(m.element_youngs_modulus(n - 1), E2);
  const double w = tip_deflection(m), ref = two_segment(L / 2, E0, E2);
  EXPECT_NEAR(w, ref, 1e-5 * ref);
  EXPECT_GT(w, 1.4 * two_segment(L / 2, E0, E0));  // the soft part matters (x1.5)
}

TEST(MaterialFields, RegionModulusEqualsPerElementAndRebuiltModel) {
  // Distal elements in their own region ("ray 2"), given its E after construction.
  Model m;
  const int r1 = m.add_material({"ray1", E0, 0.3, 1000});
  const int r2 = m.add_material({"ray2", E0, 0.3, 1000});
  for (int i = 0; i <= n; ++i) m.add_node(Vec3(L * i / n, 0, 0));
  for (int i = 0; i < n; ++i)
    m.add_beam(i, i + 1, i < n / 4 ? r1 : r2, TaperedRectangle::uniform(b, t), Vec3(0, 1, 0));
  m.fix_node(0);
  m.set_region_youngs_modulus(r2, 3 * E0);
  EXPECT_EQ(m.element_region(n - 1), r2);
  const double w = tip_deflection(m);
  EXPECT_NEAR(w, two_segment(L / 4, E0, 3 * E0), 1e-5 * w);
  // Same as building the distal elements with that modulus in the first place.
  Model direct;
  const int d = direct.add_material({"ray", E0, 0.3, 1000});
  for (int i = 0; i <= n; ++i) direct.add_node(Vec3(L * i / n, 0, 0));
  for (int i = 0; i < n; ++i)
    direct.add_beam(i, i + 1, d, TaperedRectangle::uniform(b, t), Vec3(0, 1, 0),
                    i < n / 4 ? E0 : 3 * E0);
  direct.fix_node(0);
  EXPECT_NEAR(tip_deflection(direct), w, 1e-12 * w);
}

TEST(MaterialFields, ModulationWithZeroAmplitudeIsConstantAndOtherwiseScalesE) {
  Model constant = cantilever(n, L, E0, b, t, b, t);
  const double w0 = tip_deflection(constant, 0.3);
  Model zero = cantilever(n, L, E0, b, t, b, t);
  for (int e = 0; e < n; ++e) zero.set_element_modulation(e, {0.0, 2.0, 0.4});
  EXPECT_EQ(tip_deflection(zero, 0.3), w0);
  // a = 0.5, f = 2 Hz, phi = 0.4: E(t) = E0 (1 + 0.5 sin(2 pi 2 t + 0.4)); linear range: w ~ 1/E.
  const ModulusModulation mod{0.5, 2.0, 0.4};
  for (double time : {0.0, 0.1, 0.3}) {
    Model m = cantilever(n, L, E0, b, t, b, t);
    m.set_region_modulation(0, mod);
    const double w = tip_deflection(m, time);
    EXPECT_NEAR(w, w0 / mod.factor(time), 1e-6 * std::abs(w));
  }
  // Modulation seen by the dynamics: the same time enters the strain energy.
  Model m = cantilever(n, L, E0, b, t, b, t);
  m.set_region_modulation(0, mod);
  GeneralizedAlpha ga(m, DynamicOptions{.time_step = 1e-4});
  DynamicState s = ga.reference_state(0.1);
  s.configuration.position[n].z() += 1e-4;
  Model plain = cantilever(n, L, E0, b, t, b, t);
  GeneralizedAlpha gp(plain, DynamicOptions{.time_step = 1e-4});
  DynamicState sp = s;
  EXPECT_NEAR(ga.strain_energy(s), mod.factor(0.1) * gp.strain_energy(sp), 1e-9 * gp.strain_energy(sp));
}

TEST(MaterialFields, NonPhysicalValuesAreRejected) {
  Model m = cantilever(n, L, E0, b, t, b, t);
  EXPECT_THROW(m.set_element_youngs_modulus(0, 0.0), InvalidInput);
  EXPECT_THROW(m.set_element_youngs_modulus(0, -1e9), InvalidInput);
  EXPECT_THROW(m.set_region_youngs_modulus(0, std::nan("")), InvalidInput);
  EXPECT_THROW(m.set_region_youngs_modulus(5, 1e9), InvalidInput);
  EXPECT_THROW(m.set_element_modulation(0, {1.0, 1.0, 0.0}), InvalidInput);  // E would reach 0
  EXPECT_THROW(m.set_element_modulation(0, {0.1, -1.0, 0.0}), InvalidInput);
  EXPECT_THROW(m.set_element_youngs_modulus(n, 1e9), InvalidInput);
}

TEST(MaterialFields, FieldReturnsToUniformWhenResetAndDoesNotGrow) {
  StiffnessField f;
  f.resize(3);
  EXPECT_TRUE(f.uniform());
  f.set_factor(1, 2.0);
  f.set_modulation(2, {0.3, 1.0, 0.0});
  EXPECT_FALSE(f.uniform());
  EXPECT_DOUBLE_EQ(f.scale(1, 0.7), 2.0);
  EXPECT_DOUBLE_EQ(f.scale(2, 0.25), 1.3);  // sin(pi/2)
  for (int k = 0; k < 1000; ++k) f.set_modulation(2, {0.1, 1.0, 0.0});  // a fitter's loop
  f.set_factor(1, 1.0);
  f.clear_modulation(2);
  EXPECT_TRUE(f.uniform());
}
