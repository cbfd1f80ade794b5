// The flap's centreline frames (issue 49, deliverable 4: loop/flap_flow_load.hpp,
// loop/flap_traced_model.hpp): the 3-D load read back as the line through the evaluations near the
// root, bad load files named; a twin on its own centreline leaves no residual; in a load that
// falls as the tip rises the flap settles where load and shape agree; a density error, which
// enters the no-flow shape only through q / E, lies in span(E) and the central score says so,
// while a planted rest curvature is found; the published zero-flow fit is sampled as written.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include "../scratch_dir.hpp"
#include "core/hdf5_file.hpp"
#include "fem/validation/hessenthaler_flap.hpp"
#include "loop/effect_tracing.hpp"
#include "loop/errors.hpp"
#include "loop/flap_flow_load.hpp"
#include "loop/flap_traced_model.hpp"

using namespace finverse;
namespace fv = fem::validation;

namespace {

const fv::FlapMesh kStrip{fv::FlapModel::shell, 8, 1};
constexpr std::size_t kColumns = 3 * 9 * 2;  // 3 per node of the 8 x 1 strip

void write_loads(const std::filesystem::path& path, const std::vector<double>& tips, double root,
                 const std::function<double(double, std::size_t)>& load, const std::string& schema,
                 std::size_t columns = kColumns) {
  auto f = h5::File::create(path);
  f.set_attr(".", "schema", schema);
  f.set_attr(".", "tip_at_root_m", root);
  f.set_attr(".", "flap_along", std::int64_t{8});
  f.set_attr(".", "flap_across", std::int64_t{1});
  std::vector<double> v;
  for (double t : tips)
    for (std::size_t c = 0; c < columns; ++c) v.push_back(load(t, c));
  f.write("tip_held", NdArray<double>({tips.size()}, tips));
  f.write("nodal_load", NdArray<double>({tips.size(), columns}, v));
  f.commit();
}

double a_of(std::size_t c) { return 1e-5 * std::sin(0.3 * static_cast<double>(c)); }
double b_of(std::size_t c) { return -2e-3 * std::cos(0.7 * static_cast<double>(c)); }

TEST(FlapFlowLoad, IsTheLineThroughTheEvaluationsNearTheRoot) {
  test::ScratchDir dir;
  const double root = 0.0165;
  // Three evaluations within 4 mm lie on one line; the far one (the search's start) does not.
  write_loads(dir / "l.h5", {0.0295, 0.016, 0.0172, 0.0155}, root,
              [&](double t, std::size_t c) { return t > 0.025 ? 1.0 : a_of(c) + (t - root) * b_of(c); },
              "finverse/flap-loads");
  const auto f = loop::read_flap_flow_load(dir / "l.h5");
  EXPECT_EQ(f.evaluations_used, 3);
  ASSERT_EQ(f.load0.size(), static_cast<Eigen::Index>(kColumns));
  for (std::size_t c = 0; c < kColumns; ++c) {
    EXPECT_NEAR(f.load0(static_cast<Eigen::Index>(c)), a_of(c), 1e-15);
    EXPECT_NEAR(f.slope(static_cast<Eigen::Index>(c)), b_of(c), 1e-12);
  }
}

TEST(FlapFlowLoad, ABadFileIsNamed) {
  test::ScratchDir dir;
  const auto zero = [](double, std::size_t) { return 0.0; };
  write_loads(dir / "schema.h5", {0.01, 0.02}, 0.015, zero, "finverse/other");
  write_loads(dir / "columns.h5", {0.01, 0.02}, 0.015, zero, "finverse/flap-loads", kColumns - 3);
  write_loads(dir / "one.h5", {0.01}, 0.015, zero, "finverse/flap-loads");
  for (const char* name : {"schema.h5", "columns.h5", "one.h5", "missing.h5"}) {
    try {
      loop::read_flap_flow_load(dir / name);
      ADD_FAILURE() << name << " was read";
    } catch (const loop::InvalidInput& e) {
      EXPECT_NE(std::string(e.what()).find(name), std::string::npos) << e.what();
    }
  }
}

// The strip's deflected centreline at E, sampled at its own stations (z, y).
std::vector<std::array<double, 2>> centreline_of(const fv::FlapDeflection& d) {
  std::vector<std::array<double, 2>> c;
  for (std::size_t i = 1; i < d.centreline.size(); ++i)
    c.push_back({d.centreline[i][0], d.centreline[i][1] - d.centreline[0][1]});
  return c;
}

TEST(FlapCentreline, ATwinOnItsOwnCentrelineLeavesNoResidual) {
  const fv::HessenthalerFlap flap;
  const auto d = fv::flap_deflection(flap, 2e5, kStrip, flap.buoyancy_per_length());
  loop::FlapTraceSetup setup;
  setup.mesh = kStrip;
  setup.youngs_modulus = 2e5;
  setup.refit_modulus = false;
  setup.frames = {{"no_flow", d.tip, {}, {}, centreline_of(d), {}}};
  const loop::FlapTracedModel model(setup);
  const Eigen::VectorXd r = model.residuals({}, Eigen::VectorXd(0));
  EXPECT_EQ(r.size(), 3 * 8);
  EXPECT_LT(r.cwiseAbs().maxCoeff(), 1e-12);
  setup.youngs_modulus = 2.2e5;  // stiffer: every point below its measurement
  const Eigen::VectorXd stiff = loop::FlapTracedModel(setup).residuals({}, Eigen::VectorXd(0));
  for (int i = 0; i < 8; ++i) EXPECT_LT(stiff(3 * i + 2), 0) << i;
}

TEST(FlapCentreline, InAFallingLoadTheFlapSettlesWhereLoadAndShapeAgree) {
  const fv::HessenthalerFlap flap;
  const double E = 2e5, free_tip = fv::flap_deflection(flap, E, kStrip, flap.buoyancy_per_length()).tip;
  // The tip row pulled along the buoyancy by 2e-4 N at the free tip, less 0.05 N per metre the tip
  // rises.
  loop::FlapFlowLoad load;
  load.tip0 = free_tip;
  load.along = 8;
  load.across = 1;
  load.load0 = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(kColumns));
  load.slope = load.load0;
  const fv::FlapShellModel shell = fv::flap_shell_model(flap, E, kStrip);
  for (const auto& [node, w] : shell.rows.back())
    load.load0(3 * node + 2) = 2e-4 * w, load.slope(3 * node + 2) = -0.05 * w;
  loop::FlapTraceSetup setup;
  setup.mesh = kStrip;
  setup.youngs_modulus = E;
  setup.refit_modulus = false;
  setup.frames = {{"phase_I_3d", 0.0, {}, {}, {{0.03, 0.0}}, load}};
  const loop::FlapTracedModel model(setup);
  const double t = model.tips({}, Eigen::VectorXd(0)).front();
  // The structure under the load at t ends at t: the fixed point, not the dead load at t0.
  const Eigen::VectorXd F = load.at(t);
  const fv::FlapLoad at_t{flap.buoyancy_per_length(), {}, {}, std::vector<double>(F.data(), F.data() + F.size())};
  EXPECT_NEAR(fv::flap_deflection(flap, E, kStrip, at_t, {}).tip, t, 1e-8);
  const Eigen::VectorXd F0 = load.load0;
  const fv::FlapLoad dead{flap.buoyancy_per_length(), {}, {}, std::vector<double>(F0.data(), F0.data() + F0.size())};
  const double dead_tip = fv::flap_deflection(flap, E, kStrip, dead, {}).tip;
  EXPECT_GT(t, free_tip);      // pulled up ...
  EXPECT_LT(t, dead_tip);      // ... less than the dead load would, since the pull falls as it rises
}

TEST(FlapCentreline, APlantedRestCurvatureIsFoundAndFitted) {
  const fv::HessenthalerFlap flap;
  const fv::FlapMesh strip{fv::FlapModel::shell, 16, 1};  // 16 points: enough to be significant
  const double q = flap.buoyancy_per_length();
  fv::FlapShape bent;
  bent.rest_curvature = 3.0;
  // Training: buoyancy alone; held out: 1.5 times it (a profile of one station).
  const auto d = fv::flap_deflection(flap, 2e5, strip, fv::FlapLoad{q, {}, {}, {}}, bent);
  const auto more = fv::flap_deflection(flap, 2e5, strip, fv::FlapLoad{q, {0.5 * q}, {}, {}}, bent);
  loop::FlapTraceSetup setup;
  setup.mesh = strip;
  setup.youngs_modulus = 1.6e5;
  setup.refit_modulus = true;
  setup.candidates = {"density_error", "precurved_rest_shape"};
  setup.frames = {{"no_flow", d.tip, {}, {}, centreline_of(d), {}},
                  {"more", more.tip, {0.5 * q}, {}, centreline_of(more), {}}};
  const loop::FlapTracedModel model(setup);
  loop::TraceOptions o;
  o.max_effects = 1;
  o.in_span_tolerance = loop::FlapTracedModel::kInSpanTolerance;
  o.held_out_frames = {1};
  o.lm.central = true;
  const auto r = loop::trace_effects(model, o);
  ASSERT_FALSE(r.steps.empty());
  const auto& scores = r.steps.front().scores;
  ASSERT_EQ(scores.size(), 2u);
  EXPECT_EQ(scores[0].name, "precurved_rest_shape");
  EXPECT_GT(scores[0].score.projected_fraction, 0.05);
  ASSERT_EQ(r.added, std::vector<std::string>{"precurved_rest_shape"}) << r.stop_reason;
  EXPECT_NEAR(r.parameters(1), 3.0, 0.05);
  EXPECT_NEAR(r.parameters(0), 2e5, 2e3);
}

TEST(FlapCentreline, DensityScoresNothingOnAMisfitWhenERefits) {
  // A smooth misfit no candidate holds (a bump mid-span); E refitted. A density error enters the
  // no-flow shape only through q / E: its central difference lies in span(E), a one-sided one
  // differs by its curvature term, which a smooth misfit correlates with.
  const fv::HessenthalerFlap flap;
  const fv::FlapMesh strip{fv::FlapModel::shell, 16, 1};
  const auto d = fv::flap_deflection(flap, 2e5, strip, flap.buoyancy_per_length());
  auto measured = centreline_of(d);
  for (auto& [z, y] : measured) y += 3e-4 * std::sin(M_PI * z / flap.length);
  loop::FlapTraceSetup setup;
  setup.mesh = strip;
  setup.youngs_modulus = 2e5;
  setup.candidates = {"density_error"};
  setup.frames = {{"no_flow", d.tip, {}, {}, measured, {}}};
  const loop::FlapTracedModel model(setup);
  loop::TraceOptions o;
  o.lm.central = true;
  o.in_span_tolerance = loop::FlapTracedModel::kInSpanTolerance;
  const auto r = loop::trace_effects(model, o);
  ASSERT_FALSE(r.steps.empty());
  const auto& density = r.steps.front().scores.front().score;
  EXPECT_EQ(density.statistic, 0.0) << "projected fraction " << density.projected_fraction;
  EXPECT_TRUE(r.added.empty());
}

TEST(FlapCentreline, TheZeroFlowFitIsSampledAsPublished) {
  const auto c = fv::zero_flow_centreline(FINVERSE_HESSENTHALER_REFERENCE, 5, 0.001);
  ASSERT_EQ(c.size(), 5u);
  EXPECT_NEAR(c.front()[0], 0.001, 1e-15);
  EXPECT_NEAR(c.back()[0], 0.057643, 1e-15);
  EXPECT_NEAR(c.back()[1], 0.0295 * (-0.123 + 2.468 - 2.300 + 0.978), 1e-12);
  const double s = 0.001 / 0.057643;
  EXPECT_NEAR(c.front()[1], 0.0295 * (-0.123 * s + 2.468 * s * s - 2.3 * s * s * s + 0.978 * s * s * s * s), 1e-15);
}

}  // namespace
