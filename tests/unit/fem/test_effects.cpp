// Candidate effects (fem/effects): each changes a cantilever ray the way its physics says --
// stiffening by +30 % divides the tip deflection by 1.3, Rayleigh damping decays a free vibration
// at its rate, an eigen-curvature kappa bends an unloaded ray by kappa L^2 / 2, distal softening
// matches the tapered-EI integral, a density factor scales the weight's deflection, the cup moves
// the distal corners -- and bad specs are refused with one line naming effect and parameter.
#include <cmath>
#include <numbers>

#include <gtest/gtest.h>

#include "../strip_fin.hpp"
#include "fem/effects/structural_effect.hpp"
#include "fem/errors.hpp"
#include "fem/generalized_alpha.hpp"
#include "fem/io/fin_layout.hpp"
#include "fem/modal.hpp"
#include "fem/static_solver.hpp"
#include "fem_test_models.hpp"

using namespace finverse::fem;
using finverse::fem::test::cantilever;

namespace {
constexpr double L = 0.4, E0 = 2e9, b = 0.01, t = 0.002;
constexpr int n = 8;
const double I = b * t * t * t / 12;
const double P = 1e-6 * E0 * I / (L * L);  // linear range

// One ray along x, clamped at node 0, bending out of plane along z (the section's thin side).
FinLayout ray_layout() {
  FinLayout l;
  for (int e = 0; e < n; ++e) l.beams.push_back({e, 1, e, e + 1, double(e) / n, double(e + 1) / n});
  l.ray_group[1] = RayGroup::middle;
  l.ray_eta[1] = 0;
  l.ray_length[1] = L;
  l.root_nodes = {0};
  l.normal = Vec3(0, 0, 1);
  l.span_axis = Vec3(0, 1, 0);
  l.chord_axis = Vec3(1, 0, 0);
  return l;
}

Model with(const nlohmann::json& spec, double density = 1000) {
  Model m = cantilever(n, L, E0, b, t, b, t, density);
  if (!spec.is_null()) make_effect(spec)->apply(m, ray_layout());
  return m;
}

// Static tip z-displacement at `time` under a tip load P (or none) and gravity g.
double tip_z(Model& m, double time = 1.0, double load = P, double g = 0) {
  if (load != 0) m.add_nodal_load(n, 2, load);
  m.set_load_factor([](double) { return 1.0; });
  m.set_gravity(Vec3(0, 0, g));
  StaticSolver solver(m, StaticOptions{.steps = 1});
  NodalState s = m.reference_state();
  solver.solve(s, time - 1.0, time);
  return s.position[n].z();
}

template <class F>
std::string error_of(F&& f) {
  try {
    f();
  } catch (const InvalidInput& e) {
    return e.what();
  }
  return "(no error)";
}
}  // namespace

TEST(Effects, CatalogueHasTheSixCandidates) {
  EXPECT_EQ(effect_names(), (std::vector<std::string>{"active_stiffening", "root_curvature", "rayleigh_damping",
                                                      "distal_softening", "density_error", "cupped_rest_shape"}));
  for (const auto& name : effect_names()) {  // defaults are null effects and round-trip
    auto e = make_effect({{"name", name}});
    EXPECT_EQ(make_effect(e->to_json())->to_json(), e->to_json());
  }
}

TEST(Effects, ActiveStiffeningBy30PercentDividesTheTipDeflectionBy1_3) {
  Model plain = with(nullptr);
  const double w0 = tip_z(plain, 0.3);
  // E(t) = E (1 + a sin(2 2 pi f t + phi)) with the sine = 1 at t = 0.3 s, and -1 a quarter beat on.
  const double f = 1.0, phi = std::numbers::pi / 2 - 4 * std::numbers::pi * f * 0.3;
  const nlohmann::json spec{{"name", "active_stiffening"}, {"amplitude", 0.3}, {"phase", phi}, {"frequency", f}};
  Model m = with(spec);
  EXPECT_NEAR(tip_z(m, 0.3) / w0, 1 / 1.3, 1e-6);
  Model later = with(spec);
  EXPECT_NEAR(tip_z(later, 0.3 + 0.25 / f) / w0, 1 / 0.7, 1e-6);
  // Another group: no ray of this layout is dorsal.
  EXPECT_NE(error_of([&] { with({{"name", "active_stiffening"}, {"amplitude", 0.3}, {"frequency", f}, {"group", "dorsal"}}); })
                .find("no ray elements"),
            std::string::npos);
}

TEST(Effects, RootCurvatureBendsAnUnloadedRayByKappaLSquaredOverTwo) {
  const double kappa = 0.02 / L;  // small: the linear result holds to ~1e-4
  Model m = with({{"name", "root_curvature"}, {"angle", kappa * L}, {"root_fraction", 1.0}, {"frequency", 0.0}});
  EXPECT_NEAR(tip_z(m, 1.0, 0.0) / (kappa * L * L / 2), 1.0, 1e-3);
  // Over the root half only: kappa on [0, L/2], straight beyond -> w = kappa (L/2)^2/2 + kappa (L/2) (L/2).
  Model half = with({{"name", "root_curvature"}, {"angle", kappa * L / 2}, {"root_fraction", 0.5}, {"frequency", 0.0}});
  EXPECT_NEAR(tip_z(half, 1.0, 0.0) / (kappa * L * L * 3 / 8), 1.0, 1e-3);
  // Periodic: kappa(t) = (angle / l) sin(2 pi f t + phi); at sin = -1 the ray bends the other way.
  Model periodic = with({{"name", "root_curvature"}, {"angle", kappa * L}, {"root_fraction", 1.0}, {"frequency", 2.0}});
  EXPECT_NEAR(tip_z(periodic, 0.375, 0.0) / (kappa * L * L / 2), -1.0, 1e-3);
}

TEST(Effects, RayleighDampingDecaysAFreeVibrationAtItsRate) {
  // Mass-proportional damping: the energy of any mode decays like exp(-a_M t).
  Model m = with({{"name", "rayleigh_damping"}, {"mass", 3.0}}, 1100);
  EXPECT_DOUBLE_EQ(m.rayleigh_mass(), 3.0);
  const ModalResult modes = modal_analysis(m, m.reference_state(), ModalOptions{.modes = 1});
  GeneralizedAlpha ga(m, DynamicOptions{.time_step = 2 * std::numbers::pi / modes.omega(0) / 100});
  DynamicState s = ga.reference_state();
  s.velocity = 1e-2 * modes.shapes.col(0);
  ga.initialize(s);
  const double e0 = ga.kinetic_energy(s) + ga.strain_energy(s);
  for (int k = 0; k < 400; ++k) ga.step(s);
  const double e1 = ga.kinetic_energy(s) + ga.strain_energy(s);
  EXPECT_NEAR(std::log(e1 / e0) / (-3.0 * s.time), 1.0, 0.03);
  EXPECT_NE(error_of([] { make_effect({{"name", "rayleigh_damping"}, {"mass", -1.0}}); }).find("mass"), std::string::npos);
}

TEST(Effects, DistalSofteningMatchesThePiecewiseEIIntegral) {
  const double k = 1.5;
  Model plain = with(nullptr);
  Model m = with({{"name", "distal_softening"}, {"rate", k}});
  // Tip load, EI piecewise constant per element (its mid-length): w = P sum int (L - s)^2 / EI_e ds.
  double w = 0;
  for (int e = 0; e < n; ++e) {
    const double s0 = L * e / n, s1 = L * (e + 1) / n, g = std::exp(-k * (e + 0.5) / n);
    w += P / (E0 * I * g) * (std::pow(L - s0, 3) - std::pow(L - s1, 3)) / 3;
  }
  EXPECT_NEAR(tip_z(m) / w, 1.0, 1e-5);
  EXPECT_GT(tip_z(m) / tip_z(plain), 2.0);  // e^{1.5 s/L} weighted towards the root: x2.4
}

TEST(Effects, DensityFactorScalesMassAndTheWeightsDeflection) {
  Model plain = with(nullptr);
  Model m = with({{"name", "density_error"}, {"factor", 2.5}, {"target", "rays"}});
  EXPECT_NEAR(m.total_mass() / plain.total_mass(), 2.5, 1e-12);
  // g small enough for the linear range (tip deflection 5e-5 L).
  EXPECT_NEAR(tip_z(m, 1.0, 0.0, -0.01) / tip_z(plain, 1.0, 0.0, -0.01), 2.5, 1e-4);
  EXPECT_NE(error_of([] { make_effect({{"name", "density_error"}, {"target", "fins"}}); }).find("target"),
            std::string::npos);
}

TEST(Effects, CuppedRestShapeBowsTheDistalCornersAndKeepsTheRoot) {
  using namespace finverse::test::strip;
  finverse::stage::Mesh mesh = strip_mesh();
  const FinLayout layout = io::make_fin_layout(mesh, "strip");
  EXPECT_EQ(layout.ray_group.at(3), RayGroup::dorsal);  // largest z
  EXPECT_EQ(layout.ray_group.at(2), RayGroup::middle);
  EXPECT_EQ(layout.ray_group.at(1), RayGroup::ventral);
  EXPECT_NEAR(layout.ray_length.at(1), chord, 1e-12);
  io::Effects effects;
  effects.push_back(make_effect({{"name", "cupped_rest_shape"}, {"depth", 0.1}}));
  const auto before = mesh.points;
  io::reshape_mesh(mesh, effects, layout);
  // Root centre at z = span/2: the corners have eta = +-1, u = chord -> 0.1 chord along the normal.
  EXPECT_NEAR(std::abs(mesh.points(node(nx, nz), 1) - before(node(nx, nz), 1)), 0.1 * chord, 1e-12);
  EXPECT_NEAR(mesh.points(node(nx, 0), 1), mesh.points(node(nx, nz), 1), 1e-12);
  EXPECT_DOUBLE_EQ(mesh.points(node(nx, 1), 1), before(node(nx, 1), 1));  // mid-line
  EXPECT_DOUBLE_EQ(mesh.points(node(0, 0), 1), before(node(0, 0), 1));    // root
}

TEST(Effects, BadSpecsAreRefusedWithOneLineNamingEffectAndParameter) {
  const std::string range = error_of([] { make_effect({{"name", "active_stiffening"}, {"amplitude", 1.2}}); });
  for (const char* part : {"active_stiffening", "amplitude", "-0.9 .. 0.9"})
    EXPECT_NE(range.find(part), std::string::npos) << range;
  EXPECT_EQ(range.find('\n'), std::string::npos);
  EXPECT_NE(error_of([] { make_effect({{"name", "stiffening"}}); }).find("unknown effect 'stiffening'"),
            std::string::npos);
  EXPECT_NE(error_of([] { make_effect({{"name", "distal_softening"}, {"k", 1}}); }).find("unknown key 'k'"),
            std::string::npos);
  EXPECT_NE(error_of([] { make_effect({{"name", "root_curvature"}, {"group", "tips"}}); }).find("group 'tips'"),
            std::string::npos);
  auto e = make_effect({{"name", "root_curvature"}});
  EXPECT_THROW(e->set_parameters({2.0, 0.0}), InvalidInput);
  EXPECT_THROW(e->set_parameters({0.1}), InvalidInput);
  // A periodic effect with no beat frequency known and none given.
  Model m = cantilever(n, L, E0, b, t, b, t);
  EXPECT_NE(error_of([&] { make_effect({{"name", "active_stiffening"}, {"amplitude", 0.1}})->apply(m, ray_layout()); })
                .find("frequency"),
            std::string::npos);
  EXPECT_NE(error_of([] { make_effects(nlohmann::json::parse(R"([{"name": "density_error", "factor": 0}])"), "case.yaml"); })
                .find("case.yaml: effect density_error: factor = 0"),
            std::string::npos);
}
