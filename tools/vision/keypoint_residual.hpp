// Keypoints of the ray roots and tips as features of the skeleton fit (issue 35 item 7): what
// DeepLabCut finds in each camera's images (2-D, px, with a likelihood) or Anipose triangulates
// (3-D, world metres). Each keypoint pulls the template vertex at its ray's root or tip: in a view,
// the vertex's projection towards the 2-D keypoint (residual in px); in the world, the vertex
// towards the 3-D keypoint (residual in units of sigma_3d, so one sigma weighs like one pixel).
// Both are Huber-weighted, since markerless trackers have occasional gross outliers.
#pragma once

#include <cstddef>
#include <map>
#include <vector>

#include <opencv2/core.hpp>

#include "core/nd_array.hpp"
#include "vision/normal_equations.hpp"
#include "vision/skinning.hpp"
#include "vision/view_data.hpp"

namespace finverse::vision {

enum class RayEnd { root, tip };

struct RayKeypoint2D {
  std::size_t ray = 0;   // 0: ray 1, the dorsal edge ray
  RayEnd end = RayEnd::root;
  std::size_t view = 0;  // index into the fit's views
  cv::Point2d uv;        // px
};

struct RayKeypoint3D {
  std::size_t ray = 0;
  RayEnd end = RayEnd::root;
  cv::Vec3d X;  // world, m
};

struct FrameKeypoints {
  std::vector<RayKeypoint2D> image;
  std::vector<RayKeypoint3D> world;
  bool empty() const { return image.empty() && world.empty(); }
};

// Keypoints of a record by frame index.
using KeypointRecord = std::map<long, FrameKeypoints>;

struct KeypointOptions {
  double weight = 1.0;              // per keypoint residual (0: the term is off)
  double huber_px = 3.0;            // 2-D residuals beyond this (px) get linear weight
  double sigma_3d_chords = 0.005;   // 3-D: the distance that weighs like one pixel (about a pixel at the fin)
};

// The template vertices at every ray's root and tip.
struct RayEnds {
  std::vector<int> root, tip;
  int vertex(std::size_t ray, RayEnd end) const {
    return end == RayEnd::root ? root.at(ray) : tip.at(ray);
  }
};

// Adds the keypoints' residual rows (J null: cost only). X: skinned vertices [nv,3]; chord (m)
// scales sigma_3d. 2-D keypoints use their view's camera whether or not its frame is present.
// Returns the RMS of the 2-D residuals (px; 0 without any).
double add_keypoint_residuals(const std::vector<ViewData>& views, const FrameKeypoints& keypoints, const RayEnds& ends,
                              const NdArray<double>& X, const SkinJacobian* J, const KeypointOptions& options, double chord,
                              NormalEquations& ne);

}  // namespace finverse::vision
