// The Hessenthaler (2017) Phase I run in 3-D (fsi/validation/hessenthaler_phase1_fsi.hpp): the MRI
// centreline file (fem/validation/hessenthaler_flap.hpp) and the centreline RMS, and two iterates on a coarse junction whose first held
// shape is the structure's own no-flow buoyancy deflection, carried into the flow's frame (clamp
// at the origin, the flap along +z, its buoyancy along +y).
#include <cmath>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "../scratch_dir.hpp"
#include "core/error.hpp"
#include "core/hdf5_file.hpp"
#include "fem/validation/hessenthaler_flap.hpp"
#include "fsi/validation/hessenthaler_phase1_fsi.hpp"

using namespace finverse;

namespace {

double phase1_metric(const Summary& s, const std::string& name) {
  for (const auto& m : s.metrics())
    if (m.name == name) return m.value;
  ADD_FAILURE() << "no metric " << name;
  return NAN;
}

TEST(HessenthalerPhaseI, TheMriCentrelineHas59PointsFromTheClampToTheTip) {
  const auto c = fem::validation::read_mri_centreline(FINVERSE_HESSENTHALER_CENTRELINE);
  ASSERT_EQ(c.size(), 59u);
  EXPECT_NEAR(c.front()[0], 0.977e-3, 1e-12);
  EXPECT_NEAR(c.front()[1], 0.0, 1e-12);
  EXPECT_NEAR(c.back()[0], 62.528e-3, 1e-12);
  EXPECT_NEAR(c.back()[1], 16.4105e-3, 1e-12);
}

TEST(HessenthalerPhaseI, CentrelineRmsIsTheOffsetAlongY) {
  const std::vector<std::array<double, 2>> measured{{0.001, 0.0}, {0.02, 0.003}, {0.05, 0.012}, {0.06, 0.015}};
  std::vector<std::array<double, 2>> sim{{0.0, 0.0}, {0.03, 0.006}, {0.065, 0.016}};
  // y linear in z on each leg of sim: the offsets at the measured z, by hand.
  const double d[4] = {0.0002 - 0.0, 0.004 - 0.003, (0.006 + 0.01 * 20 / 35.0) - 0.012,
                       (0.006 + 0.01 * 30 / 35.0) - 0.015};
  double sum = 0;
  for (double e : d) sum += e * e;
  EXPECT_NEAR(fsi::validation::centreline_rms(sim, measured), std::sqrt(sum / 4), 1e-15);
  // A centreline 1 mm off along y everywhere is 1 mm off; beyond the tip's z the tip counts.
  const std::vector<std::array<double, 2>> on{{0.01, 0.002}, {0.03, 0.006}, {0.07, 0.016}};
  for (auto& p : sim) p[1] += 0.001;
  EXPECT_NEAR(fsi::validation::centreline_rms(sim, on), 0.001, 1e-15);
}

TEST(HessenthalerPhaseI, ABadCentrelineFileNamesItsLine) {
  finverse::test::ScratchDir dir;
  std::ofstream(dir / "c.csv") << "# comment\nx_mm,y_mm,z_mm\n0,1,2\n0,one,3\n";
  try {
    fem::validation::read_mri_centreline(dir / "c.csv");
    ADD_FAILURE() << "a bad row was read";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("c.csv:4:"), std::string::npos) << e.what();
  }
}

TEST(HessenthalerPhaseI, TwoCoarseIteratesStartFromTheBuoyancyShape) {
  fsi::validation::HessenthalerPhaseIOptions o;
  o.flow_case = FINVERSE_HESSENTHALER_JUNCTION;
  o.reference = FINVERSE_HESSENTHALER_REFERENCE;
  o.centreline = FINVERSE_HESSENTHALER_CENTRELINE;
  o.youngs_modulus = 1.83e5;
  o.h = 4e-3;
  o.mesh = {fem::validation::FlapModel::shell, 8, 2};
  o.develop_time = 0.04;
  o.settle_time = 0.01;
  o.window_time = 0.02;
  o.move_time = 0.02;  // the move between the two evaluations in a few steps
  o.move_speed = 1.0;
  o.max_iterations = 2;
  finverse::test::ScratchDir dir;
  o.loads_file = dir / "flap_loads.h5";
  Summary s = fsi::validation::run_hessenthaler_phase1(o);
  const auto flap = fem::validation::read_hessenthaler_flap(o.reference);
  const double buoyancy = fem::validation::flap_buoyancy_deflection(flap, o.youngs_modulus, o.mesh).tip;
  const auto& first = s.parameters().at("iterates").at(0);
  EXPECT_NEAR(first.at("tip_held_m").get<double>(), buoyancy, 1e-9);
  EXPECT_EQ(phase1_metric(s, "iterations"), 2);
  EXPECT_EQ(phase1_metric(s, "steady_state_reached"), 0);
  EXPECT_GT(phase1_metric(s, "flow_steps"), 10);
  EXPECT_EQ(s.parameters().at("centreline_zy_m").size(), 9u);
  // The loads file holds both evaluations, 3 per node of the 8 x 2 strip, the first at the held tip.
  auto f = h5::File::open_read(o.loads_file);
  EXPECT_EQ(f.attr_string(".", "schema").value_or(""), "finverse/flap-loads");
  const auto tips = f.read_f64("tip_held");
  ASSERT_EQ(tips.size(), 2u);
  EXPECT_NEAR(tips(0), buoyancy, 1e-9);
  EXPECT_EQ(f.read_f64("nodal_load").shape, (std::vector<std::size_t>{2, 3 * 9 * 3}));
}

}  // namespace
