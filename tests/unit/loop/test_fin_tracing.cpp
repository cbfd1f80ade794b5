// Effect tracing on a structural twin (loop/fin_traced_model.hpp): the small strip fin of the
// fin-fem tests under a growing lateral load, its target computed with its rays stiffening
// +-30 % at 2 Hz (active_stiffening, planted). Starting from the true moduli, the tracer must
// rank active stiffening first among the candidates, add it with an amplitude near 0.3, and the
// residual must fall by far more than 5x. Quasi-static runs of 6 frames on 15 nodes: about 1 s.
// The drive as parameters (issue 45, deliverable 1): a strip whose tracked root motion holds the
// root still while the truth's root pitches and heaves; the base refit with the drive's
// correction (fit/drive_parameters.hpp) recovers the drive and the modulus.
#include <cmath>
#include <cstdio>

#include <gtest/gtest.h>

#include "../strip_fin.hpp"
#include "fem/io/fin_layout.hpp"
#include "fem/io/material_spec.hpp"
#include "loop/effect_model_factory.hpp"
#include "loop/effect_tracing.hpp"
#include "loop/fin_traced_model.hpp"

namespace finverse::loop {
namespace {

namespace strip = finverse::test::strip;

// The trace on the strip twin with `planted` (null: none) in its target.
TraceResult trace_strip(const nlohmann::json& planted) {
  const auto mesh = strip::strip_mesh();
  const auto spec = fem::io::parse_material_spec(
      nlohmann::json::parse(R"({"membrane": {"E": 2e7, "nu": 0.45, "density": 1050},
                                "rays": {"E": 1e9, "nu": 0.3, "density": 1100}})"),
      "strip materials");
  fit::FinDrive drive;
  drive.loads = strip::ramp_loads(2e-3, 6, 0.5);
  drive.root_rotation = fem::RootRotation::zero;
  auto base = std::make_shared<fit::FinModelFactory>(mesh, spec, std::vector<std::string>{"E_membrane", "E_rays"},
                                                     drive, "strip mesh");
  fem::FinLayout layout = fem::io::make_fin_layout(mesh, "strip mesh");
  layout.beat_frequency = 1.0;  // the stiffening runs at twice this
  layout.start_time = base->start_time();
  layout.ramp = 0;

  fem::RunOptions run;
  run.analysis = fem::Analysis::quasi_static;
  run.start_time = base->start_time();
  std::vector<double> times;
  for (int k = 1; k < 6; ++k) times.push_back(drive.loads->time.data[k]);

  // The target: the strip with the planted effect.
  fit::TargetMotion target;
  target.source = "strip twin";
  target.times = times;
  {
    const auto model = planted.is_null() ? base->build(Eigen::Vector2d(2e7, 1e9))
                                         : EffectModelFactory(base, {planted}, layout)
                                               .build(Eigen::Vector4d(2e7, 1e9, 0.3, 0.5));
    for (const auto& f : fem::run_structural_analysis(*model, run, times)) target.positions.push_back(f.state.position);
  }

  FinTraceSetup setup;
  setup.base = base;
  setup.best = Eigen::Vector2d(2e7, 1e9);
  fit::Parameter e;
  e.name = "E_rays";
  e.unit = "Pa";
  e.lower = 1e8;
  e.upper = 1e11;
  setup.refit = fit::ParameterSpace({e});
  for (const char* name : {"active_stiffening", "distal_softening", "cupped_rest_shape", "root_curvature"})
    setup.candidates.push_back({{"name", name}});
  setup.layout = layout;
  setup.target = target;
  setup.run = run;
  setup.trailing_edge_nodes = {strip::node(strip::nx, 0), strip::node(strip::nx, 1), strip::node(strip::nx, 2)};
  const FinTracedModel model(setup);
  EXPECT_EQ(model.score_directions("active_stiffening").size(), 2u);
  EXPECT_EQ(model.score_directions("distal_softening").size(), 1u);

  TraceOptions o;
  o.held_out_frames = {1, 3};
  o.lm.threads = 1;
  o.max_effects = 1;
  return trace_effects(model, o);
}

TEST(FinTracing, PlantedActiveStiffeningIsFoundOnAStripTwin) {
  const auto result = trace_strip({{"name", "active_stiffening"}, {"amplitude", 0.3}, {"phase", 0.5}});
  ASSERT_FALSE(result.steps.empty());
  const auto& first = result.steps.front();
  EXPECT_EQ(first.scores.front().name, "active_stiffening");
  ASSERT_EQ(result.added, std::vector<std::string>{"active_stiffening"});
  EXPECT_NEAR(first.magnitude(0), 0.3, 0.03);
  EXPECT_LT(first.after.trailing_edge_rms, first.before.trailing_edge_rms / 5);
  EXPECT_NEAR(result.parameters(0), 1e9, 0.05e9);
  // The report's maps: every mesh node, NaN on the prescribed root, each tip's RMS cut with the rest.
  ASSERT_EQ(result.base.node_rms.size(), (strip::nx + 1) * (strip::nz + 1));
  for (int j = 0; j <= strip::nz; ++j) {
    EXPECT_TRUE(std::isnan(result.base.node_rms(strip::node(0, j))));
    EXPECT_LT(result.final_state.node_rms(strip::node(strip::nx, j)), result.base.node_rms(strip::node(strip::nx, j)) / 5);
  }
  for (const auto& c : first.scores) std::printf("  %-20s score %.3e  p %.2e\n", c.name.c_str(), c.score.statistic, c.score.p_value);
  std::printf("  amplitude %.4f [%.4f, %.4f], phase %.4f; trailing edge RMS %.3e -> %.3e m\n", first.magnitude(0),
              first.lower95(0), first.upper95(0), first.magnitude(1), first.before.trailing_edge_rms,
              first.after.trailing_edge_rms);
}

// The control: a target without any effect; the fit is exact, nothing is added.
TEST(FinTracing, ControlStripTwinAddsNothing) {
  const auto result = trace_strip(nullptr);
  EXPECT_TRUE(result.added.empty());
  EXPECT_FALSE(result.stop_reason.empty());
}

// The root nodes' "tracked" motion: at rest at the loads' times (the truth's drive is unseen).
stage::Motion resting_root(const stage::Loads& loads) {
  const auto mesh = strip::strip_mesh();
  const size_t nt = loads.time.data.size(), nv = mesh.points.dim(0);
  stage::Motion m;
  m.time = loads.time;
  m.points = NdArray<double>({nt, nv, 3});
  for (size_t k = 0; k < nt; ++k)
    for (size_t i = 0; i < nv; ++i)
      for (size_t d = 0; d < 3; ++d) m.points(k, i, d) = mesh.points(i, d);
  return m;
}

TEST(FinTracing, TheDriveIsRefittedWithTheModulus) {
  const auto mesh = strip::strip_mesh();
  const auto spec =
      fem::io::parse_material_spec(nlohmann::json::parse(R"({"membrane": {"E": 2e7, "nu": 0.45, "density": 1050},
                                "rays": {"E": 1e9, "nu": 0.3, "density": 1100}})"),
                                   "strip materials");
  fit::FinDrive drive;
  drive.loads = strip::ramp_loads(2e-3, 6, 0.5);
  drive.root_motion = resting_root(*drive.loads);
  drive.root_rotation = fem::RootRotation::zero;
  drive.frequency = 1.0;
  std::vector<std::string> names{"E_rays"};
  for (const auto& n : fit::drive_parameter_names(2)) names.push_back(n);
  auto base = std::make_shared<fit::FinModelFactory>(mesh, spec, names, drive, "strip mesh");
  EXPECT_FALSE(base->moduli_and_poisson_only());
  // Truth: pitch 0.1 sin + 0.04 eta sin - 0.05 cos (rad), heave 1 mm sin; E_rays 1.3e9.
  Eigen::VectorXd truth(7);
  truth << 1.3e9, 0.1, 0.04, -0.05, 0.0, 1e-3, 0.0;

  fem::RunOptions run;
  run.analysis = fem::Analysis::quasi_static;
  run.start_time = base->start_time();
  fit::TargetMotion target;
  target.source = "strip twin";
  for (int k = 1; k < 6; ++k) target.times.push_back(drive.loads->time.data[k]);
  for (const auto& f : fem::run_structural_analysis(*base->build(truth), run, target.times))
    target.positions.push_back(f.state.position);

  FinTraceSetup setup;
  setup.base = base;
  setup.best = base->default_parameters();
  setup.best(0) = 1e9;
  std::vector<fit::Parameter> refit{{"E_rays", "Pa", 1e8, 1e11, fit::Scale::log10, std::nullopt}};
  for (const auto& n : fit::drive_parameter_names(2)) refit.push_back(*fit::drive_parameter(n, mesh));
  EXPECT_EQ(refit.back().unit, "m");
  EXPECT_NEAR(refit.back().upper, 0.25 * strip::span, 1e-15);
  setup.refit = fit::ParameterSpace(refit);
  setup.layout = fem::io::make_fin_layout(mesh, "strip mesh");
  setup.layout.beat_frequency = 1.0;
  setup.target = target;
  setup.run = run;
  setup.trailing_edge_nodes = {strip::node(strip::nx, 0), strip::node(strip::nx, 1), strip::node(strip::nx, 2)};
  const FinTracedModel model(setup);
  TraceOptions o;
  o.held_out_frames = {1, 3};
  o.lm.threads = 1;
  o.max_effects = 0;
  const TraceResult result = trace_effects(model, o);
  ASSERT_EQ(result.parameters.size(), 7);
  EXPECT_NEAR(result.parameters(0), 1.3e9, 0.01e9);
  for (int i = 1; i < 5; ++i) EXPECT_NEAR(result.parameters(i), truth(i), 2e-3) << refit[i].name;
  EXPECT_NEAR(result.parameters(5), 1e-3, 2e-5);
  EXPECT_LT(result.base.trailing_edge_rms, result.base_initial.trailing_edge_rms / 100);
}

}  // namespace
}  // namespace finverse::loop
