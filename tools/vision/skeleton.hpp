// The virtual skeleton of the fin (seed paper section 2.1 step 1: "a virtual skeleton ... the
// fin rays as chains of segments"; DESIGN.md section 5.5). Joint 0 is the root: the peduncle's
// rigid motion, a translation and a rotation about the middle of the root segment. Every ray is a
// chain of `segments` rigid segments hinged at joints with three rotational degrees of freedom,
// the first joint at the ray's root (child of joint 0), the others at equal arc-length fractions
// along the ray. Rotations are rotation vectors (axis times angle, rad) in the parent's frame.
#pragma once

#include <cstddef>
#include <vector>

#include <opencv2/core.hpp>

#include "mesh/fin_template.hpp"

namespace finverse::vision {

struct Skeleton {
  double chord = 0;
  std::size_t rays = 0, segments = 0;
  std::vector<cv::Vec3d> joint_rest;  // rest position (m) of every joint; [0] the root centre
  std::vector<int> parent;            // -1 for the root
  std::vector<int> ray;               // ray of each joint, -1 for the root
  std::vector<double> joint_s;        // arc-length fraction of each joint on its ray (0 for the root)

  std::size_t joint_count() const { return joint_rest.size(); }
  std::size_t joint(std::size_t r, std::size_t k) const { return 1 + r * segments + k; }
  // Parameters of a pose: root translation (3) then a rotation vector (3) per joint.
  std::size_t parameter_count() const { return 3 + 3 * joint_count(); }
};

Skeleton make_skeleton(const mesh::FinTemplate& t, int segments);

// A pose as the flat parameter vector: [0..2] root translation in chords (so every parameter is
// of order one), [3 + 3 j .. 5 + 3 j] the rotation vector of joint j.
struct Pose {
  std::vector<double> p;
  static Pose rest(const Skeleton& s) { return {std::vector<double>(s.parameter_count(), 0.0)}; }
};

// World transform X = R x + t of every joint's segment (x in the template's rest frame).
struct JointFrames {
  std::vector<cv::Matx33d> R;
  std::vector<cv::Vec3d> t;
};
JointFrames forward_kinematics(const Skeleton& s, const Pose& pose);

// Frame of joint j from its local rotation (rotation vector about its rest position), the root
// translation (m) and its parent's frame already in f: the step forward_kinematics takes per joint,
// also used to recompute only the descendants of a perturbed joint (skinning.cpp).
void compose_joint_frame(const Skeleton& s, std::size_t j, const cv::Vec3d& rotation_vector, const cv::Vec3d& translation,
                         JointFrames& f);

cv::Matx33d rotation_matrix(const cv::Vec3d& rotation_vector);

}  // namespace finverse::vision
