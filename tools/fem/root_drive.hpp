// The fin's analytic root drive (seed paper section 4.4, Fig. 12): every root node heaves
// y = h0 sin(2 pi f t), and each ray's root pitches about the dorsal axis z by
// theta_r(t) = Theta(eta_r) sin(2 pi f t + phi(eta_r)) with the U-shaped amplitude and W-shaped
// phase of core/root_pitch_profile.hpp (eta_r: +1 dorsal edge ray .. -1 ventral, linear in the
// ray's rank). A root node between two ray roots (membrane) takes the pitch interpolated linearly
// between them by its place along the root line (root_motion.hpp RootLine); beyond the edge rays
// the edge ray's. Each root node turns about z through itself, so its displacement is the heave
// alone. Smooth start: the whole motion times r(t) = (1 - cos(pi t / t_ramp)) / 2 for
// t < t_ramp (r = 1 after, and always when t_ramp = 0), so the fin starts at rest.
#pragma once

#include <vector>

#include "core/root_pitch_profile.hpp"
#include "fem/model.hpp"
#include "fem/root_motion.hpp"

namespace finverse::fem {

struct RayRoot {
  int root_index = 0;  // index into the root node list
  double eta = 0;      // +1 dorsal edge .. -1 ventral edge
};

class RootDrive {
 public:
  // nodes, reference: the root nodes and their rest positions; rays: the ray roots among them
  // (at least one); heave: h0 [m]; frequency: f [Hz]; ramp: t_ramp [s]. Throws InvalidInput.
  RootDrive(std::vector<int> nodes, std::vector<Vec3> reference, std::vector<RayRoot> rays, double heave,
            double frequency, double ramp, RootPitchProfile pitch);

  [[nodiscard]] double ramp_factor(double t) const;
  [[nodiscard]] double heave(double t) const;           // y of every root node [m]
  [[nodiscard]] double ray_pitch(std::size_t ray, double t) const;  // theta_r(t) [rad], ramp included
  [[nodiscard]] double pitch(int root_index, double t) const;       // theta of a root node [rad]
  [[nodiscard]] Vec3 displacement(int, double t) const { return {0, heave(t), 0}; }
  [[nodiscard]] Vec3 rotation_vector(int root_index, double t) const { return {0, 0, pitch(root_index, t)}; }
  // A node at rest X of a rigid fin carried by the drive (turned about z through its foot on the
  // root line by the pitch there, then heaved): the envelope the flow grid must hold.
  [[nodiscard]] Vec3 rigid_position(const Vec3& X, double t) const;

  // Prescribes all 6 DOFs of every root node (replacing earlier prescriptions).
  void apply(Model& model) const;

  [[nodiscard]] const std::vector<int>& nodes() const { return nodes_; }
  [[nodiscard]] const std::vector<RayRoot>& rays() const { return rays_; }
  [[nodiscard]] double frequency() const { return frequency_; }

 private:
  [[nodiscard]] double pitch_at(const RootLine::Weights& w, double t) const;

  std::vector<int> nodes_;
  std::vector<Vec3> reference_;
  std::vector<RayRoot> rays_;
  double heave_, frequency_, ramp_;
  RootPitchProfile profile_;
  RootLine line_;
  std::vector<double> ray_coordinate_;
  std::vector<RootLine::Weights> node_weights_;  // per root node, over rays_
};

}  // namespace finverse::fem
