// Prescribed root motion from tracked node positions (motion.h5 points at the mesh's root nodes,
// DESIGN.md section 4): displacements u_i(t) = x_i(t) - X_i of every root node, and one rotation
// R(t) shared by all root nodes (the fin base moves as a rigid body; its rays are clamped to it).
//
// Rotation choice (the tracked data carry positions only):
//   fit   R(t) is the least-squares rigid rotation of the root node set together with the
//         support points the caller adds (Kabsch: SVD of the cross-covariance of the centred
//         reference and current positions). A fin's root nodes lie on one line, the pitch axis,
//         so they alone cannot see the pitch: the support points (the rays' first nodes off
//         the root, apply_root_motion) carry it, and the clamp then turns with the tracked shape
//         next to it instead of holding it at zero pitch (a kink that left the quasi-static
//         base state singular). If all points are collinear the spin about that line is not
//         observable; then R(t) is the smallest rotation that turns the reference line into the
//         current one, i.e. that spin is taken as zero. A single point gives R = I.
//   zero  R(t) = I: the root rotations are held at the reference orientation.
// Samples are interpolated linearly in time: displacements directly, rotations through their
// rotation vectors (adequate for the small rotation change between video frames; rotations of
// more than pi between samples would be ambiguous and are rejected). Before the first sample the
// motion ramps from rest like the loads (load_history.hpp).
#pragma once

#include <string>
#include <vector>

#include "fem/model.hpp"
#include "fem/rotation.hpp"

namespace finverse::fem {

enum class RootRotation { fit, zero };
RootRotation parse_root_rotation(const std::string& name);  // "fit" | "zero", else InvalidInput

// Least-squares rotation taking the reference point set onto the current one (see above).
Mat3 fit_rigid_rotation(const std::vector<Vec3>& reference, const std::vector<Vec3>& current);

// Further points that move rigidly with the root, used only for the rotation fit: their rest
// positions and their positions per frame ([frame][point]).
struct RotationSupport {
  std::vector<Vec3> reference;
  std::vector<std::vector<Vec3>> positions;
};

class RootMotion {
 public:
  // positions[k][i]: position of root node nodes[i] at times[k]; reference[i]: its rest position.
  // Throws InvalidInput on non-finite data, inconsistent sizes or non-increasing times.
  RootMotion(std::vector<int> nodes, std::vector<Vec3> reference, std::vector<double> times,
             const std::vector<std::vector<Vec3>>& positions, RootRotation rotation, double ramp = 0,
             const RotationSupport& support = {});

  // Prescribes all 6 DOFs of every root node of the model (replacing earlier prescriptions).
  void apply(Model& model) const;

  Vec3 displacement(int root_index, double t) const;
  Vec3 rotation_vector(double t) const;
  const std::vector<int>& nodes() const { return nodes_; }

 private:
  std::vector<int> nodes_;
  std::vector<double> times_;
  std::vector<std::vector<Vec3>> displacement_;  // [frame][root node]
  std::vector<Vec3> rotation_;                   // [frame]
  double ramp_ = 0;
};

}  // namespace finverse::fem
