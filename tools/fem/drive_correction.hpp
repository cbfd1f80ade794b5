// A harmonic correction of a prescribed root drive (issue 45, deliverable 1): when the root
// motion is read off a reconstruction, each ray root's pitch comes from the tracked rays'
// tangents and carries their bending next to the root; the correction lets a fit estimate the
// drive with the moduli instead of holding that error. On top of the prescriptions already on
// the model's root nodes (root_motion.hpp, root_drive.hpp) it adds, at the beat frequency f,
//   pitch  dtheta(eta, t) = rho(t) sum_k P_k(eta) (a_k sin wt + b_k cos wt)   about the root line,
//   heave  dh(t)          = rho(t) (c sin wt + d cos wt)                      along the plane normal,
// w = 2 pi f, P_k the Legendre polynomials of the root node's place eta in [-1, 1] along the
// root line (a smooth low-order family over the rays), rho(t) the root motion's ramp from rest.
// The pitch is added to the rotation vector (exact for rotations about the root line, as the
// drive's; first order in the off-axis part). Sine and cosine parts keep the family linear in its
// coefficients, so a zero amplitude is an interior point with no phase to wrap.
#pragma once

#include <vector>

#include "fem/model.hpp"

namespace finverse::fem {

struct DriveCorrection {
  double frequency = 0;           // f [Hz], > 0
  double first_time = 0;          // t0: the root motion's first sample [s]
  double ramp = 0;                // rho rises linearly over [t0 - ramp, t0] (load_history.hpp)
  std::vector<double> pitch_sin;  // a_k [rad], k = 0.. (order = size)
  std::vector<double> pitch_cos;  // b_k [rad], the same size
  double heave_sin = 0, heave_cos = 0;  // c, d [m]

  [[nodiscard]] bool is_zero() const;
  // rho(t) [-] and the two corrections at a root node's eta.
  [[nodiscard]] double ramp_factor(double t) const;
  [[nodiscard]] double pitch(double eta, double t) const;
  [[nodiscard]] double heave(double t) const;

  // Adds the correction to the prescriptions of every root node (all 6 DOFs; an unprescribed DOF
  // counts as held at zero). The pitch axis is the root nodes' line, oriented along +z where it
  // has a z component; eta runs from -1 to +1 between its extreme root nodes; the heave direction
  // is the normal of the plane through the model's reference positions, oriented along +y.
  // Throws InvalidInput for fewer than two distinct root nodes, f <= 0 or a non-finite value.
  void apply(Model& model, const std::vector<int>& root_nodes) const;
};

// P_k(x), k >= 0 (Bonnet's recursion).
double legendre(int k, double x);

}  // namespace finverse::fem
