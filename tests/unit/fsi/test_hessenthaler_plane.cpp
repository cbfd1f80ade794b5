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
  // The recorded mean flow load (fin-loop flap's Phase I load): one value per station, summing to
  // the metric's net force.
  const nlohmann::json j = s.to_json();
  const auto& load = j.at("parameters").at("mean_flow_load_last_fifth");
  ASSERT_EQ(load["transverse_N_m2"].size(), static_cast<std::size_t>(o.load_bins));
  ASSERT_EQ(load["station_edges_m"].size(), static_cast<std::size_t>(o.load_bins + 1));
  double net = 0;
  for (const auto& q : load["transverse_N_m2"]) net += q.get<double>() * flap.length / o.load_bins;
  EXPECT_NEAR(net, metric(s, "phase_I_plane_mean_flow_force_transverse"), 1e-12 + 1e-9 * std::abs(net));
}

TEST(HessenthalerPlane, MissingModulusIsRefused) {
  fsi::validation::HessenthalerPlaneOptions o;
  o.reference = FINVERSE_HESSENTHALER_REFERENCE;
  EXPECT_THROW(fsi::validation::run_hessenthaler_plane_fsi(o), Error);
}
