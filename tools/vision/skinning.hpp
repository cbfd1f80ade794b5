// Skinning: how the template surface follows the virtual skeleton (seed paper section 2.1 step
// 1; linear blend skinning). Every template vertex is bound to the two neighbouring rays that
// bracket it in the fin plane (the one dorsal and the one ventral of it, measured across the ray
// lines extended past their tips), weighted by in-plane distance (so a point on a ray follows
// that ray alone and the membrane between two rays blends them), and along each ray to the two segments whose
// centres bracket its arc-length fraction (so the skinned ray bends smoothly through a joint).
// At zero joint angles every weight sum is one and every frame the identity: the template is
// reproduced exactly.
#pragma once

#include <array>
#include <vector>

#include "core/nd_array.hpp"
#include "mesh/fin_template.hpp"
#include "vision/skeleton.hpp"

namespace finverse::vision {

struct SkinBinding {
  static constexpr int kInfluences = 4;
  NdArray<double> rest;                                // [nv,3]
  std::vector<std::array<int, kInfluences>> joint;     // influencing joint (segment) per vertex
  std::vector<std::array<double, kInfluences>> weight; // weights, summing to one
  std::vector<std::vector<int>> depends;               // every joint whose angles move the vertex
  std::size_t size() const { return joint.size(); }
};

// `rest` [nv,3] lies in the fin plane (y = 0) of the template `t`.
SkinBinding bind_skin(const mesh::FinTemplate& t, const Skeleton& s, const NdArray<double>& rest);

// Vertex positions [nv,3] for the given joint frames.
NdArray<double> skin(const SkinBinding& b, const JointFrames& frames);

// Sparse Jacobian of every vertex position with respect to the pose parameters: for vertex v,
// the parameters in cols[v] and dX/dp (3 values each) in vals[v]. Rotations by central finite
// differences on the joint chain, the root translation exactly.
struct SkinJacobian {
  std::vector<std::vector<int>> cols;
  std::vector<std::vector<cv::Vec3d>> vals;
};
SkinJacobian skin_jacobian(const SkinBinding& b, const Skeleton& s, const Pose& pose, double step = 1e-6);

}  // namespace finverse::vision
