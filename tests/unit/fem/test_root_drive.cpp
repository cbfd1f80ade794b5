// Tests of the fin's root drives (root_drive.hpp, root_motion.hpp per_ray):
//   - the analytic drive's root rotations and heave equal the paper's formula (U-shaped amplitude,
//     W-shaped phase, core/root_pitch_profile.hpp) at the rays, interpolated between them, ramped;
//   - the per-ray fit of tracked positions recovers known, different pitches of each ray's root
//     (and the membrane root nodes between rays interpolate), where the one-rotation fit cannot.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "fem/errors.hpp"
#include "fem/root_drive.hpp"
#include "fem/root_motion.hpp"
#include "fem/rotation.hpp"

namespace finverse::fem {
namespace {

constexpr double pi = std::numbers::pi;

// Five root nodes on the z axis (dorsal first); rays at 0, 2, 4.
std::vector<Vec3> root_line() { return {{0, 0, 0.004}, {0, 0, 0.002}, {0, 0, 0}, {0, 0, -0.002}, {0, 0, -0.004}}; }

TEST(RootDrive, RotationsAndHeaveAreThePapersFormula) {
  const RootPitchProfile p{12, 22, -90, -20};
  const double f = 4, h0 = 0.0044, ramp = 0.25;
  const RootDrive d({10, 11, 12, 13, 14}, root_line(), {{0, 1.0}, {2, 0.0}, {4, -1.0}}, h0, f, ramp, p);
  for (double t : {0.3, 0.4125, 0.61}) {  // after the ramp
    const double wt = 2 * pi * f * t;
    EXPECT_NEAR(d.heave(t), h0 * std::sin(wt), 1e-15);
    for (auto [i, eta] : {std::pair{0, 1.0}, {2, 0.0}, {4, -1.0}}) {
      // Theta(eta) sin(wt + phi(eta)) with the shapes written out.
      const double amp = (12 + 10 * eta * eta) * pi / 180, phase = (-90 - 20 * std::cos(2 * pi * eta)) * pi / 180;
      EXPECT_NEAR(d.pitch(i, t), amp * std::sin(wt + phase), 1e-14) << "node " << i;
      EXPECT_NEAR(d.rotation_vector(i, t).z(), amp * std::sin(wt + phase), 1e-14);
    }
    // Edge rays pitch most (U): |Theta(1)| = 22 deg, the middle 12 deg.
    EXPECT_NEAR(p.amplitude(1.0), 22 * pi / 180, 1e-15);
    EXPECT_NEAR(p.amplitude(0.0), 12 * pi / 180, 1e-15);
    // Membrane root nodes halfway between two rays.
    EXPECT_NEAR(d.pitch(1, t), 0.5 * (d.pitch(0, t) + d.pitch(2, t)), 1e-15);
    EXPECT_NEAR(d.pitch(3, t), 0.5 * (d.pitch(2, t) + d.pitch(4, t)), 1e-15);
    // A rigid fin point one chord along x from the middle root turns about z there and heaves.
    const Vec3 q = d.rigid_position(Vec3(0.01, 0, 0), t);
    EXPECT_NEAR(q.x(), 0.01 * std::cos(d.pitch(2, t)), 1e-15);
    EXPECT_NEAR(q.y(), 0.01 * std::sin(d.pitch(2, t)) + d.heave(t), 1e-15);
  }
  // The smooth start: at rest at t = 0, half way at ramp / 2, whole after.
  EXPECT_EQ(d.heave(0.0), 0.0);
  EXPECT_NEAR(d.ramp_factor(ramp / 2), 0.5, 1e-15);
  EXPECT_EQ(d.ramp_factor(ramp), 1.0);
  // The model's prescribed DOFs follow the drive.
  Model m;
  for (int n = 0; n < 15; ++n) m.add_node(Vec3(0.001 * n, 0, 0));
  d.apply(m);
  int checked = 0;
  for (const auto& pd : m.prescribed()) {
    const int i = pd.node - 10;
    const double expected = pd.dof == 1 ? d.heave(0.3) : pd.dof == 5 ? d.pitch(i, 0.3) : 0.0;
    EXPECT_EQ(pd.at(0.3), expected) << "node " << pd.node << " dof " << pd.dof;
    checked += pd.dof == 1 || pd.dof == 5 ? 1 : 0;
  }
  EXPECT_EQ(checked, 10);
  EXPECT_THROW(RootDrive({1}, {{0, 0, 0}}, {}, h0, f, 0, p), InvalidInput);
  EXPECT_THROW(RootDrive({1}, {{0, 0, 0}}, {{0, 0}}, h0, 0, 0, p), InvalidInput);
}

TEST(RootMotion, PerRayFitRecoversEachRaysPitch) {
  // Rays leave root nodes 0, 2, 4 along x; each ray's root pitches by its own angle, the whole root
  // heaves. Support point: one element (1 mm) along each ray.
  const std::vector<Vec3> X = root_line();
  const std::vector<int> rays{0, 2, 4};
  const std::vector<double> theta{0.30, -0.05, 0.18};
  const double heave = 0.003;
  RotationSupport support;
  support.positions.resize(2);
  std::vector<Vec3> moved;
  for (const Vec3& x : X) moved.push_back(x + Vec3(0, heave, 0));
  for (std::size_t r = 0; r < rays.size(); ++r) {
    const Vec3 root = X[static_cast<std::size_t>(rays[r])], arm(0.001, 0, 0);
    support.reference.push_back(root + arm);
    support.root_index.push_back(rays[r]);
    support.positions[0].push_back(root + arm);
    support.positions[1].push_back(moved[static_cast<std::size_t>(rays[r])] + exp_so3(Vec3(0, 0, theta[r])) * arm);
  }
  const RootMotion m({0, 1, 2, 3, 4}, X, {0.0, 1.0}, {X, moved}, RootRotation::per_ray, 0, support);
  for (std::size_t r = 0; r < rays.size(); ++r)
    EXPECT_LT((m.rotation_vector(rays[r], 1.0) - Vec3(0, 0, theta[r])).norm(), 1e-12) << "ray " << r;
  EXPECT_LT((m.rotation_vector(1, 1.0) - Vec3(0, 0, 0.5 * (theta[0] + theta[1]))).norm(), 1e-12);
  EXPECT_LT((m.rotation_vector(3, 1.0) - Vec3(0, 0, 0.5 * (theta[1] + theta[2]))).norm(), 1e-12);
  EXPECT_LT((m.rotation_vector(2, 0.5) - Vec3(0, 0, 0.5 * theta[1])).norm(), 1e-12);
  EXPECT_LT((m.displacement(3, 1.0) - Vec3(0, heave, 0)).norm(), 1e-15);
  // One rotation for the whole root cannot tell the rays apart.
  const RootMotion one({0, 1, 2, 3, 4}, X, {0.0, 1.0}, {X, moved}, RootRotation::fit, 0, support);
  EXPECT_GT((one.rotation_vector(0, 1.0) - Vec3(0, 0, theta[0])).norm(), 0.1);
  // per_ray without support points is refused.
  EXPECT_THROW(RootMotion({0, 1, 2, 3, 4}, X, {0.0, 1.0}, {X, moved}, RootRotation::per_ray), InvalidInput);
  EXPECT_EQ(parse_root_rotation("per_ray"), RootRotation::per_ray);
}

}  // namespace
}  // namespace finverse::fem
