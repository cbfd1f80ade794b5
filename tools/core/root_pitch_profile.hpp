// The root pitch of each fin ray across the fin (seed paper section 4.4, Fig. 12(c)): the pitch
// theta(eta, t) = Theta(eta) sin(2 pi f t + phi(eta)) about the dorsal axis z, with eta the ray's
// place across the fin (+1 dorsal edge, -1 ventral edge, linear in the ray index). The amplitude
// is U-shaped (edge rays pitch most) and the phase W-shaped (cos(2 pi eta): +1 at both edges and
// the middle, -1 at the quarter spans). One definition for the prescribed kinematics of fin-synth
// (vision/kinematic_model.cpp) and the FEM root drive (fem/root_drive.hpp). Header only, so that
// the dependency-light finverse_fem can use it without linking finverse_core.
#pragma once

#include <cmath>
#include <numbers>

namespace finverse {

struct RootPitchProfile {
  double center_deg = 12;   // amplitude of the middle ray (the U's bottom)
  double edge_deg = 22;     // amplitude of the edge rays
  double phase_deg = -90;   // mean phase relative to the heave (< 0: the pitch lags)
  double phase_w_deg = -20; // half swing of the W across the rays
  static constexpr double kDeg = std::numbers::pi / 180.0;

  // Amplitude Theta(eta) [rad].
  [[nodiscard]] double amplitude(double eta) const {
    return (center_deg + (edge_deg - center_deg) * eta * eta) * kDeg;
  }
  // Phase phi(eta) [rad] relative to the heave.
  [[nodiscard]] double phase(double eta) const {
    return (phase_deg + phase_w_deg * std::cos(2 * std::numbers::pi * eta)) * kDeg;
  }
  // theta(eta) at wt = 2 pi f t.
  [[nodiscard]] double pitch(double eta, double wt) const { return amplitude(eta) * std::sin(wt + phase(eta)); }
};

}  // namespace finverse
