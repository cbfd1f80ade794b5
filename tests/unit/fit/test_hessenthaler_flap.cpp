// The Hessenthaler (2017) flap under buoyancy (fem/validation/hessenthaler_flap.hpp) and its
// modulus fit (fit/validation/hessenthaler_flap_fit.hpp): the small-load limit against the linear
// cantilever, the shell strip with nu = 0 against the beam, a fit that recovers the modulus a
// deflection was computed with, and a reference file with a missing key.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "fem/errors.hpp"
#include "fem/validation/hessenthaler_flap.hpp"
#include "fit/validation/hessenthaler_flap_fit.hpp"

using namespace finverse;
namespace fv = fem::validation;

TEST(HessenthalerFlap, SmallLoadMatchesLinearCantilever) {
  fv::HessenthalerFlap flap;
  flap.fluid_density = flap.solid_density + 0.01;  // w / L ~ 1e-5: linear
  const double E = 2e5, I = flap.width * std::pow(flap.thickness, 3) / 12.0;
  const double linear = flap.buoyancy_per_length() * std::pow(flap.length, 4) / (8.0 * E * I);
  const auto d = fv::flap_buoyancy_deflection(flap, E, {fv::FlapModel::beam, 16, 1}, 1);
  EXPECT_NEAR(d.tip / linear, 1.0, 2e-3);
}

TEST(HessenthalerFlap, ShellStripWithoutPoissonIsTheBeam) {
  fv::HessenthalerFlap flap;
  flap.poisson_ratio = 0.0;  // no anticlastic coupling: the strip bends with E b h^3 / 12
  const auto beam = fv::flap_buoyancy_deflection(flap, 2e5, {fv::FlapModel::beam, 16, 1});
  const auto shell = fv::flap_buoyancy_deflection(flap, 2e5, {fv::FlapModel::shell, 16, 2});
  EXPECT_GT(beam.tip, 0.3 * flap.length);  // large deflection: the nonlinear regime
  EXPECT_NEAR(shell.tip / beam.tip, 1.0, 0.01);
  EXPECT_LT(beam.tip_axial, 0.0);
  ASSERT_EQ(shell.centreline.size(), 17u);
  EXPECT_NEAR(shell.centreline.back()[1], shell.tip, 1e-12);
  EXPECT_NEAR(shell.centreline.front()[0], 0.0, 1e-12);
}

TEST(HessenthalerFlap, FitRecoversTheModulus) {
  const fv::HessenthalerFlap flap;
  const fv::FlapMesh mesh{fv::FlapModel::shell, 8, 1};
  const double E = 1.7e5;
  const double tip = fv::flap_buoyancy_deflection(flap, E, mesh).tip;
  double slope = 0;
  const double fitted = fit::validation::fit_flap_modulus(flap, mesh, tip, {}, &slope);
  EXPECT_NEAR(fitted / E, 1.0, 1e-5);
  EXPECT_LT(slope, 0.0);  // stiffer flap, smaller deflection
}

TEST(HessenthalerFlap, MissingReferenceKeyIsNamed) {
  const auto path = std::filesystem::temp_directory_path() / "finverse_flap_missing_key.json";
  std::ofstream(path) << R"({"geometry": {"flap_mm": {"width": 11, "thickness": 2}}})";
  try {
    fv::read_hessenthaler_flap(path);
    FAIL() << "no exception";
  } catch (const fem::InvalidInput& e) {
    EXPECT_NE(std::string(e.what()).find("geometry.flap_mm.length"), std::string::npos) << e.what();
  }
  std::filesystem::remove(path);
}
