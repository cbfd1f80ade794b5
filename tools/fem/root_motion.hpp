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
//   per_ray  each ray's root node gets its own rotation (the paper's per-ray root pitch, Fig. 12):
//         R0(t) fitted to the root nodes alone (on a line: it turns the line, spin about it zero),
//         then turned by the smallest rotation that takes R0 times the ray's support direction
//         (root -> its support point) onto the tracked one: exact for a rigid root and for
//         rays that pitch differently about the root line (a rigid R0 fitted with the support
//         points would mistake those differences for a roll). Root nodes without a support
//         point (membrane between two rays) take the
//         rotation vector interpolated linearly between their neighbours along the root line
//         (held beyond the last one). Needs RotationSupport::root_index.
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

enum class RootRotation { fit, per_ray, zero };
RootRotation parse_root_rotation(const std::string& name);  // "fit" | "per_ray" | "zero", else InvalidInput

// Least-squares rotation taking the reference point set onto the current one (see above).
Mat3 fit_rigid_rotation(const std::vector<Vec3>& reference, const std::vector<Vec3>& current);

// Smallest rotation taking direction a onto direction b (I when either is zero).
Mat3 smallest_rotation(const Vec3& a, const Vec3& b);

// Further points that move rigidly with the root, used only for the rotation fit: their rest
// positions and their positions per frame ([frame][point]); root_index (per_ray only): the root
// node (index into the root node list) each point belongs to.
struct RotationSupport {
  std::vector<Vec3> reference;
  std::vector<std::vector<Vec3>> positions;
  std::vector<int> root_index{};
};

// The fin's root line (the principal direction of the root nodes' rest positions) and linear
// interpolation along it: value at s = (1 - w) value[a] + w value[b] over carriers sorted by
// their coordinate, held beyond the first and last carrier.
struct RootLine {
  Vec3 centre = Vec3::Zero(), direction = Vec3::UnitZ();
  static RootLine fit(const std::vector<Vec3>& points);
  [[nodiscard]] double coordinate(const Vec3& p) const { return (p - centre).dot(direction); }
  struct Weights {
    int a = 0, b = 0;
    double w = 0;
  };
  // carriers: their coordinates (any order, at least one); returns the weights at s.
  [[nodiscard]] static Weights weights(const std::vector<double>& carriers, double s);
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
  Vec3 rotation_vector(int root_index, double t) const;
  Vec3 rotation_vector(double t) const { return rotation_vector(0, t); }  // fit, zero: shared by all
  const std::vector<int>& nodes() const { return nodes_; }

 private:
  std::vector<int> nodes_;
  std::vector<double> times_;
  std::vector<std::vector<Vec3>> displacement_;  // [frame][root node]
  std::vector<std::vector<Vec3>> rotation_;      // [frame][root node]
  double ramp_ = 0;
};

}  // namespace finverse::fem
