// Prescribed caudal-fin kinematics (seed paper sections 4.2 and 4.4, Fig. 12): heave, per-ray root
// pitch with U-shaped amplitude and W-shaped phase lag across the rays, chordwise and spanwise
// bending as inextensible rotations along every ray (arc length kept; see kinematic_model.hpp).
#include "vision/kinematic_model.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <numeric>
#include <vector>

#include "core/error.hpp"
#include "core/flow_scales.hpp"
#include "core/root_pitch_profile.hpp"

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
  require(p.heave_over_chord >= 0, "heave amplitude must be >= 0");
  require(p.excursion_over_chord > 0, "trailing-edge excursion must be > 0 (it sets the frequency through St)");
  require(p.chordwise_wavelength > 0, "chordwise wavelength must be > 0");
  speed_ = free_stream_speed(p.reynolds, p.chord_m, p.kinematic_viscosity);
  // St refers to the nominal trailing-edge peak-to-peak excursion, not the root heave (flow_scales.hpp).
  frequency_ = flapping_frequency(p.strouhal, speed_, p.excursion_over_chord * p.chord_m);
}

// The U and W shapes are core/root_pitch_profile.hpp's, shared with the FEM root drive.
double PrescribedKinematics::pitch_amplitude(double eta) const {
  return RootPitchProfile{p_.pitch_center_deg, p_.pitch_edge_deg, p_.pitch_phase_deg, p_.pitch_phase_w_deg}
      .amplitude(eta);
}

double PrescribedKinematics::pitch_phase(double eta) const {
  return RootPitchProfile{p_.pitch_center_deg, p_.pitch_edge_deg, p_.pitch_phase_deg, p_.pitch_phase_w_deg}.phase(eta);
}

double PrescribedKinematics::bending_deflection(double eta, double s, double wt) const {
  const double c = p_.chord_m;
  // A chordwise wave whose amplitude grows as s^2 (clamped at the root) and a spanwise cupping
  // mode, edges against the middle.
  const double chordwise = p_.chordwise_over_chord * c * s * s *
                           std::sin(wt - 2 * std::numbers::pi * s / p_.chordwise_wavelength + p_.chordwise_phase_deg * kDeg);
  const double spanwise =
      p_.spanwise_over_chord * c * s * std::cos(std::numbers::pi * eta) * std::sin(wt + p_.spanwise_phase_deg * kDeg);
  return chordwise + spanwise;
}

double PrescribedKinematics::bending_slope(double eta, double s, double wt) const {
  const double c = p_.chord_m;
  const double k = 2 * std::numbers::pi / p_.chordwise_wavelength;
  const double phase = wt - k * s + p_.chordwise_phase_deg * kDeg;
  const double chordwise = p_.chordwise_over_chord * c * (2 * s * std::sin(phase) - s * s * k * std::cos(phase));
  const double spanwise =
      p_.spanwise_over_chord * c * std::cos(std::numbers::pi * eta) * std::sin(wt + p_.spanwise_phase_deg * kDeg);
  return chordwise + spanwise;
}

NdArray<double> PrescribedKinematics::positions(const FinSurface& f, double t) const {
  const double wt = 2 * std::numbers::pi * frequency_ * t;
  const double heave = p_.heave_over_chord * p_.chord_m * std::sin(wt);
  // Lines of vertices: the vertices that share a ray coordinate and root (one ray, or one line of
  // membrane between two rays), ordered root to tip.
  std::vector<std::size_t> order(f.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    if (f.eta[a] != f.eta[b]) return f.eta[a] > f.eta[b];
    if (f.root[a] != f.root[b]) return f.root[a] < f.root[b];
    return f.s[a] < f.s[b];
  });
  NdArray<double> out({f.size(), 3});
  for (std::size_t begin = 0; begin < order.size();) {
    std::size_t end = begin + 1;
    const std::size_t first = order[begin];
    while (end < order.size() && f.eta[order[end]] == f.eta[first] && f.root[order[end]] == f.root[first]) ++end;
    const double eta = f.eta[first];
    // Each line pitches rigidly about the dorsal axis z through its root ...
    const double theta = pitch_amplitude(eta) * std::sin(wt + pitch_phase(eta));
    const double ct = std::cos(theta), st = std::sin(theta);
    // ... after bending out of the fin plane in its own frame (x, w, z relative to the root).
    // The first vertex (the root, where w = 0) is offset by w; every following rest segment keeps
    // its length and is turned out of the plane by the bending angle at its mid-point.
    double x = f.rest(first, 0) - f.root[first][0];
    double z = f.rest(first, 2) - f.root[first][1];
    double w = bending_deflection(eta, f.s[first], wt);
    for (std::size_t j = begin; j < end; ++j) {
      const std::size_t i = order[j];
      if (j > begin) {
        const std::size_t h = order[j - 1];
        const double dx = f.rest(i, 0) - f.rest(h, 0), dz = f.rest(i, 2) - f.rest(h, 2);
        const double length = std::hypot(dx, dz), ds = f.s[i] - f.s[h];
        // dw/dl = dw/ds * ds/dl along this segment; a zero-length segment has no angle.
        const double alpha = length > 0 ? std::atan(bending_slope(eta, 0.5 * (f.s[i] + f.s[h]), wt) * ds / length) : 0.0;
        const double ca = std::cos(alpha);
        x += dx * ca;
        z += dz * ca;
        w += length * std::sin(alpha);
      }
      out(i, 0) = f.root[i][0] + x * ct - w * st;
      out(i, 1) = heave + x * st + w * ct;
      out(i, 2) = f.root[i][1] + z;
    }
    begin = end;
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
          {"excursion_over_chord", p_.excursion_over_chord},
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
