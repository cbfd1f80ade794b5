// Per-frame fit of the virtual skeleton to the segmented views (seed paper section 2.1 step 1;
// DESIGN.md section 5.5, fin-track). Levenberg-Marquardt on the pose parameters (root
// translation and every joint's rotation vector) minimising
//   sum over views of the silhouette chamfer residuals (silhouette_residual.hpp), in pixels,
//   + the distances of the projected ray axes to the detected rays (ray_features.hpp), pixels,
//   + keypoints of the ray roots and tips when given (DeepLabCut 2-D per view, Anipose 3-D;
//     keypoint_residual.hpp),
//   + in the views named in coverage_views, the pixel coverages of the model against the soft
//     segmentation (coverage_residual.hpp: places the outline to a fraction of a pixel, which the
//     pixel-centre chamfer cannot, on the few-pixel-wide edge-on strips),
//   + a temporal prior: the pose stays near the constant-velocity prediction from the previous
//     two frames (smooth motion; also the warm start),
//   + spatial priors: neighbouring rays bend alike (the membrane couples them; a weak prior on
//     first differences across the span and a stiffer one on second differences, which leaves
//     the smooth U/W-shaped spanwise trends free but stops single rays folding where no
//     silhouette sees them), and rotations about x and y (the ray points leaving their lateral
//     plane: twist, in-plane bending) stay small unless the images ask for them. Without these
//     the interior ray tips drift over a record, their silhouettes hidden by the other rays.
// The Jacobian is the chain rule of the skinning Jacobian (finite differences on the joint
// chain) and the camera projection. Views are linearised in parallel (OpenMP) and summed in a
// fixed order, so results do not depend on the thread count.
#pragma once

#include <limits>
#include <string>
#include <vector>

#include "vision/coverage_residual.hpp"
#include "vision/keypoint_residual.hpp"
#include "vision/ray_features.hpp"
#include "vision/silhouette_residual.hpp"
#include "vision/skeleton.hpp"
#include "vision/skinning.hpp"

namespace finverse::vision {

struct FitOptions {
  SilhouetteOptions silhouette;
  RayFeatureOptions rays;
  // Views by name, or by role (view_roles.hpp: {"auto"}): whose ray features are used (empty:
  // all) and which carry the sub-pixel area term (coverage_residual.hpp; empty: none).
  std::vector<std::string> ray_views;
  CoverageOptions coverage;
  std::vector<std::string> coverage_views;
  double coverage_chamfer_weight = 1.0;     // factor on the chamfer weight where the coverage term is on
  KeypointOptions keypoints;                // the ray root/tip keypoints, when a frame has them
  // The fitter's neutral values; fin-track runs tracking_fit_options() (tracker.hpp), the one
  // source of its defaults, which --help and kinematics.h5's configuration show.
  int iterations = 12;              // LM iterations per frame (warm started)
  int first_iterations = 60;        // ... for the first frame, from the rest pose
  double temporal_sigma = 0.05;     // rad (translation: chords) from the prediction
  double neighbour_sigma = 0.02;    // rad between the same joint of neighbouring rays
  double out_of_plane_sigma = 0.003; // rad, rotations about x and y of the ray joints
  double span_curvature_sigma = 0.003;  // rad, second difference across three neighbouring rays (0: off)
  double joint_sigma = 1.5;         // rad, every ray joint rotation (fixes the root/ray gauge)
  double max_step = 0.1;           // largest change of one parameter per LM step (rad, chords)
  double tolerance = 1e-3;          // stop when the cost falls by less than this fraction
  double step_tolerance = 1e-4;     // ... or when no parameter moved by more than this (rad, chords)
  int max_rejections = 0;           // ... or after this many rejected steps in a row (0: never)
};

struct FrameFit {
  Pose pose;
  NdArray<double> points;            // [nv,3] skinned template
  std::vector<double> iou, rms_px;   // per view; NaN where the view is missing
  std::vector<double> area_ratio;    // per view: fitted over segmented silhouette area; NaN where missing
  double keypoint_rms_px = std::numeric_limits<double>::quiet_NaN();  // 2-D keypoints' RMS residual, when given
  std::vector<char> valid;
  int iterations = 0;
  double cost = 0;
};

class SkeletonFitter {
 public:
  // ray_vertices: template vertices on the ray axes (the points the ray features pull on).
  SkeletonFitter(const Skeleton& skeleton, const SkinBinding& binding, const NdArray<std::int32_t>& triangles,
                 std::vector<int> ray_vertices, const FitOptions& options);

  // The template vertices at the ray roots and tips, which keypoints pull on (needed only with them).
  void set_ray_ends(RayEnds ends) { ends_ = std::move(ends); }

  // Fits one frame from `start`. `prediction` (may be null) is the temporal prior's centre;
  // `keypoints` (may be null) the frame's ray keypoints.
  FrameFit fit(const std::vector<ViewData>& views, const Pose& start, const Pose* prediction, int max_iterations,
               const FrameKeypoints* keypoints = nullptr) const;

  const Skeleton& skeleton() const { return s_; }

 private:
  struct Linearisation;
  Linearisation linearise(const std::vector<ViewData>& views, const Pose& pose, const Pose* prediction, double neighbour_sigma,
                          bool use_rays, const FrameKeypoints* keypoints) const;

  const Skeleton& s_;
  const SkinBinding& b_;
  const NdArray<std::int32_t>& tri_;
  std::vector<int> ray_vertices_;
  std::vector<MeshEdge> edges_;
  RayEnds ends_;
  FitOptions o_;
};

}  // namespace finverse::vision
