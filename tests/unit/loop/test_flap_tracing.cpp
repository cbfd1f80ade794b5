// The Hessenthaler flap as a traced model (loop/flap_traced_model.hpp, loop/flap_loop.hpp) and the
// flap variants it runs (fem/validation/hessenthaler_flap.hpp): a curved rest shape without load
// sits at its arc, a load profile equal to the uniform load is the uniform load, softening and
// cupping move the tip the way they must; one datum makes every candidate score alike and the loop
// refuses to add, flagged; a twin with two data closes exactly with any candidate (coarse meshes).
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "core/summary.hpp"
#include "fem/errors.hpp"
#include "fem/validation/hessenthaler_flap.hpp"
#include "loop/effect_tracing.hpp"
#include "loop/flap_loop.hpp"
#include "loop/flap_traced_model.hpp"

using namespace finverse;
namespace fv = fem::validation;

namespace {
const fv::FlapMesh kShell{fv::FlapModel::shell, 8, 1};
}

TEST(FlapVariant, CurvedRestShapeWithoutLoadSitsOnItsArc) {
  const fv::HessenthalerFlap flap;
  fv::FlapShape shape;
  shape.rest_curvature = 5.0;
  const double k = shape.rest_curvature, L = flap.length;
  for (const auto& mesh : {fv::FlapMesh{fv::FlapModel::beam, 8, 1}, kShell}) {
    const auto d = fv::flap_deflection(flap, 2e5, mesh, fv::FlapLoad{}, shape, 1);
    EXPECT_NEAR(d.tip, (1 - std::cos(k * L)) / k, 1e-9);
    EXPECT_NEAR(d.tip_axial, std::sin(k * L) / k - L, 1e-9);
  }
}

TEST(FlapVariant, ProfileEqualToUniformLoadIsTheUniformLoad) {
  const fv::HessenthalerFlap flap;
  const double q = flap.buoyancy_per_length();
  const auto uniform = fv::flap_deflection(flap, 2e5, kShell, q);
  const auto profile = fv::flap_deflection(flap, 2e5, kShell, fv::FlapLoad{0, std::vector<double>(4, q), {}, {}}, {});
  EXPECT_NEAR(profile.tip, uniform.tip, 1e-9);
  // An axial pull along +x straightens the bent flap.
  const auto pulled = fv::flap_deflection(flap, 2e5, kShell, fv::FlapLoad{q, {}, std::vector<double>(4, 2 * q), {}}, {});
  EXPECT_LT(pulled.tip, uniform.tip);
}

TEST(FlapVariant, SofteningBendsMoreAndCuppingStiffens) {
  const fv::HessenthalerFlap flap;
  const double q = flap.buoyancy_per_length();
  const double plain = fv::flap_deflection(flap, 2e5, kShell, q).tip;
  fv::FlapShape soft;
  soft.distal_softening = 0.5;
  EXPECT_GT(fv::flap_deflection(flap, 2e5, kShell, fv::FlapLoad{q, {}, {}, {}}, soft).tip, plain);
  fv::FlapShape cup;
  cup.rest_cupping = 40;
  const fv::FlapMesh across{fv::FlapModel::shell, 8, 4};
  EXPECT_LT(fv::flap_deflection(flap, 2e5, across, fv::FlapLoad{q, {}, {}, {}}, cup).tip,
            fv::flap_deflection(flap, 2e5, across, q).tip);
  EXPECT_THROW(fv::flap_deflection(flap, 2e5, {fv::FlapModel::beam, 8, 1}, fv::FlapLoad{q, {}, {}, {}}, cup),
               fem::InvalidInput);
}

TEST(FlapTracing, OneDatumTiesEveryCandidateAndAddsNothing) {
  loop::FlapTraceSetup setup;
  setup.mesh = kShell;
  setup.youngs_modulus = 2.8e5;  // stiffer than the data: a residual to explain
  setup.refit_modulus = false;
  setup.candidates = {"density_error", "precurved_rest_shape", "modulus_offset"};
  setup.frames = {{"no_flow", 0.0295, {}, {}, {}, {}}};
  const loop::FlapTracedModel model(setup);
  loop::TraceOptions o;
  o.refit_base = false;
  const auto r = loop::trace_effects(model, o);
  ASSERT_EQ(r.steps.size(), 1u);
  const auto& scores = r.steps.front().scores;
  ASSERT_EQ(scores.size(), 3u);
  // Each candidate's sensitivity lies on the one measured row: each explains all of r, LM = m.
  for (const auto& c : scores) EXPECT_NEAR(c.score.statistic, scores.front().score.statistic, 1e-6);
  EXPECT_TRUE(r.added.empty());
}

TEST(FlapTracing, FlapLoopRefusesAndFlagsWithoutPlane) {
  const auto dir = std::filesystem::temp_directory_path() / "finverse_flap_loop_test";
  std::filesystem::create_directories(dir);
  Summary fit("validation", "fit", "stub of fin-fit flap");
  fit.info("youngs_modulus", 1.83e5, "Pa");
  fit.at_most("phase_I_prediction_missing", 1.0, 0.0, "3-D Phase I not run");
  fit.write(dir / "fit.json");
  loop::FlapLoopOptions o;
  o.reference = FINVERSE_HESSENTHALER_REFERENCE;
  o.fit_summary = dir / "fit.json";
  o.mesh = kShell;
  o.lm_evaluations = 12;
  const Summary s = loop::run_flap_loop(o);
  bool flagged = false, carried = false;
  for (const auto& m : s.metrics()) {
    if (m.name == "loop_uniaxial_identifiable" || m.name == "loop_fitted_identifiable") {
      EXPECT_EQ(m.value, 0.0) << m.name;
      flagged = true;
    }
    if (m.name == "loop_uniaxial_effects_added") {
      EXPECT_EQ(m.value, 0.0);
    }
    if (m.name == "phase_I_prediction_missing") carried = true;
  }
  EXPECT_TRUE(flagged);
  EXPECT_TRUE(carried);
  EXPECT_FALSE(s.pass());  // the 3-D prediction is still missing
  std::filesystem::remove_all(dir);
}
