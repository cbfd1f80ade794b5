// The plane version of the Hessenthaler (2017) Phase I flow (fsi/validation/hessenthaler_plane_fsi
// .hpp) on a coarse grid for a few steps: its plane-strain strip's static buoyancy deflection
// against the corotational beam with the plane-strain modulus E / (1 - nu^2), the tip lifted by the
// buoyancy (and not yet far) after the first steps, and a missing modulus refused.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "core/error.hpp"
#include "fem/validation/hessenthaler_flap.hpp"
#include "fsi/validation/hessenthaler_plane_fsi.hpp"

using namespace finverse;

namespace {
double metric(const Summary& s, const std::string& name) {
  for (const auto& m : s.metrics())
    if (m.name == name) return m.value;
  ADD_FAILURE() << "no metric " << name;
  return NAN;
}
}  // namespace

TEST(HessenthalerPlane, FewCoarseSteps) {
  fsi::validation::HessenthalerPlaneOptions o;
  o.reference = FINVERSE_HESSENTHALER_REFERENCE;
  o.youngs_modulus = 1.83e5;
  o.h = 1e-3;
  o.t_end = 0.004;  // 6 steps
  const Summary s = fsi::validation::run_hessenthaler_plane_fsi(o);
  const auto flap = fem::validation::read_hessenthaler_flap(o.reference);
  const double nu = flap.poisson_ratio;
  const double beam = fem::validation::flap_buoyancy_deflection(flap, o.youngs_modulus / (1 - nu * nu),
                                                                {fem::validation::FlapModel::beam, 32, 1})
                          .tip;
  EXPECT_NEAR(metric(s, "plane_strain_static_tip_no_flow") / beam, 1.0, 0.02);
  const double tip = metric(s, "phase_I_plane_tip_final");
  EXPECT_GT(tip, 0.0);
  EXPECT_LT(tip, 1e-3);
}

TEST(HessenthalerPlane, MissingModulusIsRefused) {
  fsi::validation::HessenthalerPlaneOptions o;
  o.reference = FINVERSE_HESSENTHALER_REFERENCE;
  EXPECT_THROW(fsi::validation::run_hessenthaler_plane_fsi(o), Error);
}
