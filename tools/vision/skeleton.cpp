// Forward kinematics of the virtual skeleton: root rigid motion and ray chains with 3-DOF joints
// (seed paper section 2.1, step 1).
#include "vision/skeleton.hpp"

#include <cmath>

#include "core/error.hpp"

namespace finverse::vision {

cv::Matx33d rotation_matrix(const cv::Vec3d& w) {
  // Rodrigues' formula, with the series near zero so tiny finite-difference steps stay exact.
  const double th2 = w.dot(w);
  const cv::Matx33d K(0, -w[2], w[1], w[2], 0, -w[0], -w[1], w[0], 0);
  double a, b;
  if (th2 < 1e-12) {
    a = 1 - th2 / 6;
    b = 0.5 - th2 / 24;
  } else {
    const double th = std::sqrt(th2);
    a = std::sin(th) / th;
    b = (1 - std::cos(th)) / th2;
  }
  return cv::Matx33d::eye() + a * K + b * (K * K);
}

Skeleton make_skeleton(const mesh::FinTemplate& t, int segments) {
  mesh::validate(t);
  if (segments < 1 || segments > 16) throw Error("--segments: expected 1..16 segments per ray");
  Skeleton s;
  s.chord = t.chord;
  s.rays = t.ray_count();
  s.segments = static_cast<std::size_t>(segments);
  const auto root = t.root_segment();
  s.joint_rest.push_back({0.5 * (root[0][0] + root[1][0]), 0.0, 0.5 * (root[0][1] + root[1][1])});
  s.parent.push_back(-1);
  s.ray.push_back(-1);
  s.joint_s.push_back(0);
  for (std::size_t r = 0; r < s.rays; ++r)
    for (std::size_t k = 0; k < s.segments; ++k) {
      const double sk = static_cast<double>(k) / segments;
      const auto p = t.point_at(r, sk);
      s.joint_rest.push_back({p[0], 0.0, p[1]});
      s.parent.push_back(k == 0 ? 0 : static_cast<int>(s.joint(r, k - 1)));
      s.ray.push_back(static_cast<int>(r));
      s.joint_s.push_back(sk);
    }
  return s;
}

JointFrames forward_kinematics(const Skeleton& s, const Pose& pose) {
  const std::size_t nj = s.joint_count();
  if (pose.p.size() != s.parameter_count()) throw Error("skeleton: pose has the wrong number of parameters");
  JointFrames f;
  f.R.resize(nj);
  f.t.resize(nj);
  const cv::Vec3d translation(pose.p[0] * s.chord, pose.p[1] * s.chord, pose.p[2] * s.chord);
  // Joints are stored parents first, so one pass suffices.
  for (std::size_t j = 0; j < nj; ++j)
    compose_joint_frame(s, j, {pose.p[3 + 3 * j], pose.p[4 + 3 * j], pose.p[5 + 3 * j]}, translation, f);
  return f;
}

// Local motion of joint j: rotate about its rest position, X = R_j (x - J_j) + J_j, composed with
// the parent's frame.
void compose_joint_frame(const Skeleton& s, std::size_t j, const cv::Vec3d& rotation_vector, const cv::Vec3d& translation,
                         JointFrames& f) {
  const cv::Matx33d Rl = rotation_matrix(rotation_vector);
  const cv::Vec3d tl = s.joint_rest[j] - Rl * s.joint_rest[j];
  if (s.parent[j] < 0) {
    f.R[j] = Rl;
    f.t[j] = tl + translation;
  } else {
    const auto q = static_cast<std::size_t>(s.parent[j]);
    f.R[j] = f.R[q] * Rl;
    f.t[j] = f.R[q] * tl + f.t[q];
  }
}

}  // namespace finverse::vision
