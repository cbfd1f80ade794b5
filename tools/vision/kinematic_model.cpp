// Prescribed caudal-fin kinematics (seed paper sections 4.2 and 4.4, Fig. 12): heave, per-ray root
// pitch with U-shaped amplitude and W-shaped phase across the rays, chordwise and spanwise bending.
#include "vision/kinematic_model.hpp"

#include <cmath>
#include <numbers>

#include "core/error.hpp"

namespace finverse::vision {
namespace {
constexpr double kDeg = std::numbers::pi / 180.0;
}

PrescribedKinematics::PrescribedKinematics(const KinematicParams& p) : p_(p) {
  auto require = [](bool ok, const std::string& what) {
    if (!ok) throw Error("kinematic model: " + what);
  };
  require(p.chord_m > 0 && p.reynolds > 0 && p.kinematic_viscosity > 0, "chord, Re and viscosity must be > 0");
  require(p.strouhal > 0, "St must be > 0");
  require(p.heave_over_chord > 0, "heave amplitude must be > 0 (it sets the frequency through St)");
  require(p.chordwise_wavelength > 0, "chordwise wavelength must be > 0");
  speed_ = p.reynolds * p.kinematic_viscosity / p.chord_m;                      // Re = U c / nu
  frequency_ = p.strouhal * speed_ / (2.0 * p.heave_over_chord * p.chord_m);   // St = f 2A / U
}

double PrescribedKinematics::pitch_amplitude(double eta) const {
  return (p_.pitch_center_deg + (p_.pitch_edge_deg - p_.pitch_center_deg) * eta * eta) * kDeg;
}

double PrescribedKinematics::pitch_phase(double eta) const {
  // cos(2 pi eta) is +1 at both edges and the middle, -1 at the quarter spans: a "W".
  return (p_.pitch_phase_deg + p_.pitch_phase_w_deg * std::cos(2 * std::numbers::pi * eta)) * kDeg;
}

NdArray<double> PrescribedKinematics::positions(const FinSurface& f, double t) const {
  const double c = p_.chord_m;
  const double wt = 2 * std::numbers::pi * frequency_ * t;
  const double heave = p_.heave_over_chord * c * std::sin(wt);
  NdArray<double> out({f.size(), 3});
  for (std::size_t i = 0; i < f.size(); ++i) {
    const double eta = f.eta[i], s = f.s[i];
    // Each ray line pitches rigidly about the dorsal axis through its root ...
    const double theta = pitch_amplitude(eta) * std::sin(wt + pitch_phase(eta));
    const double dx = f.rest(i, 0) - f.root[i][0];
    const double dz = f.rest(i, 2) - f.root[i][1];
    // ... and bends laterally in its pitched frame: a chordwise wave whose amplitude grows as s^2
    // (clamped at the root) and a spanwise cupping mode, edges against the middle.
    const double chordwise = p_.chordwise_over_chord * c * s * s *
                             std::sin(wt - 2 * std::numbers::pi * s / p_.chordwise_wavelength + p_.chordwise_phase_deg * kDeg);
    const double spanwise = p_.spanwise_over_chord * c * s * std::cos(std::numbers::pi * eta) *
                            std::sin(wt + p_.spanwise_phase_deg * kDeg);
    const double w = chordwise + spanwise;
    const double ct = std::cos(theta), st = std::sin(theta);
    out(i, 0) = f.root[i][0] + dx * ct - w * st;
    out(i, 1) = heave + dx * st + w * ct;
    out(i, 2) = f.root[i][1] + dz;
  }
  return out;
}

nlohmann::json PrescribedKinematics::parameters() const {
  return {{"model", name()},
          {"chord_m", p_.chord_m},
          {"reynolds", p_.reynolds},
          {"strouhal", p_.strouhal},
          {"kinematic_viscosity_m2_s", p_.kinematic_viscosity},
          {"free_stream_m_s", speed_},
          {"frequency_hz", frequency_},
          {"period_s", period()},
          {"heave_over_chord", p_.heave_over_chord},
          {"pitch_center_deg", p_.pitch_center_deg},
          {"pitch_edge_deg", p_.pitch_edge_deg},
          {"pitch_phase_deg", p_.pitch_phase_deg},
          {"pitch_phase_w_deg", p_.pitch_phase_w_deg},
          {"chordwise_over_chord", p_.chordwise_over_chord},
          {"chordwise_wavelength", p_.chordwise_wavelength},
          {"chordwise_phase_deg", p_.chordwise_phase_deg},
          {"spanwise_over_chord", p_.spanwise_over_chord},
          {"spanwise_phase_deg", p_.spanwise_phase_deg}};
}

}  // namespace finverse::vision
