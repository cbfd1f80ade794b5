// Motion sources for the virtual experiment (DESIGN.md sections 1 and 5.5). A MotionSource moves
// the truth fin surface; fin-synth renders whatever source it is given and writes the same
// truth.h5, so a FEM- or FSI-driven source with hidden effects can replace the prescribed model
// below without touching the renderer or the files.
//
// PrescribedKinematics is the reconstructed trout motion of the seed paper, section 4.4:
//   - root heave y_root = h0 sin(2 pi f t), h0 = 0.44 c a HALF amplitude (root peak to peak 0.88 c),
//   - root pitch theta of every ray about the dorsal axis z, amplitude U-shaped across the rays
//     (edge rays pitch most) and phase W-shaped across the rays (Fig. 12(c)),
//   - a chordwise bending wave travelling root to tip and a spanwise (cupping) bending mode,
// at St = f A / U = 0.44 with A the trailing edge's peak-to-peak excursion (nominally 1.0 c),
// Re = U c / nu = 1000 (section 4.2; U and f from core/flow_scales.hpp).
// Sign convention: theta > 0 and w > 0 move the trailing edge towards +y. The pitch LAGS the heave
// (phase -90 deg +- 20 deg) and the bending lags it too, so the trailing edge trails the root's
// lateral motion: a feathering, thrust-producing stroke. With the former leading phases (+90, and
// bending -60/-30) the trailing edge led the root by 25-56 deg, the angle of attack reached
// 64-81 deg and the fin made net drag (docs/studies/fin_kinematics_and_force_size.md).
// Fin rays are nearly inextensible (section 4.1: bony segmented rays), so the bending is not a
// lateral offset added to the rest shape, which would stretch every bent ray: the two bending
// modes define a lateral deflection w(s) whose slope sets the local bending angle
// alpha = atan(dw/dl), and every line of vertices (each ray, and the membrane lines between them)
// is rebuilt by rotating each rest segment out of the fin plane by alpha. Arc length along every
// line is then kept to round-off, and the tip deflection stays close to w (to O(slope^2)).
#pragma once

#include <memory>
#include <string>

#include <nlohmann/json.hpp>

#include "core/flow_scales.hpp"
#include "core/nd_array.hpp"
#include "vision/fin_surface.hpp"

namespace finverse::vision {

class MotionSource {
 public:
  virtual ~MotionSource() = default;
  virtual std::string name() const = 0;
  virtual double period() const = 0;  // s
  // Vertex positions [nv,3] (metres) of the surface at time t (s).
  virtual NdArray<double> positions(const FinSurface& surface, double t) const = 0;
  // Parameters that define the motion (stored in truth.h5's provenance config).
  virtual nlohmann::json parameters() const = 0;
  // Extra physical effects in the truth (truth.h5 'effects'); none for a prescribed motion.
  virtual nlohmann::json effects() const { return nlohmann::json::object(); }
};

struct KinematicParams {
  double chord_m = 0.01;
  double reynolds = 1000;
  double strouhal = 0.44;
  double kinematic_viscosity = kWaterKinematicViscosity;  // m^2/s
  double heave_over_chord = 0.44;         // root heave HALF amplitude h0 / c (peak to peak 2 h0)
  // Nominal trailing-edge peak-to-peak excursion A / c that St = f A / U refers to. It only sets
  // the frequency; the motion's own TE excursion is 0.97-1.20 c across the rays (the paper's
  // Fig. 14 points: 0.90-1.10 c, mean 1.02 c).
  double excursion_over_chord = 1.0;
  double pitch_center_deg = 12;           // root pitch amplitude of the middle ray ("U": smallest)
  double pitch_edge_deg = 22;             // ... of the edge rays (largest)
  double pitch_phase_deg = -90;           // mean phase of root pitch relative to heave (< 0: lags)
  double pitch_phase_w_deg = -20;         // half swing of the W across the rays (a W in phase lag)
  double chordwise_over_chord = 0.08;     // tip amplitude of the chordwise bending wave
  double chordwise_wavelength = 1.6;      // in ray lengths
  double chordwise_phase_deg = 150;       // relative to heave; at the tip 150 - 225 = -75 (lags)
  double spanwise_over_chord = 0.04;      // amplitude of the spanwise cupping mode at the tips
  double spanwise_phase_deg = 30;         // relative to heave; sign reversed with the others (study's "rev")
};

class PrescribedKinematics final : public MotionSource {
 public:
  explicit PrescribedKinematics(const KinematicParams& p);
  std::string name() const override { return "prescribed_kinematics"; }
  double period() const override { return 1.0 / frequency_; }  // 1 / f (truth.h5's T; see flapping_period)
  double frequency() const { return frequency_; }
  double speed() const { return speed_; }  // free-stream U, m/s
  NdArray<double> positions(const FinSurface& surface, double t) const override;
  nlohmann::json parameters() const override;

  // Root pitch amplitude (rad) and phase (rad, relative to the heave; < 0 lags) of the ray line at
  // eta (+1 dorsal, -1 ventral).
  double pitch_amplitude(double eta) const;
  double pitch_phase(double eta) const;
  // Prescribed lateral deflection w (m) of the bending modes at arc-length fraction s on the line
  // eta, in the ray's pitched frame, and its derivative dw/ds; wt = 2 pi f t.
  double bending_deflection(double eta, double s, double wt) const;
  double bending_slope(double eta, double s, double wt) const;

 private:
  KinematicParams p_;
  double speed_, frequency_;
};

}  // namespace finverse::vision
