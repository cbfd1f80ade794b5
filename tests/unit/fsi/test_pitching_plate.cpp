// Tests of the 3-D coupled step (SurfaceFlowStructureStep, tools/fsi; issue 32) and the
// pitching plate built on it, on a tiny grid (L/8, a short domain, 4 x 2 shell cells):
//   - the thin body's triangle forces moved onto the mid-surface nodes keep the force and the
//     moment (about any point, the flow side applying each triangle's force at its nodes' mean) to
//     round-off, and a wrong force would show;
//   - in a coupled run the recorded transfer mismatch stays at round-off every step;
//   - a stiff plate (K = 1000: wet frequency 24 f0) follows the rigid pitching: its trailing edge within 2 % of
//     sin(alpha0) L of the rigid one at every step, and the prescribed rigid run gives exactly the
//     rigid amplitude.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "cfd/immersed/thin_body.hpp"
#include "fsi/validation/pitching_plate_fsi.hpp"
#include "fsi/surface_flow_structure_step.hpp"

namespace finverse::fsi::validation {
namespace {

PitchingPlateOptions tiny() {
  PitchingPlateOptions o;
  o.nx = 4;
  o.nz = 2;
  o.cells_per_chord = 8;
  o.upstream = 1;
  o.downstream = 1.5;
  o.half_height = 1;
  o.half_width = 1.5;
  o.box_half_height = 0.3;
  o.steps_per_period = 24;
  o.periods = 2;
  o.ramp_periods = 1;
  o.stiffness = {1000};
  return o;
}

TEST(SurfaceLoadTransfer, KeepsForceAndMomentToRoundOff) {
  // A 3 x 2 grid mid-surface, bent out of plane, with deterministic pseudo-random triangle forces.
  const int nx = 3, nz = 2, n = (nx + 1) * (nz + 1);
  std::vector<std::array<int, 3>> mid;
  for (int k = 0; k < nz; ++k)
    for (int i = 0; i < nx; ++i) {
      const int a = k * (nx + 1) + i, b = a + 1, c = a + nx + 2, d = a + nx + 1;
      mid.push_back({a, b, c});
      mid.push_back({a, c, d});
    }
  const cfd::ThinBody body = cfd::build_thin_body(mid, n, 0.1, "test plate");
  Eigen::Matrix3Xd x(3, n);
  for (int k = 0; k <= nz; ++k)
    for (int i = 0; i <= nx; ++i) x.col(k * (nx + 1) + i) = Eigen::Vector3d(i / 3.0, 0.1 * i * i / 9.0, 0.27 * k);
  cfd::SurfaceForces f;
  unsigned state = 12345;
  const auto next = [&]() {
    state = state * 1103515245u + 12345u;
    return static_cast<double>((state >> 8) % 2001) / 1000.0 - 1.0;
  };
  for (std::size_t t = 0; t < body.triangles.size(); ++t) {
    f.pressure.push_back({next(), next(), next()});
    f.viscous.push_back({0.01 * next(), 0.01 * next(), 0.01 * next()});
  }
  const Eigen::Vector3d centre(0.3, -0.2, 0.5);
  const SurfaceLoadTransfer tr = transfer_surface_loads(body, f, x, centre);
  ASSERT_GT(tr.flow_force.norm(), 0.1);
  EXPECT_LT(tr.mismatch(1.0), 1e-13);
  EXPECT_LT((tr.node_force - tr.flow_force).norm(), 1e-13 * tr.flow_force.norm());
  EXPECT_LT((tr.node_moment - tr.flow_moment).norm(), 1e-13 * tr.flow_force.norm());
  // A load lost on one node shows.
  SurfaceLoadTransfer broken = tr;
  broken.node_force -= tr.loads.col(5);
  EXPECT_GT(broken.mismatch(1.0), 1e-3);
  EXPECT_THROW(transfer_surface_loads(body, f, x.leftCols(n - 1), centre), Error);
}

TEST(PitchingPlateFsi, StiffPlateFollowsTheRigidPitching) {
  const PitchingPlateOptions o = tiny();
  const PitchingPlateCaseResult rigid = run_pitching_plate_case(o, 0, true);
  const PitchingPlateCaseResult stiff = run_pitching_plate_case(o, 1000, false);
  const double a = std::sin(12 * std::numbers::pi / 180);
  ASSERT_EQ(rigid.te_y.size(), 48u);
  ASSERT_EQ(stiff.te_y.size(), 48u);
  // The rigid kinematics: half peak-to-peak over the last period of 24 samples of -sin(alpha).
  double lo = 1, hi = -1;
  for (std::size_t k = 24; k < 48; ++k) {
    lo = std::min(lo, rigid.te_y[k]);
    hi = std::max(hi, rigid.te_y[k]);
  }
  EXPECT_DOUBLE_EQ(rigid.amplitude, (hi - lo) / 2);
  EXPECT_NEAR(rigid.phase_deg, 0.0, 1e-9);
  double worst = 0;
  for (std::size_t k = 0; k < 48; ++k) worst = std::max(worst, std::abs(stiff.te_y[k] - rigid.te_y[k]));
  EXPECT_LT(worst, 0.02 * a);
  EXPECT_NEAR(stiff.amplitude / rigid.amplitude, 1.0, 0.02);
  EXPECT_LT(stiff.transfer_mismatch, 1e-12);
  EXPECT_LT(rigid.transfer_mismatch, 1e-12);
  EXPECT_GE(stiff.coupling_iterations_mean, 1.0);
  // The flow pushed on the plate (a lift that follows the pitch).
  EXPECT_GT(stiff.lift_amplitude, 0.1);
}

TEST(PitchingPlateFsi, StiffPlateAsASheetFollowsTheRigidPitching) {
  // The same with the zero-thickness sheet (docs/studies/thin_surface.md): the coupled step
  // places the sheet and hands the markers' forces to the nodes, force and moment kept.
  PitchingPlateOptions o = tiny();
  o.surface = "sheet";
  const PitchingPlateCaseResult rigid = run_pitching_plate_case(o, 0, true);
  const PitchingPlateCaseResult stiff = run_pitching_plate_case(o, 1000, false);
  ASSERT_EQ(stiff.te_y.size(), 48u);
  double worst = 0;
  for (std::size_t k = 0; k < 48; ++k) worst = std::max(worst, std::abs(stiff.te_y[k] - rigid.te_y[k]));
  EXPECT_LT(worst, 0.02 * std::sin(12 * std::numbers::pi / 180));
  EXPECT_LT(stiff.transfer_mismatch, 1e-12);
  EXPECT_LT(rigid.transfer_mismatch, 1e-12);
  EXPECT_GT(stiff.lift_amplitude, 0.1);
}

TEST(PitchingPlateFsi, RejectsBadOptions) {
  PitchingPlateOptions o = tiny();
  o.nz = 3;
  EXPECT_THROW(run_pitching_plate_case(o, 1, false), Error);
  o = tiny();
  o.periods = 1;
  EXPECT_THROW(run_pitching_plate_case(o, 1, false), Error);
  o = tiny();
  o.stiffness = {-1};
  EXPECT_THROW(run_pitching_plate(o), Error);
}

}  // namespace
}  // namespace finverse::fsi::validation
