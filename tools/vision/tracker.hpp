// The tracker behind fin-track (DESIGN.md sections 1 and 5.5; seed paper section 2.1 step 1): the
// fin's 3-D motion over a record of synchronized multi-view frames. Per frame every view is
// loaded and segmented (view_data.hpp) and the virtual skeleton is fitted to all of them at once
// (skeleton_fit.hpp): the first frame cold from the rest pose, every later one warm-started from a
// prediction of the previous frames' motion, which also centres the temporal prior. A view
// without the frame is left out of that frame's fit. The result is the record as kinematics.h5
// holds it and, given the truth (validation), the per-view silhouette scores that are graded.
#pragma once

#include <cstddef>
#include <functional>
#include <map>
#include <memory>
#include <opencv2/core.hpp>
#include <optional>
#include <string>
#include <vector>

#include "core/nd_array.hpp"
#include "core/stage_files.hpp"
#include "mesh/fin_template.hpp"
#include "vision/camera.hpp"
#include "vision/fin_surface.hpp"
#include "vision/fit_quality.hpp"
#include "vision/keypoint_residual.hpp"
#include "vision/segmentation.hpp"
#include "vision/skeleton.hpp"
#include "vision/skeleton_fit.hpp"
#include "vision/skinning.hpp"

namespace finverse::vision {

// fin-track's fit: FitOptions with the values measured on the validation record
// (docs/studies/tracking_fit_defaults.md): ray features in the face-on views only, the coverage
// term in the edge-on views (roles from the cameras: view_roles.hpp), 18 LM iterations per
// frame, stop after two rejected steps. The one source of fin-track's defaults.
FitOptions tracking_fit_options();

struct TrackerOptions {
  FitOptions fit = tracking_fit_options();
  SegmentationOptions segmentation;
  int surface_subdivisions = 4;      // template surface columns per gap between rays (even)
  int segments = 7;                  // skeleton segments per ray
  double prediction_velocity = 0.5;  // fraction of the last frame-to-frame change in the prediction
  double fps = 500;                  // time of frame k: k / fps
  std::optional<double> period;      // the motion's period (kinematics.h5 T) when the record is periodic
  std::map<std::string, cv::Rect> fin_regions;  // per view name: the rectangle that holds the fin
  bool cut_at_root_plane = false;               // body cut off at the projected root plane x = 0
  FitQualityOptions quality;                    // when the fit cannot be trusted (fit_quality.hpp)
};

// The model that is fitted: the template surface, its skeleton and skin, and the ray axes (the
// surface vertices on ray r, root to tip: ray_vertices[ray_offsets[r] .. ray_offsets[r + 1]]).
struct TrackingModel {
  double chord = 0;
  FinSurface surface;
  Skeleton skeleton;
  SkinBinding binding;
  NdArray<std::int32_t> ray_offsets, ray_vertices;
  RayEnds ray_ends() const;  // the first and last vertex of every ray's axis
};
TrackingModel make_tracking_model(const mesh::FinTemplate& fin, int surface_subdivisions, int segments);

// The grey (CV_8U) frame `frame` of view `view` (an index into the cameras), or an empty Mat where
// that view has no such frame. Called from several threads at once; may throw.
using FrameLoader = std::function<cv::Mat(std::size_t view, long frame)>;

struct TrackInput {
  std::vector<Camera> cameras;  // the calibration the fit projects with
  std::vector<long> frames;     // frame indices, ascending (gaps allowed)
  FrameLoader load;
  std::string source = "frames";  // names the record in messages
  const KeypointRecord* keypoints = nullptr;  // ray root/tip keypoints by frame index (may be null)
};

// Validation: the true surface of every frame index and the calibration as given (the fit's may
// be perturbed), the scores projecting both surfaces through the latter.
struct TruthReference {
  const NdArray<double>* points = nullptr;  // [> last frame, nv, 3], row k = frame index k
  std::vector<Camera> cameras;
  std::string name = "truth";  // names the truth in messages
};

struct TrackResult {
  std::vector<long> frames;
  stage::Kinematics kinematics;  // everything but provenance
  double seconds = 0;            // load, segment and fit, every frame (scoring excluded)
  double first_seconds = 0;      // ... the first frame's (cold start)
  double seconds_per_frame = 0;  // steady state: the mean after the first frame
  double worst_iou = 1;          // fit against the segmentation, every valid view and frame
  double keypoint_rms_px = 0;    // 2-D keypoints: RMS of the fitted ray ends against them, all frames
  std::size_t keypoint_frames = 0;  // frames with 2-D keypoints
  FitVerdict verdict;            // per-frame flags (also in kinematics) and the run's failure, if any
  // With a truth, per view the worst over the frames of
  std::vector<double> fit_truth_iou;        // the fitted against the true surface, area-coverage
                                            // silhouettes (silhouette_coverage.hpp; graded)
  std::vector<double> fit_truth_pixel_iou;  // the same, pixel-centre silhouettes
  std::vector<double> truth_iou;            // the true surface against the segmentation
};

// The warm start and temporal-prior centre of the next frame: the last pose plus `velocity` times
// the last frame-to-frame change, scaled by gap_ratio (the next frame gap over the last one); the
// last pose itself when `before` (the pose before it) is null. Less than the full velocity, so a
// direction the images barely constrain cannot keep drifting on its own momentum.
Pose predict_pose(const Pose& last, const Pose* before, double gap_ratio, double velocity);

class Tracker {
 public:
  Tracker(const mesh::FinTemplate& fin, const TrackerOptions& options);
  Tracker(const Tracker&) = delete;  // the fitter refers to the model
  Tracker& operator=(const Tracker&) = delete;
  ~Tracker();

  const TrackingModel& model() const { return model_; }
  const TrackerOptions& options() const { return options_; }

  // Tracks every frame of `input`. Throws finverse::Error when a frame cannot be loaded or
  // segmented, when no view shows the fin in some frame, or when the truth does not cover the
  // frames on this template.
  TrackResult track(const TrackInput& input, const TruthReference* truth = nullptr) const;

 private:
  TrackerOptions options_;
  TrackingModel model_;
  std::unique_ptr<SkeletonFitter> fitter_;
};

}  // namespace finverse::vision
